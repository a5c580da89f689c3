// penink preview: steers the view and shows each frame the server draws (an SVG). The view is
// the scene file's own keys (target, distance, azimuth, altitude, sun, ...); the server draws
// whatever view it gets last. While the mouse drags, frames are asked at DRAG_SCALE of the size.
"use strict";
const token = new URLSearchParams(location.search).get("token") || "";
const DRAG_SCALE = 0.4;
const state = {
  view: null, save: "", frames: 0, fullFrames: 0, lastSvg: "", lastFullSvg: "", busy: false,
  pending: null, lastMs: 0, point: null, fullView: null,
};
window.penink = state;  // read by tests (tests/preview/browser_test.py)

const $ = (id) => document.getElementById(id);
const img = $("drawing"), stage = $("stage"), status = $("status");
const url = (path, extra) => path + "?token=" + encodeURIComponent(token) + (extra || "");

function setStatus(text, error) {
  status.textContent = text;
  status.classList.toggle("error", !!error);
}

async function post(path, body, extra) {
  const r = await fetch(url(path, extra), {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  });
  return r;
}

// Fits the image's box to the stage at the view's aspect (a small frame is shown at full size).
function fitImage() {
  if (!state.view) return;
  const w = stage.clientWidth - 32, h = stage.clientHeight - 32;
  const k = Math.min(w / state.view.width, h / state.view.height, 1.5);
  img.style.width = Math.round(state.view.width * k) + "px";
  img.style.height = Math.round(state.view.height * k) + "px";
}

// Asks for a frame; a request made while one is on its way waits and the newest one goes next.
function draw(scale) {
  state.pending = { view: JSON.parse(JSON.stringify(state.view)), scale: scale };
  if (!state.busy) next();
}

async function next() {
  const job = state.pending;
  state.pending = null;
  if (!job) { state.busy = false; return; }
  state.busy = true;
  setStatus(job.scale < 1 ? "drawing (small)…" : "drawing…");
  const t0 = performance.now();
  try {
    const r = await post("/frame", job.view, "&scale=" + job.scale);
    if (r.status === 200) {
      const svg = await r.text();
      state.lastMs = performance.now() - t0;
      state.frames += 1;
      state.lastSvg = svg;
      if (job.scale >= 1) {
        state.lastFullSvg = svg;
        state.fullFrames += 1;
        state.fullView = job.view;
      }
      const old = img.src;
      img.src = URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" }));
      if (old.startsWith("blob:")) setTimeout(() => URL.revokeObjectURL(old), 1000);
      fitImage();
      setStatus((job.scale < 1 ? "small frame " : "drawn in ") + Math.round(state.lastMs) + " ms");
    } else if (r.status !== 409) {
      const e = await r.json().catch(() => ({ error: r.statusText }));
      setStatus(e.error || ("error " + r.status), true);
    }
  } catch (e) {
    setStatus("the server is gone (" + e.message + ")", true);
  }
  if (!state.pending) {
    state.busy = false;
    if (job.scale >= 1) setStatus(status.textContent.startsWith("drawn") ? status.textContent + " · ready" : status.textContent, status.classList.contains("error"));
  } else {
    next();
  }
}

// ---- controls bound to view keys
const sliders = ["light_azimuth", "light_altitude", "vertical_exaggeration", "crease_min_score", "ridge_min_score",
  "hachure_spacing_min", "hachure_spacing_max", "fov"];
function showValue(key) {
  const v = state.view[key];
  $(key + "_out").textContent = Math.abs(v) >= 10 ? v.toFixed(0) : v.toFixed(2).replace(/\.?0+$/, "");
}
function bindControls() {
  for (const key of sliders) {
    const input = $(key);
    input.value = state.view[key];
    showValue(key);
    input.addEventListener("input", () => { state.view[key] = parseFloat(input.value); showValue(key); draw(DRAG_SCALE); });
    input.addEventListener("change", () => draw(1));
  }
  const style = $("style");
  if (![...style.options].some((o) => o.value === state.view.style)) style.add(new Option(state.view.style, state.view.style));
  style.value = state.view.style;
  style.addEventListener("change", () => { state.view.style = style.value; draw(1); });
  const box = $("layers");
  for (const name of ["silhouettes", "creases", "ridges", "hachures", "coastline", "surface"]) {
    const label = document.createElement("label");
    const check = document.createElement("input");
    check.type = "checkbox";
    check.checked = state.view.layers[name] !== false;
    check.dataset.layer = name;
    check.addEventListener("change", () => { state.view.layers[name] = check.checked; draw(1); });
    label.append(check, " " + name);
    box.append(label);
  }
}

