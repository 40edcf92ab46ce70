#!/usr/bin/env python3
"""Generates runout_valley.asc: a small synthetic DEM for the run-out example
(share/scenes/runout_valley.json). A 30-degree hillside descends towards +x,
eases into a 4-degree valley floor, and a shallow gully on the hillside guides
the flow; gentle undulations make the normals vary. 5 m cells, 120 x 80."""
import math
import os

NCOLS, NROWS, CELL = 120, 80, 5.0
X0, Y0 = 0.0, 0.0  # lower-left corner


def elevation(x, y):
    steep, floor = math.tan(math.radians(30.0)), math.tan(math.radians(4.0))
    foot, blend = 260.0, 80.0  # slope eases from steep to floor over [foot - blend/2, foot + blend/2]
    a, b = foot - blend / 2, foot + blend / 2
    # slope(x) = steep before a, linear blend on [a, b], floor after b; Z(600) = 0
    def integral(x1, x2):  # integral of slope from x1 to x2 (x1 < x2)
        def prim(t):
            if t <= a:
                return steep * t
            if t <= b:
                s = (t - a) / (b - a)
                return steep * a + (t - a) * (steep + (floor - steep) * s / 2)
            return steep * a + (b - a) * (steep + floor) / 2 + floor * (t - b)
        return prim(x2) - prim(x1)
    z = integral(x, 600.0)
    gully = -6.0 * math.exp(-((y - 200.0) / 45.0) ** 2) * (1.0 if x < b else math.exp(-(x - b) / 60.0))
    banks = 0.0006 * (y - 200.0) ** 2
    bumps = 1.2 * math.sin(x / 37.0) * math.cos(y / 29.0)
    return z + gully + banks + bumps


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "runout_valley.asc")
    with open(out + ".tmp", "w") as f:
        f.write(f"ncols {NCOLS}\nnrows {NROWS}\nxllcorner {X0}\nyllcorner {Y0}\ncellsize {CELL}\nNODATA_value -9999\n")
        for r in range(NROWS - 1, -1, -1):  # north row first
            y = Y0 + (r + 0.5) * CELL
            f.write(" ".join(f"{elevation(X0 + (c + 0.5) * CELL, y):.2f}" for c in range(NCOLS)) + "\n")
    os.replace(out + ".tmp", out)
    print("wrote", out)


if __name__ == "__main__":
    main()
