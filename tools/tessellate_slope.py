#!/usr/bin/env python3
"""Writes a strength-reduction scene of a slope cut into blocks, with no slip surface given.

The section (x across the slope, z up) is a slope of height H rising at 1 : --slope-ratio from its toe at x = 0,
z = 0, with level ground --behind metres behind the crest and, optionally, a foundation layer --depth metres deep
that reaches --front metres in front of the toe (Griffiths & Lane 1999's depth factor D = 1 + depth / H). The
section is cut into triangles about --cell metres across and extruded by --width (default: one cell) into
triangular prisms, the blocks. Every block shares its faces with its neighbours; these faces are the joints
(Mohr-Coulomb, c, phi, tensile strength c / tan(phi) by default, perfectly plastic), and the scene's DDA keeps
them as fixed joints ("joints": "initial_faces"): the rigid-block-spring method, in which strength reduction finds
the critical mechanism among the joints by itself.

The triangles: the wedge under the slope face is one triangle cut into n x n similar triangles (n = H / cell
rounded); the ground behind the crest and the foundation are rectangles of cells cut along both diagonals (four
triangles a cell), so that slip may run along either diagonal. Fixed blocks hold the section: a rough base under
it (a joint as strong as the soil) and smooth walls (no friction, no cohesion: rollers) at its ends.

Joint springs: each contact point (a corner of a shared face) gets --joint-stiffness (Pa/m, normal; shear 0.4 of
it) times a quarter of the area of a cell-sized face. A small-displacement spring model's collapse load does not
depend on the springs' stiffness; the verification case checks that it does not here either.

    /usr/bin/python3 tools/tessellate_slope.py --height 10 --slope-ratio 2 --cohesion 10e3 --friction 20 \\
        --unit-weight 20e3 --cell 2.5 --out slope.json"""
import argparse
import os
import sys

import numpy as np

from block_geometry import (GRAVITY, add_joint_options, block, box, check_joint_options, joint, oriented,
                            strength_reduction_scene, tensile_strength, write_scene)
from esri_grid import write_asc


def wedge_triangles(height, run, n):
    """The triangle under the face, toe (0, 0), heel (run, 0), crest (run, height), cut into n^2 similar ones."""
    def node(i, j):
        return (i * run / n, j * height / n)
    triangles = []
    for i in range(n):
        for j in range(i + 1):
            triangles.append((node(i, j), node(i + 1, j), node(i + 1, j + 1)))
            if j < i:
                triangles.append((node(i, j), node(i + 1, j + 1), node(i, j + 1)))
    return triangles


def crossed_cells(xs, zs):
    """Each cell of the grid xs x zs cut along both diagonals into four triangles about its centre."""
    triangles = []
    for i in range(len(xs) - 1):
        for j in range(len(zs) - 1):
            a, b = (xs[i], zs[j]), (xs[i + 1], zs[j])
            c, d = (xs[i + 1], zs[j + 1]), (xs[i], zs[j + 1])
            m = (0.5 * (xs[i] + xs[i + 1]), 0.5 * (zs[j] + zs[j + 1]))
            triangles += [(a, b, m), (b, c, m), (c, d, m), (d, a, m)]
    return triangles


def spaced(lo, hi, cell):
    """Nodes from lo to hi, about cell apart (at least one interval)."""
    n = max(1, round((hi - lo) / cell))
    return [lo + (hi - lo) * k / n for k in range(n + 1)]


def section_triangles(args):
    """The section's triangles, conforming: every shared side is a whole side of both triangles."""
    h, run, cell = args.height, args.slope_ratio * args.height, args.cell
    n = max(1, round(h / cell))
    triangles = wedge_triangles(h, run, n)
    rows = [h * j / n for j in range(n + 1)]
    behind = spaced(run, run + args.behind, cell) if args.behind > 0 else [run]
    triangles += crossed_cells(behind, rows)
    if args.depth > 0:
        front = spaced(-args.front, 0.0, cell) if args.front > 0 else [0.0]
        columns = front[:-1] + [run * i / n for i in range(n)] + behind
        triangles += crossed_cells(columns, spaced(-args.depth, 0.0, cell))
    return triangles, n


