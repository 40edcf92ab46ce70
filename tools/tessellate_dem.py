#!/usr/bin/env python3
"""Writes a strength-reduction scene of the ground under a DEM cut into tetrahedral blocks, with no slip surface given.

The volume is the ground over a rectangular plan window (--window X0 X1 Y0 Y1) from a level base (--base, an
elevation) up to the DEM's surface, bilinear between the DEM's cell centres. The window is cut into columns about
--cell metres across; each column is cut into --layers layers whose surfaces run from the base (flat) to the
ground (the DEM), so that every layer follows the terrain a little less than the one above it. Each cell of a layer
is a hexahedron with vertical sides. Each hexahedron is cut into 24 tetrahedra: each of its six faces into four
triangles about the face's centre, each triangle joined to the cell's centre. The cut depends on nothing but the
cell, so the tetrahedra conform (every inner face is a whole face of exactly two of them), and a cell's faces run
along both diagonals of each of its sides, as the cells cut along both diagonals of tools/tessellate_slope.py do in
the section: a slip surface through the cells can climb either way, and a slope turned or mirrored is cut the same
way. (Kuhn's six tetrahedra about one main diagonal give each side one diagonal only, and a slip surface that has to
climb the other way locks.)

The faces are the joints (Mohr-Coulomb, c, phi, tensile strength c / tan(phi) by default, perfectly plastic), kept
as fixed joints ("joints": "initial_faces"): the rigid-block-spring method, in which strength reduction finds the
critical mechanism among the joints by itself. A rough fixed base (a joint as strong as the ground) and smooth
fixed walls (rollers) on the window's four sides hold the volume. Each contact point (a corner of a shared face)
gets --joint-stiffness (Pa/m, normal; shear 0.4 of it) times a third of a triangle of a cell-sized face (a
quarter of the face).

    /usr/bin/python3 tools/tessellate_dem.py --dem share/dem/hillside_valley.asc --window 0 90 -130 -70 \\
        --base -8 --cell 15 --out slope.json"""
import argparse
import itertools
import os
import sys

import numpy as np

from block_geometry import (GRAVITY, add_joint_options, block, box, check_joint_options, joint, oriented,
                            strength_reduction_scene, tensile_strength, volume, write_scene)
from esri_grid import read_asc, refuse
from tessellate_slope import spaced


class Surface:
    """The DEM's ground, bilinear between its cell centres."""

    def __init__(self, path):
        values, extent, nodata = read_asc(path)
        self.path = path
        self.values = values[::-1]  # south row first
        self.nodata = nodata
        self.cell = (extent[1] - extent[0]) / values.shape[1]
        self.x0 = extent[0] + 0.5 * self.cell  # the first cell centre
        self.y0 = extent[2] + 0.5 * self.cell
        if min(values.shape) < 2:
            refuse("%s: %d x %d cells: a surface between cell centres needs at least 2 x 2" % (path, *values.shape))

    def at(self, x, y):
        """The ground's elevation at (x, y), which must lie between the DEM's cell centres."""
        rows, cols = self.values.shape
        fx, fy = (x - self.x0) / self.cell, (y - self.y0) / self.cell
        eps = 1e-9
        if not (-eps <= fx <= cols - 1 + eps and -eps <= fy <= rows - 1 + eps):
            refuse("%s: the point (%g, %g) of --window lies outside the DEM's cell centres" % (self.path, x, y))
        i, j = min(max(int(fx), 0), cols - 2), min(max(int(fy), 0), rows - 2)
        corners = self.values[j:j + 2, i:i + 2]
        tx, ty = fx - i, fy - j
        return float((1 - ty) * ((1 - tx) * corners[0, 0] + tx * corners[0, 1])
                     + ty * ((1 - tx) * corners[1, 0] + tx * corners[1, 1]))

    def check_window(self, window):
        """Refuses a window over which the DEM has a hole: any cell whose centre lies within a cell of it."""
        x0, x1, y0, y1 = window
        rows, cols = self.values.shape
        xs = self.x0 + np.arange(cols) * self.cell
        ys = self.y0 + np.arange(rows) * self.cell
        near_x = (xs >= x0 - self.cell) & (xs <= x1 + self.cell)
        near_y = (ys >= y0 - self.cell) & (ys <= y1 + self.cell)
        holes = np.argwhere((self.values == self.nodata) & near_y[:, None] & near_x[None, :])
        if len(holes):
            j, i = holes[0]
            refuse("%s: %d cell(s) without data in --window, the first at (%g, %g)"
                   % (self.path, len(holes), xs[i], ys[j]))


