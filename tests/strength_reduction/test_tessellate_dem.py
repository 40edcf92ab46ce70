#!/usr/bin/env python3
"""tools/tessellate_dem.py: the tetrahedra under a DEM conform (every inner face a whole face of exactly two of them,
every other face on the base, the window's sides or the ground) and fill the ground's volume exactly; the safety
factor of a slope does not change when the slope is turned by 90 degrees or moved (the cut is the same), and lies
above the section's rigid-block factor (fewer, coarser blocks); on the hillside's spur the failing mass reaches the
hand-off and the run-out over the DEM (the slip surface let into it) with its volume and the ground's reduced
strength; bad input exits 2 and writes nothing.

    test_tessellate_dem.py TALUS SOURCE_DIR WORK_DIR"""
import functools
import math
import os
import re
import sys
from collections import Counter

import numpy as np

talus, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tools"))
import tessellate_dem as tool  # noqa: E402
from esri_grid import read_asc, write_asc  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_runs  # noqa: E402
from tool_runs import check  # noqa: E402

HILLSIDE = os.path.join(source, "share", "dem", "hillside_valley.asc")
HILLSIDE_ARGS = ["--dem", HILLSIDE, "--window", "0", "90", "-130", "-70", "--base", "-8"]
write_scene = functools.partial(tool_runs.write_scene, os.path.join(source, "tools", "tessellate_dem.py"), work)
run = functools.partial(tool_runs.run, talus, work)


def slope_dem(path, turned=False, shift=(0.0, 0.0, 0.0)):
    """Griffiths & Lane's 2:1 slope, 10 m high, toe at x = 0 (level ground in front and behind), constant along y;
    turned by 90 degrees about z it rises along +y instead. Cell centres fall on the toe and the crest."""
    cell, n_along, n_across = 0.5, 100, 30
    along = -14.25 + (np.arange(n_along) + 0.5) * cell
    profile = np.clip(along / 2.0, 0.0, 10.0) + shift[2]
    if turned:  # (x, y) -> (-y, x): x' across in [-7.25, 7.75], y' = x along
        write_asc(path, np.tile(profile[::-1, None], (1, n_across)), -7.25 + shift[0], -14.25 + shift[1], cell)
    else:
        write_asc(path, np.tile(profile, (n_across, 1)), -14.25 + shift[0], -7.25 + shift[1], cell)


