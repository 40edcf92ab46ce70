"""Floating box (block_particles): the settled draft against Archimedes."""
import numpy as np

from verification.cases._util import block_frames, set_dp

NAME = "floating_box_draft"
TITLE = "Floating box of density 500 (DBC block particles): draft vs Archimedes"
SCENE = "share/scenes/buoyancy_floating.json"
# 5, 6.7 and 8 particles across the 0.2 m box. At 0.03 its side faces (0.2, 0.4 m) and its bottom all lie
# two thirds of a cell off the fluid lattice (phi = 2/3), at 0.04 only its bottom does (phi = 1/2), at 0.025
# none. The fluid is fitted to the faces, edges and corners (plugins/coupling/fluid_fit.hpp), and at 0.03 the
# block's particle lattice is stretched to 7 spacings of 0.0286 m across it (block_particles.cpp) so that it
# ends on the faces too. Before the fit reached the edges, a void of 626 cm3 (15.6 % of the displaced
# volume, all within dp/2 of the 8 submerged edges) stayed at 0.03 and the box floated 4.1 % high.
LADDER = [0.04, 0.03, 0.025]
# The issue's gate: the draft within 2 % of Archimedes' rho_b / rho_w x height (0.1 m).
TOLERANCE = {0.04: 0.02, 0.03: 0.02, 0.025: 0.02}
ERROR_LABEL = "|draft / (rho_b / rho_w H) - 1|, draft = still level - box bottom, mean over the last 40 %"
REFERENCE = "Archimedes: draft = rho_b / rho_w x H = 0.1 m for the 0.2 m box of density 500"
# The draft's error is set by the DBC layer's give and where the faces fall on the lattice, not
# only by dp (8 particles across at most): it must stay within 2 % at every rung.
CONVERGES = False
QUICK_INDEX = 0

LEVEL = 0.3  # the scene's still-water level (m)


def configure(scene, dp, option):
    set_dp(scene, dp)
    # The host fills rows of particles with centres (k + 1/2) dp <= the box's top: a level that is not a whole
    # number of rows (0.3 m at dp 0.04: 7.5) gets one more (0.32 m), and a box released at 0.1 m below the
    # nominal level then starts 0.02 m too deep and heaves for longer than the run. Round the level to whole
    # rows and release the box at rest at its Archimedes draft below it.
    level = dp * round(LEVEL / dp)
    next(b for b in scene["bodies"] if b["kind"] == "fluid")["shape"]["box"]["max"][2] = level
    block = next(b for b in scene["bodies"] if b["name"] == "box")
    box = block["shape"]["box"]
    height = box["max"][2] - box["min"][2]
    box["min"][2] = level - block["density"] / 1000.0 * height
    box["max"][2] = box["min"][2] + height
    scene["outputs"] = [{"type": "hdf5", "every": 0.02, "fields": ["density"], "xdmf": False}]
    return scene


def _heave(run):
    times, z, vertices = [], [], None
    for t, blocks in block_frames(run):
        box = next(b for b in blocks if b["name"] == "box")
        times.append(t)
        z.append(box["vertices"][:, 2].min())
        vertices = box
    return np.asarray(times), np.asarray(z), vertices


def _draft(run):
    t, bottom, box = _heave(run)
    height = box["vertices"][:, 2].max() - box["vertices"][:, 2].min()
    body = next(b for b in run.scene["bodies"] if b["name"] == "box")
    level = next(b for b in run.scene["bodies"] if b["kind"] == "fluid")["shape"]["box"]["max"][2]
    late = t > 0.6 * t[-1]
    return level - bottom[late].mean(), body["density"] / 1000.0 * height, t, bottom


def error(run):
    measured, expected, _, _ = _draft(run)
    return abs(measured / expected - 1.0)


def gates(run):
    measured, expected, t, bottom = _draft(run)
    late = t > 0.6 * t[-1]
    half = int(late.sum()) // 2
    drift = bottom[late][half:].mean() - bottom[late][:half].mean()
    return [("no drift: the two halves of the last 40 % agree within 1 % of the draft", bool(abs(drift) < 0.01 * expected),
             f"{drift * 1000:+.2f} mm"),
            ("heave bounded: |bottom - mean| < 10 % of the draft over the last 40 %",
             bool(np.abs(bottom[late] - bottom[late].mean()).max() < 0.1 * expected),
             f"{np.abs(bottom[late] - bottom[late].mean()).max() * 1000:.2f} mm")]
