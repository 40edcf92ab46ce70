#!/usr/bin/env python3
"""tools/make_ellipsoid_slide.py: the shipped spherical cap and hillside scenes are what it writes; the joints are
equally stiff per unit area on every facet; the faceted block's volume converges to the smooth ellipsoidal cap at
second order, in any frame; a face fitted to a planar DEM is that plane; every block it writes passes
`talus validate`; a face that misses the ellipsoid is refused.

    test_ellipsoid_slide.py TALUS SOURCE_DIR WORK_DIR"""
import json
import math
import os
import subprocess
import sys

talus, source, work = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "tools"))
import make_ellipsoid_slide as tool  # noqa: E402
import make_spherical_cap  # noqa: E402
from block_geometry import polygon_area  # noqa: E402
import numpy as np  # noqa: E402
from esri_grid import write_asc  # noqa: E402

failures, checks = [], []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    checks.append(what)
    if not ok:
        failures.append(what)


def load(name):
    with open(os.path.join(source, "share", "scenes", name)) as f:
        return json.load(f)


def run_tool(*args):
    return subprocess.run([sys.executable, os.path.join(source, "tools", "make_ellipsoid_slide.py"), *args],
                          capture_output=True, text=True)


os.makedirs(work, exist_ok=True)

# 1. The shipped scenes are what the tools write.
check(make_spherical_cap.scene(4, 16, 5.0) == load("spherical_cap.json"),
      "share/scenes/spherical_cap.json is make_spherical_cap.py's default")
hillside = os.path.join(work, "hillside_chain.json")
r = run_tool("--dem", os.path.join(source, "share", "dem", "hillside_valley.asc"),
             "--ellipsoid", "16.6", "0", "50", "48.5", "30", "48.5", "--cohesion", "30e3", "--friction", "20",
             "--runout-scene", os.path.join(source, "share", "scenes", "hillside_runout.json"), "--out", hillside)
with open(hillside) as f:
    written = json.load(f)
shipped = load("hillside_chain.json")
written["pipeline"][0]["handoff"] = shipped["pipeline"][0]["handoff"]  # relative to another folder
check(r.returncode == 0 and written == shipped, "share/scenes/hillside_chain.json is what the tool writes")

# 2. Each facet's contact points (one per corner) share its area: stiffness x corners / area is the same everywhere.
cap = load("spherical_cap.json")
per_area, areas = [], []
for body in cap["bodies"][:-1]:
    vertices = body["shape"]["polyhedron"]["vertices"]
    corners = len(vertices) // 2
    areas.append(polygon_area([tuple(v) for v in vertices[:corners]]))
    per_area.append(body["contact"]["normal_stiffness"] * corners / areas[-1])
spread = max(per_area) / min(per_area) - 1.0
check(spread < 1e-5 and abs(per_area[0] / 1e9 - 1.0) < 1e-5 and max(areas) / min(areas) > 2.0,
      "joint stiffness 1e9 Pa/m on every facet (spread %.2g) while facet areas differ %.1f-fold"
      % (spread, max(areas) / min(areas)))

# 3. Volume against the smooth cap (abc pi h^2 (3 - h) / 3 on the unit ball): a turned, unequal ellipsoid cut by a
# tilted plane; errors fall four-fold per doubling of the facets.
ellipsoid = tool.Ellipsoid((3.0, -2.0, 30.0), (36.0, 24.0, 30.0), 25.0)
point, normal = (0.0, 0.0, 0.0), tool.unit((-0.8, 0.3, 1.0))
exact = tool.exact_cap_volume(ellipsoid, point, normal)
errors = []
for rings, segments in ((4, 16), (8, 32), (16, 64)):
    _, v = tool.slide_bodies(ellipsoid, point, normal, rings, segments, 0.125, 2000.0, 2300.0, 3e4, 30.0, 1e9)
    errors.append(abs(v / exact - 1.0))
    print("     %d x %d facets: volume %.2f m^3, smooth %.2f m^3, error %.3g %%" % (rings, segments, v, exact,
                                                                                   100 * errors[-1]))
