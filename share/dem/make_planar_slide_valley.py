"""Writes planar_slide_valley.asc: the planar slide's 30 degree slope (z = -x tan 30, the slip plane of
share/scenes/planar_slide.json) down to the foot of its base block at x = 25 cos 30, then a level floor; 0.5 m
cells over x in [-10, 80], y in [-10, 14]. The terrain the failed slab runs out over in planar_slide_chain.json."""
import math
import os

CELL = 0.5
X0, X1, Y0, Y1 = -10.0, 80.0, -10.0, 14.0
SLOPE = math.tan(math.radians(30.0))
FOOT = 25.0 * math.cos(math.radians(30.0))


def main():
    ncols, nrows = int((X1 - X0) / CELL), int((Y1 - Y0) / CELL)
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "planar_slide_valley.asc")
    with open(path, "w") as f:
        f.write(f"ncols {ncols}\nnrows {nrows}\nxllcorner {X0}\nyllcorner {Y0}\ncellsize {CELL}\nNODATA_value -9999\n")
        row = " ".join(f"{-min(X0 + (c + 0.5) * CELL, FOOT) * SLOPE:.6f}" for c in range(ncols))
        for _ in range(nrows):
            f.write(row + "\n")


if __name__ == "__main__":
    main()