def slope_args(dem, turned=False, shift=(0.0, 0.0, 0.0)):
    window = ([-5.0, 0.0, -12.0, 32.0] if turned else [-12.0, 32.0, 0.0, 5.0])
    window = [w + shift[k // 2] for k, w in enumerate(window)]
    return ["--dem", dem, "--window", *map(str, window), "--base", str(-2.0 + shift[2]), "--cell", "5",
            "--cohesion", "10e3", "--friction", "20"]


os.makedirs(work, exist_ok=True)

# 1. Conforming tetrahedra that fill the ground: on the extruded slope (exact volume 308 m^2 x 5 m) and on the
# hillside's spur (the volume under the triangulated ground).
dem = os.path.join(work, "slope.asc")
slope_dem(dem)
for name, argv, exact in (("slope", slope_args(dem), 308.0 * 5.0), ("hillside", HILLSIDE_ARGS + ["--cell", "20"], None)):
    args = tool.parse(argv + ["--out", "unused"])
    grid = tool.Grid(tool.Surface(args.dem), args)
    faces, total, tets = Counter(), 0.0, 0
    for _, corners in grid.hexahedra():
        for points in tool.crossed(corners):
            shape = tool.tetrahedron(points)
            total += tool.volume(*shape)
            tets += 1
            for f in shape[1]:
                faces[tuple(sorted(tuple(round(c, 9) for c in points[i]) for i in f))] += 1
    x0, x1, y0, y1 = args.window
    top_area, top_volume, stray = 0.0, 0.0, 0
    for f, k in faces.items():
        if k == 2:
            continue
        on_side = any(all(abs(p[d] - v) < 1e-9 for p in f) for d, v in ((0, x0), (0, x1), (1, y0), (1, y1)))
        on_base = all(abs(p[2] - args.base) < 1e-9 for p in f)
        if on_side or on_base:
            continue
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = f
        plan = 0.5 * abs((bx - ax) * (cy - ay) - (cx - ax) * (by - ay))
        top_area += plan
        top_volume += plan * ((az + bz + cz) / 3.0 - args.base)
        stray += plan == 0.0
    if exact is None:
        exact = top_volume
    check(max(faces.values()) == 2 and stray == 0 and abs(top_area / ((x1 - x0) * (y1 - y0)) - 1.0) < 1e-12
          and abs(total / exact - 1.0) < 1e-12,
          "%s: %d tetrahedra conform (%d inner faces shared twice; the rest on the base, the sides or the ground, "
          "which covers the window once) and fill %.6f of %.6f m^3"
          % (name, tets, sum(1 for k in faces.values() if k == 2), total, exact))

# 2. Turned by 90 degrees, or moved by (1000, -2000, 300) m, the slope is cut into the same blocks and keeps its
# factor (to the bisection's tolerance: the blocks come in another order, so sums round differently).
factors = {}
for name, turned, shift in (("slope", False, (0.0, 0.0, 0.0)), ("turned", True, (0.0, 0.0, 0.0)),
                            ("moved", False, (1000.0, -2000.0, 300.0))):
    dem = os.path.join(work, name + ".asc")
    slope_dem(dem, turned, shift)
    r, scene = write_scene(name, *slope_args(dem, turned, shift))
    ran, _, factors[name] = run(scene, name)
    check(r.returncode == 0 and ran.returncode == 0 and not math.isnan(factors[name]),
          "%s: F_s = %.4f" % (name, factors[name]))
check(abs(factors["turned"] - factors["slope"]) <= 0.005 and abs(factors["moved"] - factors["slope"]) <= 0.005,
      "turned and moved: F_s %.4f and %.4f against %.4f" % (factors["turned"], factors["moved"], factors["slope"]))
# The section cut of tools/tessellate_slope.py gives 1.4888 at 2.5 m on this slope (foundation 2 m) and simplified
# Bishop 1.368: a rigid-block factor is an upper bound of its blocks' mechanisms, and these blocks are coarser.
check(1.4888 <= factors["slope"] <= 2.0, "the 5 m cut's F_s %.4f lies above the section cut's 1.4888 and below 2"
      % factors["slope"])

# 3. The hillside's spur, a face that is not a plane: the chain from a tessellated DEM to its run-out.
runout_template = os.path.join(source, "share", "scenes", "hillside_runout.json")
r, scene = write_scene("hillside", *HILLSIDE_ARGS, "--cell", "20", "--runout-scene", runout_template)
ran, out, fs = run(scene, "hillside")
text = ran.stdout + ran.stderr
check(not math.isnan(fs), "hillside: F_s = %.4f" % fs)
raster_volume = tool_runs.check_handoff(r, ran)
# The run-out's terrain is the DEM with the slip surface let into it: the fixed walls (which rise above the ground)
# and the base (which reaches beyond it) are not terrain.
terrain_path = os.path.join(out, "strength_reduction_terrain.asc")
if os.path.exists(terrain_path):
    terrain, ground = read_asc(terrain_path)[0], read_asc(HILLSIDE)[0]
    thickness = read_asc(os.path.join(out, "strength_reduction_thickness.asc"))[0]
    scar = thickness > 0.0
    check(terrain.shape == ground.shape and np.all(terrain <= ground + 1e-6) and np.all(terrain[~scar] == ground[~scar])
          and float(np.max(ground - terrain)) > 1.0,
          "the run-out's terrain: the DEM off the failed mass, up to %.2f m under it beneath"
          % float(np.max(ground - terrain)))
else:
    check(False, "the hand-off wrote %s" % terrain_path)
# The run-out's basal law is the ground's joint reduced by F_s, not the smooth walls' that the slip surface also
# runs along.
strength = re.search(r"c/F_s = ([0-9.e+-]+) Pa, phi_F = ([0-9.e+-]+) deg", text)
check(strength is not None and abs(float(strength.group(1)) / (30e3 / fs) - 1.0) < 1e-3
      and abs(float(strength.group(2)) - math.degrees(math.atan(math.tan(math.radians(30.0)) / fs))) < 0.01,
      "the run-out gets c/F_s = %s Pa and phi_F = %s deg (the ground's joint: %.4g Pa, %.4g deg)"
      % (strength.group(1) if strength else "-", strength.group(2) if strength else "-", 30e3 / fs,
         math.degrees(math.atan(math.tan(math.radians(30.0)) / fs))))
tool_runs.check_runout_keeps_volume(talus, work, out, raster_volume, "hillside_runout")

# 4. Bad input: exit 2, nothing written.
nodata = os.path.join(work, "nodata.asc")
z = np.full((30, 100), 5.0)
z[10, 40] = -9999.0
write_asc(nodata, z, -14.25, -7.25, 0.5)
for bad in (HILLSIDE_ARGS[:2] + ["--window", "0", "500", "-130", "-70", "--base", "-8", "--cell", "20"],
            HILLSIDE_ARGS[:4] + ["90", "-130", "-70", "--base", "10", "--cell", "20"],
            ["--dem", nodata, "--window", "-12", "32", "0", "5", "--base", "0", "--cell", "5"],
            ["--dem", os.path.join(work, "missing.asc"), "--window", "0", "1", "0", "1", "--base", "0", "--cell", "1"],
            HILLSIDE_ARGS + ["--cell", "0"], HILLSIDE_ARGS + ["--cell", "20", "--layers", "0"]):
    r, path = write_scene("bad", *bad)
    check(r.returncode == 2 and "error" in r.stderr and not os.path.exists(path),
          "refused with exit 2, nothing written: %s" % (r.stderr.strip().splitlines() or ["-"])[-1])

tool_runs.finish()
