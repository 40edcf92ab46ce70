"""2D dam break: surge front against Martin & Moyce (1952)."""
import math
import os

import numpy as np

from verification.cases._util import frames, set_dp

NAME = "martin_moyce_front"
TITLE = "2D dam break (column height 2a), surge front against Martin & Moyce (1952)"
SCENE = "share/scenes/dam_break_2d_martin_moyce.json"
LADDER = [0.005, 0.0035, 0.0025]
# The two measured column sizes differ by about 7 %: that spread is the tolerance.
TOLERANCE = {0.005: 0.07, 0.0035: 0.07, 0.0025: 0.07}
KNOWN_DEVIATION = ("the simulated front leads the measurements by a nearly constant time offset (9 % mean "
                   "deviation at dp = a/20, 12 % at a/40, growing with resolution); the front speed is within "
                   "the measured spread. The experiment's gate release is the likely cause; the water SPH issue "
                   "stays open on this point.")
ERROR_LABEL = "mean |Z_sim - Z_exp| / Z_exp over the measured points with T <= 3 (both column sizes)"
REFERENCE = "Martin & Moyce (1952) Fig. 3, n^2 = 2, a = 1.125 in and 2.25 in (shared/validation-data)"
A, G = 0.1, 9.81
OPTIONS = {"density_diffusion": ["fourtakas", "molteni"]}
DATA = os.path.join(os.path.dirname(__file__), "..", "..", "..", "..", "shared", "validation-data")


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["outputs"] = [{"type": "hdf5", "every": 0.005, "fields": ["velocity"]}]
    scene["time"]["end"] = 3.2 / math.sqrt(2 * G / A)
    if option:
        scene["pipeline"][0].update(option)
    return scene


def measured():
    points = []
    for name in ("dambreak_martin_moyce1952_n2eq2_a1.125in.csv", "dambreak_martin_moyce1952_n2eq2_a2.25in.csv"):
        with open(os.path.join(DATA, name)) as f:
            rows = [line.split(",") for line in f if line.strip() and not line.startswith("#")]
        data = [(float(t), float(z)) for t, z in rows[1:]]  # first row: the header
        points += [(t, z) for t, z in data if t <= 3.0]
    return np.array(points)


def front_history(run):
    t, z = [], []
    for time, f in frames(run):
        t.append(time * math.sqrt(2 * G / A))
        z.append(f["x"].max() / A)
    return np.array(t), np.array(z)


def error(run):
    T, Z = front_history(run)
    data = measured()
    simulated = np.interp(data[:, 0], T, Z)
    return float(np.mean(np.abs(simulated - data[:, 1]) / data[:, 1]))


def gates(run):
    T, Z = front_history(run)
    t = T / math.sqrt(2 * G / A)
    ritter = 1.0 + 2.0 * math.sqrt(G * 2 * A) * t / A
    return [("never faster than Ritter's front 2 sqrt(gH)", bool(np.all(Z <= ritter + 1e-9)),
             f"max Z - Z_Ritter {np.max(Z - ritter):.3g}")]
