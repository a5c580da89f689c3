#!/usr/bin/env python3
"""Writes an ESRI ASCII grid (+ .prj, UTM 33N) of six Gaussian hills (90-420 m high, sigma
90-700 m, within 1.3 km of the centre, on a 50 m plain) sampled every SPACING metres over a
square of SIDE nodes: the analytic hills of docs/timings.md.
Usage: bench/analytic_hills.py OUT.asc [SPACING=10] [SIDE=601]"""
import math
import sys

HILLS = [(-900, -700, 420, 520), (800, 600, 360, 380), (300, -1100, 250, 260),
         (-1200, 900, 300, 700), (1300, -900, 180, 160), (0, 200, 120, 90)]
PRJ = ('PROJCS["WGS 84 / UTM zone 33N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,'
       '298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION['
       '"Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",15],'
       'PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],'
       'UNIT["metre",1]]')


def main():
    out = sys.argv[1]
    spacing = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 601
    half = (n - 1) * spacing / 2
    with open(out, "w") as f:
        f.write(f"ncols {n}\nnrows {n}\nxllcorner {500000 - half - spacing / 2}\n"
                f"yllcorner {4000000 - half - spacing / 2}\ncellsize {spacing}\nNODATA_value -9999\n")
        for r in range(n):
            y = half - r * spacing
            row = []
            for c in range(n):
                x = -half + c * spacing
                z = 50.0 + sum(h * math.exp(-((x - hx) ** 2 + (y - hy) ** 2) / (2 * s * s)) for hx, hy, h, s in HILLS)
                row.append(f"{z:.3f}")
            f.write(" ".join(row) + "\n")
    with open(out.rsplit(".", 1)[0] + ".prj", "w") as f:
        f.write(PRJ + "\n")


if __name__ == "__main__":
    main()
