"""Mangeney et al. (2000) Coulomb dam break on an incline with the depth-integrated SPH stage."""
import math

import numpy as np

from verification.cases._util import last_frame, set_dp
from verification.cases.ritter_dam_break import front_gate

NAME = "mangeney_dam_break"
TITLE = "Mangeney Coulomb dam break on a 30 degree incline (depth-integrated SPH, friction angle 20 degrees)"
SCENE = "share/verification/mangeney_dam_break.json"
LADDER = [0.2, 0.1, 0.05]
# Particle-wise relative L1 of the slope-normal depth on s in [-2, 7.5] (along the slope) at t = 1 s; the issue
# asks for 5 %, held at every rung. Measured 3.0 %, 1.2 %, 1.1 % (dp 0.2, 0.1, 0.05). Front gate (furthest
# particle within 2 l of the analytic front, along the slope): gaps of 1.51, 1.57, 1.63 l measured.
TOLERANCE = {0.2: 0.05, 0.1: 0.05, 0.05: 0.05}
ERROR_LABEL = "relative L1 of the slope-normal depth over the particles on s in [-2, 7.5] (t = 1 s)"
REFERENCE = ("Mangeney et al. (2000) J. Geophys. Res. 105(B9): h = (2 c0 - s/t + m t/2)^2 / (9 g cos theta), "
             "c0 = sqrt(g h0 cos theta), m = g sin theta - g cos theta tan delta; front 2 c0 t + m t^2 / 2 = 6.736 m")
EXPECTED_ORDER = 1.0
G, H0 = 9.81, 1.0
THETA, DELTA = math.radians(30.0), math.radians(20.0)


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["domain"]["max"][1] = 60 * dp  # the strip: 60 particles across, periodic
    scene["bodies"][0]["shape"]["box"]["max"][1] = 60 * dp
    return scene


def mangeney(s, t):
    gc = G * math.cos(THETA)
    c0 = math.sqrt(gc * H0)
    m = G * math.sin(THETA) - gc * math.tan(DELTA)
    shift = 0.5 * m * t * t
    h = np.where(s <= -c0 * t + shift, H0, (2 * c0 - s / t + 0.5 * m * t) ** 2 / (9 * gc))
    return np.where(s >= 2 * c0 * t + shift, 0.0, h)


def front(t):
    gc = G * math.cos(THETA)
    return 2 * math.sqrt(gc * H0) * t + 0.5 * (G * math.sin(THETA) - gc * math.tan(DELTA)) * t * t


def error(run):
    t, f = last_frame(run)
    s, h = f["x"] / math.cos(THETA), f["depth"]
    mask = (s >= -2.0) & (s <= 7.5)
    exact = mangeney(s[mask], t)
    return float(np.abs(h[mask] - exact).sum() / exact.sum())


def gates(run):
    t, f = last_frame(run)
    h = f["depth"]
    c = math.cos(THETA)
    # Along the slope: plan x and the plan smoothing length divided by cos theta.
    return [("no negative or non-finite depth", bool(np.all(np.isfinite(h)) and np.all(h >= 0)), f"min h {h.min():.3g} m"),
            ("mass conserved", int(f["x"].size) == run.summary["fluid_particles"], f"{f['x'].size} particles"),
            front_gate(f["x"] / c, f["smoothing_length"] / c, front(t))]
