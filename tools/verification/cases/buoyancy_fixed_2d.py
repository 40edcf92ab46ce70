"""Fixed submerged block (block_particles, plane slab): the fluid's force against rho g V."""
import math

import numpy as np

from verification.cases._util import last_frame

NAME = "buoyancy_fixed_2d"
TITLE = "Fixed submerged block (DBC block particles), plane slab: vertical force vs rho g V"
SCENE = "share/scenes/buoyancy_fixed_2d.json"
# 4, 5 and 10 particles across the block's 0.1 m height. At dp = 0.02 the block's top and bottom
# faces lie halfway between two rows of the fluid lattice (the case that measured +20 % before the
# fluid was fitted to the faces, plugins/coupling/fluid_fit.hpp); at 0.025 and 0.01 they lie on
# the lattice's cell faces.
LADDER = [0.025, 0.02, 0.01]
# The gate is 2 %. What remains is the DBC boundary's give: under the fluid's pressure the
# first fluid row settles about 0.05-0.1 dp into the block's particle layer (measured: the gap to
# the face falls from 0.5 dp to 0.42-0.5 dp), 2 x 0.1 dp / 0.1 m = 4 % at dp = 0.02 at worst: 4 % there
# (5 across, faces fitted), 3 % at 0.025 (4 across, faces on the lattice), the 2 % at 0.01.
# At dp = 0.02 the water's 0.35 m are 17.5 spacings, so the fluid is 18 rows 0.0194 m apart (a box keeps
# its faces). The force swings with a period of about 0.1 s, decaying: the window's halves differ by
# 1.003 % of rho g V (-1.52 % and -0.52 %), just outside the "settled" gate, while the mean is 1.0 % low.
# With 18 rows 0.02 m apart instead (the surface 1 cm high) the swing is three times larger and the
# mean 2.8 % low. The gate stays, and that rung is reported failing.
TOLERANCE = {0.025: 0.03, 0.02: 0.04, 0.01: 0.02}
ERROR_LABEL = "|F_z / (rho g V) - 1|, F_z averaged over every step of 0.1-0.3 s"
REFERENCE = ("Archimedes: rho g V, V = 0.2 x 0.1 m x slab width, rho the Tait density at the block's mid-depth "
             "(+0.36 % over rho0 at c0 = 20)")
# The error is set by where the faces fall on the fluid lattice (on a cell face at 0.025 and 0.01,
# halfway at 0.02, where the fit moves the fluid) as much as by dp: it must stay within the
# tolerance at every rung, not fall monotonically.
CONVERGES = False
RHO0, G, C0, GAMMA = 1000.0, 9.81, 20.0, 7.0
ROWS_Y = 7  # the periodic slab's width in particles (the neighbour search needs >= 2.5 support radii)
T0, T1 = 0.1, 0.3


def _width(scene):
    return scene["domain"]["max"][1] - scene["domain"]["min"][1]


def configure(scene, dp, option):
    width = ROWS_Y * dp
    scene["domain"]["max"][1] = width
    for body in scene["bodies"]:
        if body["kind"] in ("fluid", "wall"):
            body["dp"] = dp
        for key in ("box", "box_walls"):
            if key in body["shape"]:
                body["shape"][key]["max"][1] = width
    scene["time"]["end"] = T1
    return scene


def _block(scene):
    return next(b for b in scene["bodies"] if b["kind"] == "block")["shape"]["box"]


def reference(scene):
    box = _block(scene)
    level = next(b for b in scene["bodies"] if b["kind"] == "fluid")["shape"]["box"]["max"][2]
    depth = level - 0.5 * (box["min"][2] + box["max"][2])
    b = RHO0 * C0 * C0 / GAMMA
    rho = RHO0 * (1.0 + RHO0 * G * depth / b) ** (1.0 / GAMMA)
    volume = np.prod(np.asarray(box["max"]) - np.asarray(box["min"]))
    return rho * G * volume


def force_record(run):
    path = run.output_files("probes")[-1]
    with open(path) as f:
        rows = [line for line in f if not line.startswith("#")]
    names = rows[0].strip().split(",")
    data = np.array([[float(v) for v in line.split(",")] for line in rows[1:]])
    return data[:, names.index("time")], data[:, names.index("block_fz")], data[:, names.index("block_fx")], \
        data[:, names.index("mass")]


def mean_force(run):
    t, fz, _, _ = force_record(run)
    window = (t >= T0) & (t <= T1)
    return float(fz[window].mean())


def error(run):
    return abs(mean_force(run) / reference(run.scene) - 1.0)


def gates(run):
    t, fz, fx, mass = force_record(run)
    ref = reference(run.scene)
    window = (t >= T0) & (t <= T1)
    half = int(window.sum()) // 2
    first, second = fz[window][:half].mean(), fz[window][half:].mean()
    _, frame = last_frame(run)
    inside = ((frame["x"] > 0.1) & (frame["x"] < 0.3) & (frame["z"] > 0.15) & (frame["z"] < 0.25)).sum()
    return [
        ("settled: the two halves of the window agree within 1 % of rho g V", bool(abs(first - second) < 0.01 * ref),
         f"{100 * (first / ref - 1):+.2f} % / {100 * (second / ref - 1):+.2f} %"),
        ("no horizontal force (symmetric block)", bool(abs(fx[window].mean()) < 1e-3 * ref),
         f"mean F_x {fx[window].mean():.2e} N"),
        ("fluid mass conserved", bool(abs(mass[-1] / mass[0] - 1.0) < 1e-12), f"{mass[-1] / mass[0] - 1:.1e}"),
        ("no fluid particle inside the block", int(inside) == 0, f"{int(inside)} inside"),
    ]
