#!/usr/bin/env python3
"""Crease stroke shapes in a penink SVG (the centre lines of its creases layer, image pixels), for
what an illustrator notes: short strokes, star-like clusters of short strokes, tributaries
bending sharply into their junctions.
  short: crease paths under 6 px long;
  star clusters: points where >= 3 crease path ends lie within 6 px of one end, at least 3 of
    them ends of paths under 15 px (each cluster counted once);
  end bends: for each path end within 6 px of another crease path (a tributary near its trunk:
    the even spacing stops it a few px short), the largest turn between consecutive segments over
    its last 10 px; the share of those ends turning more than 30 degrees.
Usage: bench/crease_shapes.py DRAWING.svg   (e.g. after penink render examples/jacksboro.tif --map -o j.svg)
Independent of penink's code: it reads only the SVG."""
import math, re, sys
svg = open(sys.argv[1]).read()
m = re.search(r'<g[^>]*id="creases"[^>]*>(.*?)</g>', svg, re.S)
paths = []
for p in re.finditer(r'<path ([^>]*)/>', m.group(1) if m else ''):
    a = p.group(1)
    o = re.search(r'inkscape:original-d="([^"]*)"', a) or re.search(r' d="([^"]*)"', a)
    nums = [float(x) for x in re.findall(r'-?[0-9.]+(?:e-?[0-9]+)?', o.group(1))]
    pts = list(zip(nums[0::2], nums[1::2]))
    if len(pts) >= 2: paths.append(pts)
def length(p): return sum(math.dist(p[i], p[i+1]) for i in range(len(p)-1))
lens = [length(p) for p in paths]
short = sum(1 for l in lens if l < 6)
ends = [(p[0], l) for p, l in zip(paths, lens)] + [(p[-1], l) for p, l in zip(paths, lens)]
grid = {}
for i, (e, l) in enumerate(ends): grid.setdefault((int(e[0]//6), int(e[1]//6)), []).append(i)
star = 0; seen = set()
for i, (e, l) in enumerate(ends):
    if i in seen: continue
    near = [j for dx in (-1,0,1) for dy in (-1,0,1) for j in grid.get((int(e[0]//6)+dx, int(e[1]//6)+dy), []) if math.dist(ends[j][0], e) <= 6]
    if len(near) >= 3 and sum(1 for j in near if ends[j][1] < 15) >= 3:
        star += 1; seen.update(near)
# end bends at junctions
pg = {}
for k, p in enumerate(paths):
    for q in p: pg.setdefault((int(q[0]), int(q[1])), set()).add(k)
def touches(k, e):
    for dx in range(-6,7):
        for dy in range(-6,7):
            for j in pg.get((int(e[0])+dx, int(e[1])+dy), ()):
                if j != k and any(math.dist(e, q) <= 6.0 for q in paths[j]): return True
    return False
def turn(a, b, c):
    u = (b[0]-a[0], b[1]-a[1]); v = (c[0]-b[0], c[1]-b[1])
    nu, nv = math.hypot(*u), math.hypot(*v)
    if nu < 1e-9 or nv < 1e-9: return 0.0
    return math.degrees(math.acos(max(-1, min(1, (u[0]*v[0]+u[1]*v[1])/(nu*nv)))))
joined = sharp = 0
for k, p in enumerate(paths):
    for seq in (p, p[::-1]):
        if not touches(k, seq[-1]): continue
        joined += 1
        # vertices within the last 6 px
        acc = 0.0; i = len(seq) - 1
        while i > 0 and acc < 10.0: acc += math.dist(seq[i], seq[i-1]); i -= 1
        worst = max([turn(seq[j-1], seq[j], seq[j+1]) for j in range(max(1, i), len(seq)-1)] or [0.0])
        sharp += worst > 30
print(f"{len(paths)} crease paths, {sum(lens):.0f} px; {short} under 6 px; {star} star clusters; "
      f"{joined} ends on another crease, {100.0*sharp/max(joined,1):.1f} % turning > 30 deg in their last 10 px")
