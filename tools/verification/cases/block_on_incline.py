"""Explicit DDA: a block sliding down a 30 degree incline with phi = 20 degrees."""
import math

import numpy as np

NAME = "block_on_incline"
TITLE = "DDA block sliding on a 30 degree incline, friction angle 20 degrees"
SCENE = "share/scenes/block_on_incline.json"
# DDA has no particle spacing: the ladder refines the time step through the
# safety factor on dt < 2/omega_max.
LADDER = [0.8, 0.4, 0.2]
TOLERANCE = {0.8: 0.01, 0.4: 0.01, 0.2: 0.01}
ERROR_LABEL = "relative error of the sliding distance at t = 1 s"
REFERENCE = "d(t) = g (sin 30 - cos 30 tan 20) t^2 / 2 = 0.9064 m at 1 s"
G = 9.81


def configure(scene, safety, option):
    scene["pipeline"][0]["safety"] = safety
    scene["outputs"] = [{"type": "hdf5", "every": 0.5}]
    return scene


def displacement(run):
    with run.hdf5() as f:
        steps = sorted(f["Blocks"].keys(), key=lambda k: int(k[5:]))
        first, last = f["Blocks"][steps[0]], f["Blocks"][steps[-1]]
        names = [n.decode() if isinstance(n, bytes) else n for n in first["name"][...]]
        k = names.index("cube")
        moved = np.asarray(last["position"][k]) - np.asarray(first["position"][k])
        return float(np.linalg.norm(moved)), float(last.attrs["TimeValue"][0])


def error(run):
    d, t = displacement(run)
    theta, phi = math.radians(30), math.radians(20)
    exact = G * (math.sin(theta) - math.cos(theta) * math.tan(phi)) * t * t / 2
    return abs(d - exact) / exact
