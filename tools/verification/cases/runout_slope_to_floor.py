"""Frictionless run-out from a 30 degree slope through a smooth transition onto the floor: the energy balance."""
import math

import numpy as np

from verification.cases._util import frames, periodic_strip, set_dp

NAME = "runout_slope_to_floor"
TITLE = "Frictionless strip from a 30 degree slope onto a flat floor through a 60 m transition (depth-integrated SPH)"
SCENE = "share/verification/runout_slope_to_floor.json"
LADDER = [1.0, 0.5, 0.25]
# The issue asks for the speed kept within 2 % through the transition. Energy is the exact statement of that for a
# frictionless flow: |E(t) - E(0)| over the kinetic energy once the whole strip is on the floor (2 % of the kinetic
# energy is 1 % of the speed, so this is stricter). Measured in the tests at dp 0.5: 0.09 %.
TOLERANCE = {1.0: 0.02, 0.5: 0.02, 0.25: 0.02}
ERROR_LABEL = "|E - E0| / kinetic energy, first frame with the whole strip on the floor"
REFERENCE = ("energy conservation without friction: kinetic (along the surface) + potential + 1/2 g cos(theta) h "
             "per unit mass")
G, RHO, FLOOR = 9.81, 2000.0, 90.0  # the floor starts at foot + transition / 2
CONVERGES = False  # the error is time-integration round-off far below the tolerance, not a resolution effect


def configure(scene, dp, option):
    return periodic_strip(set_dp(scene, dp), dp, axis=1)  # the strip across y, 8 spacings wide


def energies(f):
    """(kinetic, potential + hydrostatic) of a frame, J per the strip."""
    m = RHO * f["volume"]
    # cos(theta) from the terrain: 30 degrees on the slope, eased to 0 over [30, 90].
    x = f["x"]
    slope = np.where(x <= 30.0, math.tan(math.radians(30.0)),
                     np.where(x >= FLOOR, 0.0, math.tan(math.radians(30.0)) * (FLOOR - x) / 60.0))
    cos = 1.0 / np.sqrt(1.0 + slope * slope)
    return float(np.sum(0.5 * m * f["speed"] ** 2)), float(np.sum(m * G * (f["elevation"] + 0.5 * cos * f["depth"])))


def on_floor(run):
    """(E0, the first frame with every particle on the floor beyond a margin of three smoothing lengths)."""
    first, landed = None, None
    for t, f in frames(run):
        if first is None:
            first = f
        if np.min(f["x"]) > FLOOR + 6.0 and landed is None:
            landed = (t, f)
    return first, landed


def error(run):
    first, landed = on_floor(run)
    if landed is None:
        return float("inf")
    k0, p0 = energies(first)
    k, p = energies(landed[1])
    return abs(k + p - k0 - p0) / k


def gates(run):
    first, landed = on_floor(run)
    if landed is None:
        return [("the strip reaches the floor", False, "not on the floor by the end")]
    k0, p0 = energies(first)
    k, p = energies(landed[1])
    return [("the strip reaches the floor", True, f"t = {landed[0]:.3g} s"),
            ("speed kept within 2 % (kinetic energy / potential drop >= 0.96)", k / (p0 - p) >= 0.96,
             f"kinetic / drop {k / (p0 - p):.4f}"),
            ("no particle lost", landed[1]["x"].size == first["x"].size, f"{landed[1]['x'].size} particles")]
