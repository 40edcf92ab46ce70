"""Still water in a tank for 20 s on each wall model: one, two and three layers of DBC particles, and mDBC."""
import math

import numpy as np

from verification.cases._hard_sph import scan
from verification.cases._util import last_frame, set_dp

NAME = "still_water_walls"
TITLE = "Still water, 2D tank 0.4 m deep, 20 s: DBC with 1, 2, 3 wall layers and mDBC"
SCENE = "share/scenes/hydrostatic_2d.json"
# dp = 0.01 would cost about 18 min per wall model (20 s at 270 000 steps).
LADDER = [0.04, 0.025, 0.02]
# The wall models compared (the full ladder sweeps them; --quick runs the default, mDBC).
OPTIONS = {"walls": ["dbc_1_layer", "dbc_2_layers", "dbc_3_layers", "mdbc"]}
ERROR_LABEL = "|free-surface level - analytic level| / dp after 20 s (interior columns)"
REFERENCE = ("mass conservation with the Tait EOS: the level h of the settled column, "
             "h = (1/g) int_0^{g rho0 H} dp / rho(p), H = 0.4 m")
# The gate: the free surface at rest within 0.1 dp of its analytic level.
TOLERANCE = {0.04: 0.1, 0.025: 0.1, 0.02: 0.1}
# The level's error is set by how the wall holds the bottom row (the gap) and the compressibility, not by
# the ladder: it must stay within 0.1 dp at every dp.
CONVERGES = False
END = 20.0
RHO0, G, H, WIDTH = 1000.0, 9.81, 0.4, 0.4
C0, GAMMA = 40.0, 7.0  # the scene's Tait EOS


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["time"]["end"] = END
    scene["outputs"] = [{"type": "hdf5", "every": 2.0, "fields": ["velocity", "density", "pressure", "mass"]}]
    walls = option.get("walls", "mdbc")
    wall = next(b for b in scene["bodies"] if b["kind"] == "wall")
    if walls == "mdbc":
        wall["boundary"]["method"] = "mdbc"
    else:
        wall["layers"] = int(walls.split("_")[1])
    return scene


def analytic_level():
    """Height of the settled column of mass rho0 H per unit area under the Tait EOS (midpoint rule, 1e-9 exact)."""
    b = RHO0 * C0 ** 2 / GAMMA
    bottom = RHO0 * G * H
    n = 20000
    pressures = (np.arange(n) + 0.5) * bottom / n
    density = RHO0 * (1.0 + pressures / b) ** (1.0 / GAMMA)
    return float(np.sum(1.0 / density) * bottom / n / G)


def _rows(run):
    """(dp, level, bottom-row height, floor pressure) of the last frame over the interior columns."""
    dp = run.scene["bodies"][0]["dp"]
    _, f = last_frame(run)
    x, y, p = f["x"], f["y"], f["pressure"]
    interior = (x > 3 * dp) & (x < WIDTH - 3 * dp)
    columns = np.round((x[interior] - 0.5 * dp) / dp).astype(int)
    ys = y[interior]
    tops = np.array([ys[columns == c].max() for c in np.unique(columns)])
    bottoms = np.array([ys[columns == c].min() for c in np.unique(columns)])
    lowest = interior & (y < bottoms.mean() + 0.5 * dp)
    # The bottom row's pressure carried down to the floor (y = 0) hydrostatically.
    floor = float(np.mean(p[lowest] + RHO0 * G * y[lowest]))
    return dp, float(tops.mean() + 0.5 * dp), float(bottoms.mean()), floor


def error(run):
    dp, level, _, _ = _rows(run)
    return abs(level - analytic_level()) / dp


def gates(run):
    dp, level, bottom, floor = _rows(run)
    outside, outside_t, _, _, bad = scan(run, [0.0, 0.0], [WIDTH, 1.0], axes=(0, 1))
    _, f = last_frame(run)
    speed = np.sqrt(f["velocity_0"] ** 2 + f["velocity_1"] ** 2)
    limit = 0.01 * math.sqrt(G * H)
    removed = run.summary.get("removed", 0)
    crossed = run.summary.get("wall_crossings", 0)  # found inside a wall and put back on its surface
    return [("reached the end", run.summary["time"] >= run.scene["time"]["end"] * (1 - 1e-9),
             f"t = {run.summary['time']:.4g} s"),
            ("no particle lost or through a wall (any frame)",
             removed == 0 and bad == 0 and outside == 0 and crossed == 0,
             f"{removed} removed, {bad} non-finite, {outside} outside, {crossed} put back from inside a wall" +
             (f" at t = {outside_t:.3g} s" if outside else "")),
            ("floor pressure within 2 % of rho0 g H", abs(floor / (RHO0 * G * H) - 1.0) <= 0.02,
             f"{floor / (RHO0 * G * H):.4f} rho0 g H (the bottom row's, carried to the floor); "
             f"fluid-wall gap at rest {bottom / dp:.3f} dp (bottom row above the floor; 0.5 on the fill lattice); "
             f"level {level:.5f} m vs {analytic_level():.5f} m"),
            ("at rest at the end: max |v| below 1 % of sqrt(gH)", float(speed.max()) < limit,
             f"max |v| {speed.max():.3g} m/s, limit {limit:.3g}")]
