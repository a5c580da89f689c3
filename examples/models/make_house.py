#!/usr/bin/env python3
"""Writes house.obj: a gabled brick house (y up, metres) with usemtl groups for the penink
feature-line and indication-texture demo: brick_walls, roof, ground, stone_chimney, door, window.
Faces are counter-clockwise seen from outside; walls are split on a grid so doors and windows
are separate faces (material boundaries) without T-junctions."""
import sys

V, F = [], []  # vertices, (material, [indices])
index = {}

def v(p):
    key = tuple(round(c, 6) for c in p)
    if key not in index:
        index[key] = len(V) + 1
        V.append(key)
    return index[key]

def face(mat, pts):
    F.append((mat, [v(p) for p in pts]))

def wall(origin, u, w, us, ws, holes):
    """Quad grid on the plane origin + a*u + b*w (u right, w up seen from outside)."""
    for i in range(len(us) - 1):
        for j in range(len(ws) - 1):
            a0, a1, b0, b1 = us[i], us[i + 1], ws[j], ws[j + 1]
            cx, cy = (a0 + a1) / 2, (b0 + b1) / 2
            mat = "brick_walls"
            for (x0, x1, y0, y1, m) in holes:
                if x0 < cx < x1 and y0 < cy < y1:
                    mat = m
            P = lambda a, b: tuple(origin[k] + a * u[k] + b * w[k] for k in range(3))
            face(mat, [P(a0, b0), P(a1, b0), P(a1, b1), P(a0, b1)])

L, D, H, RIDGE, OVER = 8.0, 6.0, 4.0, 6.5, 0.4
front_holes = [(1, 2.4, 1.2, 2.8, "window"), (5.6, 7, 1.2, 2.8, "window"), (3.4, 4.6, 0, 2.2, "door")]
xs = [0, 1, 2.4, 3.4, 4.6, 5.6, 7, 8]
ys = [0, 1.2, 2.2, 2.8, 4]
wall((0, 0, D), (1, 0, 0), (0, 1, 0), xs, ys, front_holes)                 # front, +z
wall((L, 0, 0), (-1, 0, 0), (0, 1, 0), xs, ys, [(3, 5, 1.2, 2.8, "window")])  # back, -z
zs = [0, 2, 4, 6]
wall((0, 0, 0), (0, 0, 1), (0, 1, 0), zs, ys, [(2, 4, 1.2, 2.8, "window")])   # left, -x
wall((L, 0, D), (0, 0, -1), (0, 1, 0), zs, ys, [(2, 4, 1.2, 2.8, "window")])  # right, +x
# Gables: fans from the apex over the wall's top vertices (no T-junctions).
for x, order in ((0.0, zs), (L, zs[::-1])):
    apex = (x, RIDGE, D / 2)
    for a, b in zip(order, order[1:]):
        face("brick_walls", [(x, H, a), (x, H, b), apex])
# Roof slopes with overhang; the ridge is a crease.
slope = (RIDGE - H) / (D / 2)
ye = H - OVER * slope
face("roof", [(-OVER, ye, D + OVER), (L + OVER, ye, D + OVER), (L + OVER, RIDGE, D / 2), (-OVER, RIDGE, D / 2)])
face("roof", [(L + OVER, ye, -OVER), (-OVER, ye, -OVER), (-OVER, RIDGE, D / 2), (L + OVER, RIDGE, D / 2)])
# Chimney (stone), a box through the back slope.
x0, x1, z0, z1, y0, y1 = 5.5, 6.3, 1.0, 1.8, 5.0, 7.6
face("stone_chimney", [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)])
face("stone_chimney", [(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)])
face("stone_chimney", [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)])
face("stone_chimney", [(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)])
face("stone_chimney", [(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)])
# Ground, a 20 m x 18 m lawn.
face("ground", [(-6, 0, 12), (14, 0, 12), (14, 0, -6), (-6, 0, -6)])

out = open(sys.argv[1] if len(sys.argv) > 1 else "house.obj", "w")
out.write("# penink demo house: gabled brick house on a lawn, y up, metres (examples/models/make_house.py)\n")
for p in V:
    out.write("v %g %g %g\n" % p)
for mat in ["brick_walls", "window", "door", "roof", "stone_chimney", "ground"]:
    out.write("g %s\nusemtl %s\n" % (mat, mat))
    for m, idx in F:
        if m == mat:
            out.write("f " + " ".join(str(i) for i in idx) + "\n")