class Grid:
    """The nodes: xs x ys in plan, layer k of nz at base + (ground - base) k / nz."""

    def __init__(self, surface, args):
        x0, x1, y0, y1 = args.window
        surface.check_window(args.window)
        self.xs, self.ys = spaced(x0, x1, args.cell), spaced(y0, y1, args.cell)
        self.ground = np.array([[surface.at(x, y) for y in self.ys] for x in self.xs])
        self.base = args.base
        top, low = float(self.ground.max()), float(self.ground.min())
        if not low - self.base >= 0.05 * (top - self.base):
            refuse("--base %g: the ground over --window reaches down to %g, so its thinnest column (%g m) would be "
                   "under 5 %% of its deepest (%g m); set --base lower"
                   % (self.base, low, low - self.base, top - self.base))
        self.nz = args.layers or max(1, round((top - self.base) / args.cell))

    def node(self, i, j, k):
        """Node (i, j) of the plan grid on layer surface k."""
        return (self.xs[i], self.ys[j], self.base + (self.ground[i, j] - self.base) * k / self.nz)

    def hexahedra(self):
        """(cell index, its corners as a dict (a, b, c) -> point) for every cell, bottom layer first."""
        nx, ny = len(self.xs) - 1, len(self.ys) - 1
        for k in range(self.nz):
            for j in range(ny):
                for i in range(nx):
                    yield (i, j, k), {(a, b, c): self.node(i + a, j + b, k + c)
                                      for a, b, c in itertools.product((0, 1), repeat=3)}


# The faces of the unit cell, each with its corners in turn.
HEX_FACES = [[(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
             [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)], [(0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1)],
             [(0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)], [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)]]


def mean(points):
    """The mean of points (x, y, z)."""
    return tuple(sum(p[d] for p in points) / len(points) for d in range(3))


def crossed(corners):
    """A cell's 24 tetrahedra: each face in four triangles about its centre, each joined to the cell's centre."""
    centre = mean(list(corners.values()))
    tets = []
    for face in HEX_FACES:
        q = [corners[c] for c in face]
        middle = mean(q)
        tets += [[centre, middle, q[m], q[(m + 1) % 4]] for m in range(4)]
    return tets


def tetrahedron(points):
    """A tetrahedron's shape (vertices, outward faces)."""
    return list(points), oriented(points, [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])


def steepest_cell(grid):
    """The plan cell whose ground is steepest (largest gradient of its bilinear surface at its centre)."""
    g = grid.ground
    dx, dy = np.diff(grid.xs), np.diff(grid.ys)
    sx = 0.5 * (g[1:, 1:] + g[1:, :-1] - g[:-1, 1:] - g[:-1, :-1]) / dx[:, None]
    sy = 0.5 * (g[1:, 1:] + g[:-1, 1:] - g[1:, :-1] - g[:-1, :-1]) / dy[None, :]
    i, j = np.unravel_index(np.argmax(sx * sx + sy * sy), sx.shape)
    return int(i), int(j)


