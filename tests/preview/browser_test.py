#!/usr/bin/env python3
"""`penink preview` in a real browser: Debian's chromium, headless, driven by chromedriver
through Selenium. Checks that requests without the token, or naming another Host, are refused
(403); that a frame goes uncompressed to a client that accepts brotli; that a drag changes the
camera and draws smaller frames while it lasts; that a click on the terrain gives its
coordinates; and that Save writes a scene whose `penink render` is the page's SVG byte for byte. Prints the redraw times it measured (no limit is asserted: speed
goals belong to bench/). Exit 77 (CTest: skipped) with the reason when chromium, chromedriver
or Selenium is missing or chromium cannot start.

Usage: browser_test.py PENINK SOURCE_DIR [SCENE_OR_DEM] [SCREENSHOT.png]
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

SKIP = 77


def skip(reason):
    print("SKIP: " + reason)
    sys.exit(SKIP)


def status_of(url, host=None):
    req = urllib.request.Request(url)
    if host:
        req.add_header("Host", host)
    try:
        with urllib.request.urlopen(req, timeout=20) as r:
            return r.status
    except urllib.error.HTTPError as e:
        return e.code


def wait_for(driver, script, timeout=60.0, what="the page"):
    end = time.time() + timeout
    while time.time() < end:
        if driver.execute_script(script):
            return
        time.sleep(0.02)
    raise AssertionError("timed out waiting for " + what + ": " + script)


IDLE = "return window.penink && penink.view && !penink.busy && penink.fullFrames > 0"


def main():
    penink, source = sys.argv[1], sys.argv[2]
    scene = sys.argv[3] if len(sys.argv) > 3 and sys.argv[3] else os.path.join(source, "examples", "volcano.toml")
    screenshot = sys.argv[4] if len(sys.argv) > 4 else ""
    chromium = shutil.which("chromium")
    driver_path = shutil.which("chromedriver")
    if not chromium or not driver_path:
        skip("chromium and chromedriver are not installed (Debian: chromium chromium-driver)")
    try:
        from selenium import webdriver
        from selenium.webdriver.common.action_chains import ActionChains
        from selenium.webdriver.common.by import By
        from selenium.webdriver.common.keys import Keys
    except ImportError:
        skip("Selenium is not installed (Debian: python3-selenium)")

    work = tempfile.mkdtemp(prefix="penink_browser_")
    save = os.path.join(work, "steered.toml")
    proc = subprocess.Popen([penink, "preview", scene, "--save", save], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, cwd=work)
    driver = None
    try:
        line = proc.stdout.readline()
        m = re.search(r"(http://127\.0\.0\.1:(\d+)/)\?token=([0-9a-f]{32})", line)
        assert m, "no URL printed: %r %s" % (line, proc.stderr.read() if proc.poll() is not None else "")
        base, port, token = m.group(1), m.group(2), m.group(3)
        url = base + "?token=" + token

        # refused: no token, a wrong one, another Host; nothing served but the page's own paths
        assert status_of(base) == 403
        assert status_of(base + "?token=" + "0" * 32) == 403
        assert status_of(base + "preview.js") == 403
        assert status_of(url, host="evil.example:" + port) == 403
        assert status_of(url, host="127.0.0.1:1") == 403
        assert status_of(url) == 200
        assert status_of(base + "preview.js?token=" + token) == 200
        assert status_of(base + "etc/passwd?token=" + token) == 404
        assert status_of(base + "../CMakeLists.txt?token=" + token) in (400, 404)

        # a frame goes uncompressed to a client that accepts brotli, as browsers do (the
        # server's brotli took seconds a frame)
        with urllib.request.urlopen(base + "view?token=" + token, timeout=20) as r:
            start_view = json.load(r)["view"]
        req = urllib.request.Request(base + "frame?token=" + token + "&scale=0.1", data=json.dumps(start_view).encode(),
                                     headers={"Accept-Encoding": "gzip, deflate, br"})
        with urllib.request.urlopen(req, timeout=120) as r:
            assert r.headers.get("Content-Encoding") is None, r.headers.get("Content-Encoding")
            assert r.read().startswith(b"<?xml")

        opts = webdriver.ChromeOptions()
        opts.binary_location = chromium
        for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                  "--window-size=1500,900", "--user-data-dir=" + os.path.join(work, "profile")):
            opts.add_argument(a)
        try:
            from selenium.webdriver.chrome.service import Service
            driver = webdriver.Chrome(service=Service(executable_path=driver_path), options=opts)
        except Exception as e:  # noqa: BLE001 (any failure to start the browser is a skip)
            skip("chromium does not start: " + str(e).splitlines()[0])
        driver.set_script_timeout(60)

        # a second client without the token gets nothing
        driver.get(base)
        assert "forbidden" in driver.page_source, driver.page_source[:200]

        driver.get(url)
        wait_for(driver, IDLE, 120, "the first frame")
        view0 = driver.execute_script("return JSON.parse(JSON.stringify(penink.view))")
        assert driver.execute_script("return penink.lastFullSvg.startsWith('<?xml')")

        # drag: orbit. Small frames while it moves, then one full frame.
        stage = driver.find_element(By.ID, "drawing")
        frames0 = driver.execute_script("return penink.frames")
        full0 = driver.execute_script("return penink.fullFrames")
        chain = ActionChains(driver, duration=50)
        chain.move_to_element(stage).click_and_hold()
        for _ in range(12):
            chain.move_by_offset(12, 3)
            chain.pause(0.12)
        chain.perform()
        time.sleep(0.3)
        t_release = time.time()
        ActionChains(driver).release().perform()
        wait_for(driver, "return penink.fullFrames > %d && !penink.busy" % full0, 60, "the frame after the drag")
        after_release = time.time() - t_release
        view1 = driver.execute_script("return penink.view")
        small = driver.execute_script("return penink.frames") - frames0 - 1
        drag_ms = driver.execute_script("return penink.lastMs")
        assert abs(view1["azimuth"] - view0["azimuth"]) > 10, (view0["azimuth"], view1["azimuth"])
        assert view1["altitude"] != view0["altitude"]
        assert small >= 1, "no smaller frame was drawn while dragging"

        # a smaller frame's round trip, measured alone
        small_ms = driver.execute_async_script("""
            const done = arguments[0];
            const t0 = performance.now();
            fetch('/frame?token=%s&scale=0.4', {method: 'POST', body: JSON.stringify(penink.view)})
              .then(r => r.text()).then(() => done(performance.now() - t0));""" % token)

        # shift-drag pans: the target moves, the angles stay
        full1 = driver.execute_script("return penink.fullFrames")
        ActionChains(driver, duration=50).key_down(Keys.SHIFT).move_to_element(stage).click_and_hold() \
            .move_by_offset(60, 0).pause(0.1).move_by_offset(60, 20).release().key_up(Keys.SHIFT).perform()
        wait_for(driver, "return penink.fullFrames > %d && !penink.busy" % full1, 60, "the frame after the pan")
        view2 = driver.execute_script("return penink.view")
        assert (view2["target_x"], view2["target_y"]) != (view1["target_x"], view1["target_y"])
        assert view2["azimuth"] == view1["azimuth"]

        # a click on the middle of the drawing: the ground there, in the map CRS and lon/lat
        ActionChains(driver).move_to_element(stage).click().perform()
        wait_for(driver, "return document.getElementById('point').textContent.includes('elevation')", 30,
                 "the clicked point")
        point = driver.find_element(By.ID, "point").text
        assert "lon " in point and "lat " in point, point

        # Save: its render is the page's SVG, byte for byte
        driver.find_element(By.ID, "save").click()
        wait_for(driver, "return penink.saved", 30, "the save")
        svg = driver.execute_script("return penink.lastFullSvg")
        assert driver.execute_script("return JSON.stringify(penink.fullView) === JSON.stringify(penink.view)")
        assert os.path.exists(save)
        out = os.path.join(work, "rendered.svg")
        subprocess.run([penink, "render", save, "-o", out, "-q"], check=True, cwd=work)
        with open(out, encoding="utf-8") as f:
            rendered = f.read()
        assert rendered == svg, "the saved scene renders differently (%d vs %d bytes)" % (len(rendered), len(svg))

        if screenshot:
            driver.save_screenshot(screenshot)
        print("preview: first frame drawn; drag: %d smaller frames, last %.0f ms; full frame %.2f s after "
              "letting go; a smaller frame alone %.0f ms; saved scene renders the page's SVG (%d bytes)"
              % (small, drag_ms, after_release, small_ms, len(svg)))
    finally:
        if driver:
            driver.quit()
        if proc.poll() is None:
            proc.send_signal(signal.SIGTERM)
            try:
                code = proc.wait(20)
            except subprocess.TimeoutExpired:
                proc.kill()
                raise AssertionError("penink preview did not stop on SIGTERM")
            assert code == 0, "penink preview ended with %d: %s" % (code, proc.stderr.read())
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