// ---- mouse: orbit, pan, wheel, click
let drag = null;
const deg = Math.PI / 180;
function metresPerPixel() {
  const v = state.view;
  return v.distance * 2 * Math.tan(v.fov * deg / 2) / Math.max(img.clientWidth, 1);
}
stage.addEventListener("contextmenu", (e) => e.preventDefault());
stage.addEventListener("pointerdown", (e) => {
  if (!state.view) return;
  stage.setPointerCapture(e.pointerId);
  drag = { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY, pan: e.shiftKey || e.button === 2, moved: false };
  stage.classList.add("dragging");
});
stage.addEventListener("pointermove", (e) => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX, drag.y = e.clientY;
  if (!drag.moved && Math.hypot(e.clientX - drag.x0, e.clientY - drag.y0) < 3) return;
  drag.moved = true;
  const v = state.view;
  if (drag.pan) {
    const m = metresPerPixel(), a = v.azimuth * deg;
    const stretch = 1 / Math.max(Math.sin(Math.abs(v.altitude) * deg), 0.2);  // ground seen at a slant
    v.target_x += -dx * m * Math.cos(a) + dy * m * stretch * Math.sin(a);
    v.target_y += dx * m * Math.sin(a) + dy * m * stretch * Math.cos(a);
  } else {
    v.azimuth = ((v.azimuth + dx * 0.3) % 360 + 360) % 360;
    v.altitude = Math.max(-89.5, Math.min(20, v.altitude - dy * 0.2));
  }
  draw(DRAG_SCALE);
});
function release(e) {
  if (!drag) return;
  const click = !drag.moved;
  drag = null;
  stage.classList.remove("dragging");
  const r = img.getBoundingClientRect();
  const onImage = e.clientX >= r.left && e.clientX < r.right && e.clientY >= r.top && e.clientY < r.bottom;
  if (click && onImage) locate(e);
  else if (!click) draw(1);
}
stage.addEventListener("pointerup", release);
stage.addEventListener("pointercancel", release);
let wheelTimer = 0;
stage.addEventListener("wheel", (e) => {
  if (!state.view) return;
  e.preventDefault();
  state.view.distance = Math.min(1e8, Math.max(1, state.view.distance * Math.exp(e.deltaY * 0.0015)));
  draw(DRAG_SCALE);
  clearTimeout(wheelTimer);
  wheelTimer = setTimeout(() => draw(1), 250);
}, { passive: false });
window.addEventListener("resize", fitImage);

async function locate(e) {
  if (!state.fullView) return;
  const r = img.getBoundingClientRect();
  const x = (e.clientX - r.left) / r.width * state.fullView.width, y = (e.clientY - r.top) / r.height * state.fullView.height;
  const resp = await post("/locate", { x: x, y: y });
  const p = await resp.json();
  state.point = p.hit ? p : null;
  $("look").disabled = !p.hit;
  if (!p.hit) { $("point").textContent = "Not on the terrain."; return; }
  const lines = ["x " + p.x.toFixed(1) + "   y " + p.y.toFixed(1), "elevation " + p.elevation.toFixed(1) + " m"];
  if (p.lon !== undefined) lines.push("lon " + p.lon.toFixed(6) + "  lat " + p.lat.toFixed(6));
  $("point").textContent = lines.join("\n");
}
$("look").addEventListener("click", () => {
  if (!state.point) return;
  state.view.target_x = state.point.x;
  state.view.target_y = state.point.y;
  draw(1);
});

// ---- save and export
$("save").addEventListener("click", async () => {
  const r = await post("/save", state.view);
  const j = await r.json();
  $("file").textContent = r.ok ? "Saved " + j.saved : j.error;
  state.saved = r.ok ? j.saved : "";
});
$("export").addEventListener("click", async () => {
  const formats = [...document.querySelectorAll("input[name=format]:checked")].map((c) => c.value);
  $("file").textContent = "exporting…";
  const r = await post("/export", { view: state.view, formats: formats });
  const j = await r.json();
  $("file").textContent = r.ok ? "Wrote " + j.exported.join(", ") : j.error;
});

(async function start() {
  const r = await fetch(url("/view"));
  const j = await r.json();
  state.view = j.view;
  state.save = j.save;
  $("file").textContent = "Save writes " + j.save;
  bindControls();
  fitImage();
  draw(1);
})();
