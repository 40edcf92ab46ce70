#!/usr/bin/env python3
"""tools/tessellate_slope.py and fixed joints: the section's triangles conform (every inner side shared by exactly
two of them) and fill the section exactly, with and without a foundation; every shared face becomes one joint of
four springs and nothing else is a joint; the safety factor of the Griffiths & Lane slope at the coarse rung does
not depend on the joints' stiffness (a small-displacement spring model's collapse load must not) and lies near the
finite-element and Bishop factors; tools/bishop_circle.py gives Bishop & Morgenstern's chart factor on the same
geometry, scales exactly with c and tan(phi) and not with the slope's size; a restarted search continues exactly;
the failing mass reaches the hand-off and the run-out over the section's DEM with its volume; bad arguments exit 2.

    test_tessellate_slope.py TALUS SOURCE_DIR WORK_DIR"""
import csv
import functools
import json
import os
import sys
from collections import Counter

talus, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tools"))
import tessellate_slope as tool  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tool_runs  # noqa: E402
from tool_runs import check  # noqa: E402

TOOL = os.path.join(source, "tools", "tessellate_slope.py")
write_scene = functools.partial(tool_runs.write_scene, TOOL, work)
run = functools.partial(tool_runs.run, talus, work)


def trial_rows(out):
    with open(os.path.join(out, "strength_reduction.csv")) as f:
        return list(csv.DictReader(f))


os.makedirs(work, exist_ok=True)

# 1. Conforming triangles that fill the section.
for depth, front in ((0.0, 0.0), (5.0, 7.5)):
    args = tool.parse(["--cell", "2.5", "--depth", str(depth), "--front", str(front), "--out", "unused"])
    triangles, n = tool.section_triangles(args)
    sides = Counter()
    for t in triangles:
        for k in range(3):
            a, b = t[k], t[(k + 1) % 3]
            sides[tuple(sorted((tuple(round(x, 9) for x in a), tuple(round(x, 9) for x in b))))] += 1
    area = sum(0.5 * abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) for a, b, c in triangles)
    run_x = args.slope_ratio * args.height
    exact = 0.5 * run_x * args.height + args.behind * args.height + (front + run_x + args.behind) * depth
    x_lo, x_hi = -front if depth else 0.0, run_x + args.behind

    def on_boundary(side):
        (x0, z0), (x1, z1) = side
        face = abs(z0 - x0 / args.slope_ratio) < 1e-9 and abs(z1 - x1 / args.slope_ratio) < 1e-9 and x0 >= 0 and x1 >= 0
        level = (z0 == z1 and z0 in (args.height, -depth)) or (z0 == z1 == 0.0 and max(x0, x1) <= 0.0)
        return face or level or (x0 == x1 and x0 in (x_lo, x_hi))

    open_sides = [s for s, k in sides.items() if k == 1 and not on_boundary(s)]
    check(max(sides.values()) == 2 and not open_sides and abs(area / exact - 1.0) < 1e-12,
          "depth %g: %d triangles conform (%d inner sides shared twice, %d unshared inner sides) and cover %.6f of "
          "%.6f m^2" % (depth, len(triangles), sum(1 for k in sides.values() if k == 2), len(open_sides), area, exact))

# The shipped scene is what the tool writes by default at 2.5 m cells.
_, default = write_scene("default", "--cell", "2.5")
with open(default) as f, open(os.path.join(source, "share", "scenes", "tessellated_slope.json")) as g:
    check(json.load(f) == json.load(g), "share/scenes/tessellated_slope.json is the tool's default at --cell 2.5")

# 2. The coarse rung: joints, the factor, and its independence of the springs.
factors = {}
for stiffness in ("1e7", "1e8", "1e9"):
    r, scene = write_scene("slope_" + stiffness, "--cell", "2.5", "--joint-stiffness", stiffness)
    ran, out, fs = run(scene, "slope_" + stiffness)
    check(r.returncode == 0 and ran.returncode == 0, "joint stiffness %s Pa/m: the scene is written and runs" % stiffness)
    factors[stiffness] = fs
    if stiffness == "1e8":
        args = tool.parse(["--cell", "2.5", "--out", "unused"])
        triangles, _ = tool.section_triangles(args)
        shared = Counter()
        for t in triangles:
            for k in range(3):
                shared[tuple(sorted((tuple(round(x, 9) for x in t[k]), tuple(round(x, 9) for x in t[(k + 1) % 3]))))] += 1
        inner = sum(1 for k in shared.values() if k == 2)
        on_fixed = sum(1 for (a, b), k in shared.items() if k == 1 and (a[1] == b[1] == 0.0 or a[0] == b[0] == 32.0))
        rows = trial_rows(out)
        check(all(int(row["contacts"]) == 4 * (inner + on_fixed) for row in rows),
              "%s contacts in every trial = 4 springs x (%d shared faces + %d on the base and back wall)"
              % (rows[0]["contacts"], inner, on_fixed))
        failing = [row for row in rows if row["outcome"] == "failed"]
        check(bool(failing) and all(row["no_equilibrium"] == "1" or row["displacement_limit"] == "1"
                                    or row["displacement_growing"] == "1" for row in failing),
              "every failing trial fails by collapse (no equilibrium or displacement), not by the slip path alone")
