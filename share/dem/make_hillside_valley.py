#!/usr/bin/env python3
"""Writes hillside_valley.asc: a synthetic practical slope for the whole landslide chain
(share/scenes/hillside_chain.json). A hillside 50 m high at 40 degrees faces -x above a valley whose floor falls
2 % towards -y; the hillside's toe bulges out as a spur around y = -100, and across the valley the opposite bank
rises at 15 degrees beyond x = -40. Slope breaks are rounded over a few metres; between them, around y = 0, the
face is a plane (z = tan 40 (x - 10) + 0.02 y), where the slide of hillside_chain.json sits. 2 m cells, x in [-100, 120],
y in [-160, 100]."""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from esri_grid import write_asc  # noqa: E402

CELL = 2.0
X0, X1, Y0, Y1 = -100.0, 120.0, -160.0, 100.0
HEIGHT, FACE = 50.0, math.tan(math.radians(40.0))
ROUNDING = 1.0  # m, width over which slope breaks are rounded


def softplus(s, width):
    return width * np.logaddexp(0.0, s / width)


def elevation(x, y):
    floor = 0.02 * y
    toe = 10.0 - 8.0 * np.exp(-((y + 100.0) / 30.0) ** 2)
    rise = softplus(FACE * (x - toe), ROUNDING) - softplus(FACE * (x - toe) - HEIGHT, ROUNDING)
    plateau = 0.05 * softplus(x - toe - HEIGHT / FACE, ROUNDING)
    bank = math.tan(math.radians(15.0)) * softplus(-40.0 - x, ROUNDING)
    return floor + rise + plateau + bank


def main():
    nc, nr = int(round((X1 - X0) / CELL)), int(round((Y1 - Y0) / CELL))
    x = X0 + (np.arange(nc) + 0.5) * CELL
    y = Y1 - (np.arange(nr) + 0.5) * CELL  # north row first
    gx, gy = np.meshgrid(x, y)
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hillside_valley.asc")
    write_asc(path, elevation(gx, gy), X0, Y0, CELL)
    print("wrote", path)


if __name__ == "__main__":
    main()
