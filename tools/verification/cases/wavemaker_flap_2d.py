"""Flap wavemaker hinged at the bed, 2D: the wave height to stroke ratio H/S against linear wavemaker theory."""
from verification.cases import wavemaker_piston_2d as piston

NAME = "wavemaker_flap_2d"
TITLE = "Flap wavemaker hinged at the bed, 2D, rotating dynamic boundary particles: H/S against Biesel's linear theory"
SCENE = "share/scenes/wavemaker_flap_2d.json"
LADDER = piston.LADDER  # d/10, d/15, d/20
# 10 %, as the piston (wavemaker_piston_2d.py): linear theory at H/L = 0.016, evanescent modes < 1e-3 at x = 3 h,
# start-up transient and end-wall reflection < 0.2 % in the window,
# SPH wave damping between paddle and gauge.
TOLERANCE = dict(piston.TOLERANCE)
# Measured (2026-11-22, 1 thread): H/S at G1 0.5104 / 0.5162 / 0.5257 (-7.0 / -5.9 / -4.2 %), at G2 -9.8 / -8.4 /
# -7.8 %, against 0.5486 at kh = 1.0365.
ERROR_LABEL = ("|H/S - theory| / theory, S at the still-water level, H = 2 x first-harmonic amplitude at gauge G1 "
               "(x = 3 h) over 3.0-5.0 s")
REFERENCE = ("linear wavemaker theory (Biesel & Suquet 1951; Dean & Dalrymple 1991, sec. 6.2): flap hinged at the bed "
             "H/S = 4 (sinh kh / kh) (kh sinh kh - cosh kh + 1) / (sinh 2kh + 2kh), omega^2 = g k tanh kh")
CONVERGES = piston.CONVERGES
QUICK_INDEX = 0


def configure(scene, dp, option):
    return piston.configure(scene, dp, option)


def error(run):
    return piston.error(run)


def gates(run):
    # Not gated: the one complete wave at G2 in the window is the flap's first, whose crest particles move about 20 %
    # faster than the next crest's at the same crest height (start-up), so steady linear theory is no reference.
    return piston.wave_gates(run) + [
        ("fastest crest particle at G2 (not gated: the window's one wave is a start-up wave)", True,
         piston.crest_particle_line(run))]