spread = max(factors.values()) - min(factors.values())
print("     F_s at joint stiffness 1e7, 1e8, 1e9 Pa/m: %s" % ", ".join("%.4f" % f for f in factors.values()))
check(spread <= 0.01, "F_s does not depend on the joint stiffness over two decades (spread %.4f <= two tolerances)"
      % spread)
# Griffiths & Lane 1999, example 1 (D = 1): 1.40 by finite elements, 1.38 by Bishop and Morgenstern's charts. Rigid
# triangles overestimate at coarse cells (a mechanism must follow their sides); the verification case has the ladder.
fs = factors["1e8"]
check(abs(fs / 1.40 - 1.0) < 0.08, "F_s = %.4f at 2.5 m cells, %+.1f %% from the finite-element 1.40" %
      (fs, 100 * (fs / 1.40 - 1.0)))

# The limit-equilibrium reference on the same geometry (tools/bishop_circle.py): Bishop & Morgenstern's chart value,
# exact homogeneity (c and tan(phi) times k give F times k), and the same F for a slope ten times the size with the
# same c / (gamma H).
import bishop_circle  # noqa: E402
import math  # noqa: E402


def bishop(*argv):
    return bishop_circle.search(bishop_circle.parse(list(argv)))


f_ref, circle = bishop()
check(abs(f_ref - 1.38) < 0.005, "simplified Bishop over circles: F = %.4f (the chart's 1.38), circle at (%.2f, %.2f) "
      "R %.2f" % (f_ref, *circle))
k = 1.5
f_k = bishop("--cohesion", "15e3", "--friction", str(math.degrees(math.atan(k * math.tan(math.radians(20))))))[0]
check(abs(f_k / (k * f_ref) - 1.0) < 1e-3, "c and tan(phi) times 1.5: F times %.5f" % (f_k / f_ref))
f_big = bishop("--height", "100", "--cohesion", "100e3")[0]
check(abs(f_big / f_ref - 1.0) < 1e-3, "ten times the size at the same c / (gamma H): F = %.4f" % f_big)
print("     strength reduction on rigid blocks %.4f, simplified Bishop %.4f (%+.1f %%)" % (fs, f_ref,
                                                                                   100 * (fs / f_ref - 1.0)))

# 3. A restart from the first checkpoint continues the search exactly.
_, scene = write_scene("restart", "--cell", "2.5")
with open(scene) as f:
    s = json.load(f)
s["checkpoint"] = {"every": 0.3, "keep": 5}
with open(scene, "w") as f:
    json.dump(s, f)
whole, out, fs_whole = run(scene, "restart_whole")
points = sorted(p for p in os.listdir(out) if p.endswith(".checkpoint"))
resumed, out2, fs_resumed = run(scene, "restart_resumed", "--restart", os.path.join(out, points[0]))


def table(directory):
    return [{k: v for k, v in row.items() if k != "wall_s"} for row in trial_rows(directory)]


check(whole.returncode == 0 and resumed.returncode == 0 and fs_whole == fs_resumed and table(out) == table(out2),
      "restarted from %s: F_s %.4f and the trial table as the whole run's" % (points[0] if points else "-", fs_resumed))

# 4. The whole chain from a section: the failing mass is the blocks that moved beyond anything the holding trial
# showed; its volume reaches the thickness raster within 1 % (the gate) and runs out over the section's DEM
# (written by the tool) with that volume.
dem = os.path.join(work, "section_dem.asc")
r, scene = write_scene("chain", "--cell", "2.5", "--dem", dem, "--runout-scene",
                       os.path.join(source, "share", "scenes", "planar_slide_runout.json"))
ran, out, _ = run(scene, "chain")
raster_volume = tool_runs.check_handoff(r, ran)
tool_runs.check_runout_keeps_volume(talus, work, out, raster_volume, "chain_runout")

# 5. Bad arguments.
for bad in (["--cell", "20"], ["--cell", "0"], ["--cell", "2.5", "--friction", "95"],
            ["--cell", "2.5", "--dem", os.path.join(work, "alone.asc")]):
    r, path = write_scene("bad", *bad)
    check(r.returncode == 2 and "error" in r.stderr and not os.path.exists(path),
          "refused with exit 2, nothing written: %s" % " ".join(bad))

tool_runs.finish()
