"""Ritter's dry-bed dam break with the depth-integrated SPH stage."""
import math

import numpy as np

from verification.cases._util import last_frame, set_dp

NAME = "ritter_dam_break"
TITLE = "Ritter dry-bed dam break (depth-integrated SPH, frictionless flat bed)"
SCENE = "share/verification/ritter_dam_break.json"
LADDER = [0.2, 0.1, 0.05]
# Particle-wise relative L1 of the depth on x in [-2, 5] at t sqrt(g/h0) = 2; the issue asks
# for 5 %, held at every rung. Measured 3.6 %, 1.7 %, 1.1 % (dp 0.2, 0.1, 0.05). The front (furthest
# particle within 2 l of 2 c0 t, see front_gate) is a gate: gaps of 1.50, 1.56, 1.63 l measured.
TOLERANCE = {0.2: 0.05, 0.1: 0.05, 0.05: 0.05}
ERROR_LABEL = "relative L1 of depth h(x) over the particles on x in [-2, 5] (t sqrt(g/h0) = 2)"
REFERENCE = "Ritter (1892) analytic solution h = (2 sqrt(g h0) - x/t)^2 / (9 g) in the fan"
EXPECTED_ORDER = 1.0
G, H0 = 9.81, 1.0


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["domain"]["max"][1] = 60 * dp  # the strip: 60 particles across, periodic
    scene["bodies"][0]["shape"]["box"]["max"][1] = 60 * dp
    return scene


def ritter(x, t):
    c0 = math.sqrt(G * H0)
    h = np.where(x <= -c0 * t, H0, (2 * c0 - x / t) ** 2 / (9 * G))
    return np.where(x >= 2 * c0 * t, 0.0, h)


def error(run):
    t, f = last_frame(run)
    x, h = f["x"], f["depth"]
    mask = (x >= -2.0) & (x <= 5.0)
    exact = ritter(x[mask], t)
    return float(np.abs(h[mask] - exact).sum() / exact.sum())


def front_gate(x, smoothing, exact_front):
    """The front is the furthest particle (the flow's extent: SPH puts no mass beyond it except through its
    kernel). The issue asks for it within 2 l of the analytic front, l the smoothing length of that particle
    (it follows the 1D spacing, l = 1.3 V / (dp sigma), unbounded in practice). The gap is set by the mass
    of one particle: the exact profile near the front holds only (x_f - x)^3 / (27 g t^2) of volume per unit
    width, so the leading particle's mass sits ~cbrt(V) behind the exact front (see the issue note)."""
    lead = int(np.argmax(x))
    gap = exact_front - float(x[lead])
    ell = float(smoothing[lead])
    return ("front: furthest particle within 2 l of the analytic front", abs(gap) <= 2.0 * ell,
            f"lead {x[lead]:.3f} m, exact {exact_front:.3f} m, gap {gap:.3f} m = {gap / ell:.2f} l (l {ell:.3f} m)")


def gates(run):
    t, f = last_frame(run)
    h = f["depth"]
    return [("no negative or non-finite depth", bool(np.all(np.isfinite(h)) and np.all(h >= 0)), f"min h {h.min():.3g} m"),
            ("mass conserved", int(f["x"].size) == run.summary["fluid_particles"], f"{f['x'].size} particles"),
            front_gate(f["x"], f["smoothing_length"], 2 * math.sqrt(G * H0) * t)]
