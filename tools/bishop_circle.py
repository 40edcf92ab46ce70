#!/usr/bin/env python3
"""Simplified Bishop (1955) factor of safety of the slope tools/tessellate_slope.py cuts, by a search over circles.

The section is the tool's: toe at x = 0, z = 0, the face rising at 1 : --slope-ratio to the crest at height H, level
ground behind it, a rigid base --depth below the toe (circles may touch it, not cross it) and, with a foundation,
level ground in front of the toe. Each circle's sliding mass is cut into vertical slices; the factor solves
F = sum[(c b + W tan(phi)) / m_alpha] / sum[W sin(alpha)], m_alpha = cos(alpha) + sin(alpha) tan(phi) / F, by
fixed-point iteration. The search runs a coarse grid of centres and radii, then refines round the best circle.
It is the limit-equilibrium reference the tessellated slope's strength reduction is compared with, on the same
geometry.

    /usr/bin/python3 tools/bishop_circle.py --height 10 --slope-ratio 2 --cohesion 10e3 --friction 20"""
import argparse
import math

import numpy as np


def ground(x, height, ratio):
    return np.clip(x / ratio, 0.0, height)


def bishop(circle, args, slices=200):
    """The factor of one circle (xc, zc, R), or None when it cuts no proper sliding mass or crosses the base."""
    xc, zc, r = circle
    if zc - r < -args.depth - 1e-9 or r <= 0:
        return None
    xs = np.linspace(xc - r, xc + r, 4001)
    below = zc - np.sqrt(np.maximum(r * r - (xs - xc) ** 2, 0.0)) < ground(xs, args.height, args.slope_ratio)
    inside = np.nonzero(below)[0]
    if inside.size < 2 or np.any(np.diff(inside) > 1):
        return None  # no mass, or the arc leaves and re-enters the ground
    edges = np.linspace(xs[inside[0]], xs[inside[-1]], slices + 1)
    x, b = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    base = zc - np.sqrt(np.maximum(r * r - (x - xc) ** 2, 0.0))
    weight = args.unit_weight * b * np.maximum(ground(x, args.height, args.slope_ratio) - base, 0.0)
    alpha = np.arcsin(np.clip((x - xc) / r, -1.0, 1.0))
    driving = np.sum(weight * np.sin(alpha))
    if driving <= 0:
        return None
    tan_phi, factor = math.tan(math.radians(args.friction)), 1.0
    for _ in range(200):
        m = np.cos(alpha) + np.sin(alpha) * tan_phi / factor
        if np.any(m <= 0.2):  # the usual limit on m_alpha: steep slice bases make the method meaningless
            return None
        new = np.sum((args.cohesion * b + weight * tan_phi) / m) / driving
        if abs(new - factor) < 1e-9:
            return new
        factor = new
    return None


def search(args):
    """Smallest factor over a grid of circles, refined three times round the best; (F, (xc, zc, R))."""
    h, run = args.height, args.slope_ratio * args.height
    best = (math.inf, None)
    for xc in np.linspace(-0.5 * run, 1.5 * run, 41):
        for zc in np.linspace(0.5 * h, 4.0 * h, 36):
            for r in np.linspace(0.5 * h, 5.0 * h, 46):
                f = bishop((xc, zc, r), args, 60)
                if f is not None and f < best[0]:
                    best = (f, (xc, zc, r))
    step = (run / 20, h / 10, h / 10)
    for _ in range(3):
        if best[1] is None:
            break
        centre = best[1]
        for dx in np.linspace(-step[0], step[0], 9):
            for dz in np.linspace(-step[1], step[1], 9):
                for dr in np.linspace(-step[2], step[2], 9):
                    circle = (centre[0] + dx, centre[1] + dz, centre[2] + dr)
                    f = bishop(circle, args)
                    if f is not None and f < best[0]:
                        best = (f, circle)
        step = tuple(s / 4 for s in step)
    return best


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--height", type=float, default=10.0, help="slope height H, m (default 10)")
    ap.add_argument("--slope-ratio", type=float, default=2.0, help="horizontal run per unit rise (default 2)")
    ap.add_argument("--depth", type=float, default=0.0, help="rigid base below the toe, m (default 0)")
    ap.add_argument("--unit-weight", type=float, default=20e3, help="soil unit weight, N/m^3 (default 20e3)")
    ap.add_argument("--cohesion", type=float, default=10e3, help="cohesion, Pa (default 10e3)")
    ap.add_argument("--friction", type=float, default=20.0, help="friction angle, deg (default 20)")
    args = ap.parse_args(argv)
    for name in ("height", "slope_ratio", "unit_weight"):
        if not getattr(args, name) > 0:
            ap.error("--%s must be > 0" % name.replace("_", "-"))
    if args.depth < 0 or args.cohesion < 0 or not 0 <= args.friction < 90:
        ap.error("--depth and --cohesion must be >= 0 and --friction in [0, 90)")
    return args


def main():
    args = parse()
    factor, circle = search(args)
    if circle is None:
        raise SystemExit("error: no circle cuts a sliding mass out of this slope")
    print("simplified Bishop: F = %.4f on the circle centred at x = %.2f m, z = %.2f m, radius %.2f m"
          % (factor, *circle))


if __name__ == "__main__":
    main()