orders = [math.log2(errors[k] / errors[k + 1]) for k in range(2)]
check(all(1.8 < p < 2.2 for p in orders), "volume converges at order 2 (%.2f, %.2f)" % tuple(orders))
check(errors[-1] < 5e-3, "16 x 64 facets within 0.5 %% of the smooth cap (%.3g %%)" % (100 * errors[-1]))

# 4. Frame invariance: the same configuration moved and turned about z has the same block volume.
turn, shift = math.radians(70.0), (1234.5, -876.0, 210.0)


def moved(p):
    return (p[0] * math.cos(turn) - p[1] * math.sin(turn) + shift[0],
            p[0] * math.sin(turn) + p[1] * math.cos(turn) + shift[1], p[2] + shift[2])


n_turned = (normal[0] * math.cos(turn) - normal[1] * math.sin(turn),
            normal[0] * math.sin(turn) + normal[1] * math.cos(turn), normal[2])
_, v0 = tool.slide_bodies(ellipsoid, point, normal, 8, 32, 0.125, 2000.0, 2300.0, 3e4, 30.0, 1e9)
other = tool.Ellipsoid(moved(ellipsoid.centre), ellipsoid.axes, 25.0 + 70.0)
_, v1 = tool.slide_bodies(other, moved(point), n_turned, 8, 32, 0.125, 2000.0, 2300.0, 3e4, 30.0, 1e9)
check(abs(v1 / v0 - 1.0) < 1e-9, "moved and turned: same volume (%.3g relative)" % abs(v1 / v0 - 1.0))

# 5. The seed's cap from a DEM of its planar face: the fitted face is z = x, the same blocks as the given plane.
cell, x0, y0 = 0.5, -20.0, -50.0
nc, nr = 200, 200
rows = [[min(max(x0 + (c + 0.5) * cell, 0.0), 40.0) for c in range(nc)] for _ in range(nr)]
dem = os.path.join(work, "cap_face.asc")
write_asc(dem, np.array(rows), x0, y0, cell)
from_dem, from_plane = os.path.join(work, "cap_dem.json"), os.path.join(work, "cap_plane.json")
r1 = run_tool("--dem", dem, "--ellipsoid", "0", "0", "40", "40", "40", "40", "--out", from_dem)
r2 = run_tool("--plane", "0", "0", "0", "-1", "0", "1", "--ellipsoid", "0", "0", "40", "40", "40", "40",
              "--out", from_plane)
with open(from_dem) as f:
    a = json.load(f)
with open(from_plane) as f:
    b = json.load(f)
gap = max(abs(p - q) for x, y in zip(a["bodies"], b["bodies"])
          for u, w in zip(x["shape"]["polyhedron"]["vertices"], y["shape"]["polyhedron"]["vertices"])
          for p, q in zip(u, w))
check(r1.returncode == 0 and r2.returncode == 0 and gap < 1e-6,
      "a face fitted to a planar DEM gives the plane's blocks (largest vertex gap %.3g m)" % gap)
check("departs from it by up to" in r1.stdout, "the fit's departure is printed")

# 6. Every block it writes is a valid convex polyhedron for talus.
v = subprocess.run([talus, "validate", hillside], capture_output=True, text=True)
check(v.returncode == 0, "talus validate accepts the written hillside scene")

# 7. A face that misses the ellipsoid is refused, nothing written.
missing = os.path.join(work, "missing.json")
r = run_tool("--plane", "0", "0", "100", "0", "0", "1", "--ellipsoid", "0", "0", "0", "10", "10", "10",
             "--out", missing)
check(r.returncode != 0 and "does not cut the ellipsoid" in r.stderr and not os.path.exists(missing),
      "a face that misses the ellipsoid is refused and nothing is written")

print("%d passed, %d failed" % (len(checks) - len(failures), len(failures)))
sys.exit(1 if failures else 0)