def scene(args):
    surface = Surface(args.dem)
    grid = Grid(surface, args)
    x0, x1, y0, y1 = args.window
    top = float(grid.ground.max())
    relief = top - float(grid.ground.min())
    density = args.unit_weight / GRAVITY
    tensile = tensile_strength(args)
    point_stiffness = args.joint_stiffness * args.cell * args.cell / 12.0
    soil = joint(args.cohesion, args.friction, tensile, point_stiffness)
    smooth = joint(0.0, 0.0, 0.0, point_stiffness)
    thick = max(args.cell, 0.1 * (top - grid.base))
    wall_top = top + thick
    # Fixed blocks first: a contact takes the model of the block listed first. The walls meet face to face.
    fixed = [
        block("base", box((x0 - thick, y0 - thick, grid.base - thick), (x1 + thick, y1 + thick, grid.base)), density,
              soil, True),
        block("wall_west", box((x0 - thick, y0, grid.base), (x0, y1, wall_top)), density, smooth, True),
        block("wall_east", box((x1, y0, grid.base), (x1 + thick, y1, wall_top)), density, smooth, True),
        block("wall_south", box((x0 - thick, y0 - thick, grid.base), (x1 + thick, y0, wall_top)), density, smooth,
              True),
        block("wall_north", box((x0 - thick, y1, grid.base), (x1 + thick, y1 + thick, wall_top)), density, smooth,
              True)]
    bodies = list(fixed)
    total = 0.0
    monitor_cell = steepest_cell(grid) + (grid.nz - 1,)
    monitor = None
    for (i, j, k), corners in grid.hexahedra():
        for t, points in enumerate(crossed(corners)):
            shape = tetrahedron(points)
            total += volume(*shape)
            bodies.append(block("t%d_%d_%d_%d" % (i, j, k, t), shape, density, soil))
            if (i, j, k) == monitor_cell and t == 0:
                monitor = [round(v, 6) for v in mean(points)]
    n_across = max(len(grid.xs), len(grid.ys), grid.nz + 1) - 1
    stage = {"stage": "strength_reduction", "dda": {"joints": "initial_faces"}, "bracket": args.bracket,
             "tolerance": args.tolerance, "max_steps": args.max_steps or max(20000, 5000 * n_across),
             "displacement_limit": args.displacement_limit or 0.02 * relief, "monitors": [monitor]}
    if args.runout_scene:
        out_dir = os.path.dirname(os.path.abspath(args.out))
        stage["handoff"] = {"runout_scene": os.path.relpath(os.path.abspath(args.runout_scene), out_dir),
                            "dem": os.path.relpath(os.path.abspath(args.dem), out_dir)}
    tets = len(bodies) - len(fixed)
    description = (
        "The ground under %s over x in [%g, %g], y in [%g, %g] from a level base at z = %g up to the DEM (%.4g m of "
        "relief), cut into %d x %d columns about %g m across and %d terrain-following layers, %d tetrahedra "
        "(%.6g m^3), on a rough fixed base between smooth walls; joints c = %g Pa, phi = %g deg, tensile strength "
        "%.4g Pa, perfectly plastic, kept as fixed joints (rigid-block-spring method); unit weight %g N/m^3. Written "
        "by tools/tessellate_dem.py."
        % (os.path.basename(args.dem), x0, x1, y0, y1, grid.base, relief, len(grid.xs) - 1, len(grid.ys) - 1,
           args.cell, grid.nz, tets, total, args.cohesion, args.friction, tensile, args.unit_weight))
    lo = [x0 - 2 * thick, y0 - 2 * thick, grid.base - 2 * thick]
    hi = [x1 + 2 * thick, y1 + 2 * thick, wall_top + thick]
    return strength_reduction_scene(description, lo, hi, bodies, stage), tets, total


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dem", required=True, help="ESRI ASCII DEM of the ground")
    ap.add_argument("--window", type=float, nargs=4, required=True, metavar=("X0", "X1", "Y0", "Y1"),
                    help="plan extent of the volume, m (inside the DEM's cell centres)")
    ap.add_argument("--base", type=float, required=True,
                    help="elevation of the level base under the volume, m (below the ground everywhere in the "
                         "window: the thinnest column at least 5 %% of the deepest)")
    ap.add_argument("--cell", type=float, required=True, help="column size in plan, m (the mesh parameter)")
    ap.add_argument("--layers", type=int, help="layers from the base to the ground (default: the deepest column "
                                               "over --cell, rounded)")
    add_joint_options(ap, cohesion=30e3, friction=30.0)
    ap.add_argument("--max-steps", type=int,
                    help="step budget of a trial (default 5000 per cell along the grid's longest side, at least "
                         "20000)")
    ap.add_argument("--displacement-limit", type=float,
                    help="displacement that fails a trial, m (default 2%% of the ground's relief in the window)")
    ap.add_argument("--runout-scene", help="run-out scene the strength reduction hands the failing mass to, over "
                                           "--dem")
    ap.add_argument("--out", required=True, help="scene file to write")
    args = ap.parse_args(argv)
    x0, x1, y0, y1 = args.window
    if not (x1 > x0 and y1 > y0):
        ap.error("--window must have X1 > X0 and Y1 > Y0")
    if not args.cell > 0:
        ap.error("--cell must be > 0")
    if args.cell > min(x1 - x0, y1 - y0):
        ap.error("--cell must not exceed the window's shorter side")
    if args.layers is not None and args.layers < 1:
        ap.error("--layers must be >= 1")
    check_joint_options(ap, args)
    return args


def main():
    args = parse()
    s, tets, total = scene(args)
    write_scene(args.out, s)
    print("wrote %s: %d tetrahedra, %.6g m^3 of ground" % (args.out, tets, total))


if __name__ == "__main__":
    sys.exit(main())