def prism(triangle, width):
    """A triangle of the section (x, z) extruded along y from 0 to width."""
    vertices = [(x, 0.0, z) for x, z in triangle] + [(x, width, z) for x, z in triangle]
    faces = [[0, 1, 2], [3, 4, 5], [0, 1, 4, 3], [1, 2, 5, 4], [2, 0, 3, 5]]
    return vertices, oriented(vertices, faces)


def section_dem(args):
    """The section's ground surface as a DEM for the run-out: the profile, constant across the slope, from
    --runout-reach in front of the toe to the back wall and the slope's height to either side of the blocks; (values
    north row first, x0, y0, cell)."""
    cell, width = args.dem_cell, args.width or args.cell
    x0 = -(args.front if args.depth > 0 else 0.0) - args.runout_reach
    x1 = args.slope_ratio * args.height + args.behind
    y0, y1 = -args.height, width + args.height
    nx, ny = round((x1 - x0) / cell), round((y1 - y0) / cell)
    x = x0 + (np.arange(nx) + 0.5) * cell
    surface = np.clip(x / args.slope_ratio, 0.0, args.height)
    return np.tile(surface, (ny, 1)), x0, y0, cell


def scene(args):
    triangles, n = section_triangles(args)
    width = args.width if args.width else args.cell
    density = args.unit_weight / GRAVITY
    tensile = tensile_strength(args)
    point_stiffness = args.joint_stiffness * args.cell * width / 4.0
    soil = joint(args.cohesion, args.friction, tensile, point_stiffness)
    smooth = joint(0.0, 0.0, 0.0, point_stiffness)
    run = args.slope_ratio * args.height
    x_lo = -args.front if args.depth > 0 else 0.0
    x_hi = run + args.behind
    z_lo, thick = -args.depth, max(args.cell, 0.1 * args.height)
    # Fixed blocks first: a contact takes the model of the block listed first.
    bodies = [block("base", box((x_lo - thick, 0.0, z_lo - thick), (x_hi + thick, width, z_lo)), density, soil, True),
              block("back_wall", box((x_hi, 0.0, z_lo), (x_hi + thick, width, args.height)), density, smooth, True)]
    if args.depth > 0 and args.front > 0:
        bodies.append(block("front_wall", box((x_lo - thick, 0.0, z_lo), (x_lo, width, 0.0)), density, smooth, True))
    for k, t in enumerate(triangles):
        bodies.append(block("b%d" % k, prism(t, width), density, soil))
    area = sum(0.5 * abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) for a, b, c in triangles)
    crest = [round(run + 0.25 * args.cell, 6), round(0.5 * width, 6), round(args.height - 0.1 * args.cell, 6)]
    stage = {"stage": "strength_reduction", "dda": {"joints": "initial_faces"}, "bracket": args.bracket,
             "tolerance": args.tolerance, "max_steps": args.max_steps or max(20000, 5000 * n),
             "displacement_limit": args.displacement_limit or 0.02 * args.height, "monitors": [crest]}
    if args.runout_scene:
        out_dir = os.path.dirname(os.path.abspath(args.out))
        stage["handoff"] = {"runout_scene": os.path.relpath(os.path.abspath(args.runout_scene), out_dir),
                            "dem": os.path.relpath(os.path.abspath(args.dem), out_dir)}
    description = (
        "A slope %g m high at 1:%g (toe at x = 0), level ground %g m behind the crest%s, cut into %d triangular "
        "prisms about %g m across (%d cells up the face) and %g m wide, on a rough fixed base between smooth walls; "
        "joints c = %g Pa, phi = %g deg, tensile strength %.4g Pa, perfectly plastic, kept as fixed joints "
        "(rigid-block-spring method); unit weight %g N/m^3. Written by tools/tessellate_slope.py."
        % (args.height, args.slope_ratio, args.behind,
           ", a foundation %g m deep reaching %g m in front of the toe" % (args.depth, args.front) if args.depth else "",
           len(triangles), args.cell, n, width, args.cohesion, args.friction, tensile, args.unit_weight))
    lo = [x_lo - 2 * thick, -width, z_lo - 2 * thick]
    hi = [x_hi + 2 * thick, 2 * width, args.height + 2 * thick]
    return strength_reduction_scene(description, lo, hi, bodies, stage), len(triangles), area


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--height", type=float, default=10.0, help="slope height H, m (default 10)")
    ap.add_argument("--slope-ratio", type=float, default=2.0, help="horizontal run per unit rise (default 2)")
    ap.add_argument("--behind", type=float, default=None, help="level ground behind the crest, m (default 1.2 H)")
    ap.add_argument("--depth", type=float, default=0.0, help="foundation layer under the toe, m (default 0)")
    ap.add_argument("--front", type=float, default=None,
                    help="foundation reach in front of the toe, m (default 1.2 H with a foundation)")
    ap.add_argument("--cell", type=float, required=True, help="block size, m (the mesh parameter)")
    ap.add_argument("--width", type=float, help="extrusion width, m (default: one cell)")
    add_joint_options(ap, cohesion=10e3, friction=20.0)
    ap.add_argument("--max-steps", type=int,
                    help="step budget of a trial (default 5000 per cell up the face, at least 20000: relaxation "
                         "takes longer the more blocks a disturbance crosses)")
    ap.add_argument("--displacement-limit", type=float,
                    help="displacement that fails a trial, m (default 2%% of the height: far beyond the elastic "
                         "displacements, so that trials fail by collapse, and the criterion does not depend on the "
                         "block size or the springs)")
    ap.add_argument("--runout-scene", help="run-out scene the strength reduction hands the failing mass to (needs "
                                           "--dem)")
    ap.add_argument("--dem", help="ESRI ASCII DEM to write for the hand-off: the section's ground, constant across "
                                  "the slope")
    ap.add_argument("--dem-cell", type=float, help="cell of the DEM, m (default a fifth of --cell)")
    ap.add_argument("--runout-reach", type=float, help="level ground the DEM covers in front of the toe, m "
                                                       "(default 3 H)")
    ap.add_argument("--out", required=True, help="scene file to write")
    args = ap.parse_args(argv)
    if bool(args.runout_scene) != bool(args.dem):
        ap.error("--runout-scene and --dem go together: the run-out needs ground round the release")
    if args.dem_cell is None:
        args.dem_cell = args.cell / 5
    if args.runout_reach is None:
        args.runout_reach = 3 * args.height
    if not (args.dem_cell > 0 and args.runout_reach >= 0):
        ap.error("--dem-cell must be > 0 and --runout-reach >= 0")
    if args.behind is None:
        args.behind = 1.2 * args.height
    if args.front is None:
        args.front = 1.2 * args.height if args.depth > 0 else 0.0
    for name in ("height", "slope_ratio", "cell"):
        if not getattr(args, name) > 0:
            ap.error("--%s must be > 0" % name.replace("_", "-"))
    if args.behind < 0 or args.depth < 0 or args.front < 0 or (args.width is not None and args.width <= 0):
        ap.error("--behind, --depth and --front must be >= 0 and --width > 0")
    if args.cell > args.height:
        ap.error("--cell must not exceed --height")
    check_joint_options(ap, args)
    return args


def main():
    args = parse()
    s, blocks, area = scene(args)
    write_scene(args.out, s)
    if args.dem:
        write_asc(args.dem, *section_dem(args))
        print("wrote %s: the section's ground for the run-out" % args.dem)
    print("wrote %s: %d blocks over %.1f m^2 of section" % (args.out, blocks, area))


if __name__ == "__main__":
    sys.exit(main())
