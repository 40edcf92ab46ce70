"""Steady Bingham channel flow (Papanastasiou-regularised) against the analytic plug-flow solution."""
import numpy as np

from verification.cases._util import last_frame, periodic_strip, row_averages, set_dp
from verification.cases.herschel_bulkley_channel_2d import half_width, regularised_profile as hbp_profile

NAME = "bingham_channel_2d"
TITLE = "Bingham channel flow, 2D, three-pass non-Newtonian viscosity, dynamic boundary particles"
SCENE = "share/scenes/bingham_channel_2d.json"
# L/10, L/15, L/20. The plug's high regularised viscosity bounds dt by h^2 mu/rho: L/40 costs
# ~20 min on a 2-core machine, so the ladder stops at L/20, where the 3 % applies.
# The issue sets 3 % (at L/20 here); the coarser rungs, with 10 and 15 particles across the channel,
# cannot resolve the plug and carry no tolerance: they must only show the error falling.
# The scene uses the extrapolated no-slip wall and the harmonic pair viscosity. With the arithmetic mean the
# plug's regularised viscosity (100 mu_p) leaks into the yielded layer and u_c is 16 % low at L/20 (measured
# 2026-11-22); the old 2.4 % there was that error cancelled by the DBC wall's ~0.7 dp wider channel. With the
# harmonic mean u_c at L/20 is 1.021 x the ideal value, the exact regularised (m = 2000) solution being 1.020 x.
LADDER = [1e-4, 6.6667e-5, 5e-5]
TOLERANCE = {1e-4: float("nan"), 6.6667e-5: float("nan"), 5e-5: 0.03}
ERROR_LABEL = "relative error of the steady centre (plug) velocity"
REFERENCE = "analytic Bingham plane Poiseuille flow: s0 = tau_y/(rho F), u_c = rho F (H - s0)^2 / (2 mu_p)"
RHO, F, MU_P, TAU_Y, L = 1000.0, 2e-4, 1e-3, 5e-5, 1e-3
H = L / 2
S0 = TAU_Y / (RHO * F)
M = 2000.0  # the scene's Papanastasiou exponent (s)
# Plug width from the velocity profile, the measure of herschel_bulkley_channel_2d (there gated at L/40): the
# half-width where u >= (1 - EPS) u_c, on the SPH profile and on the exact regularised one alike (EPS = 0.05: the
# regularised and ideal widths differ by 4 % there, 10 % at 0.02 where the regularised plug's creep shows).
# Reported, not gated: measured 2026-11-22 33.8 %, 23.1 %, 16.9 % narrow at L/10, L/15, L/20 (order ~1.1: the
# kernel smooths the regularised viscosity's jump at the plug edge, which creeps; hbp_bingham_limit_2d follows the
# same width to L/60 and gates it there). 3 % would need rungs far beyond this ladder's cost. (The stress-based width it
# replaces, where mu_eff |D| = tau_y, read 14-30 % narrow: the regularised stress blurs the edge.)
EPS = 0.05
QUICK_INDEX = 2  # the rung that carries the tolerance


def analytic(y):
    s = np.abs(y - H)
    u = RHO * F * (H**2 - s**2) / (2 * MU_P) - TAU_Y * (H - s) / MU_P
    return np.where(s < S0, RHO * F * (H - S0) ** 2 / (2 * MU_P), u)


def configure(scene, dp, option):
    periodic_strip(set_dp(scene, dp), dp)
    scene["outputs"] = [{"type": "hdf5", "every": 0.2, "fields": ["velocity", "shear_rate", "mu_eff"]}]
    return scene


def profile(run):
    """Row averages (y, u, stress mu_eff |D|) of the last frame."""
    _, f = last_frame(run)
    return row_averages(f, run.scene["bodies"][0]["dp"], f["velocity_0"], f["mu_eff"] * f["shear_rate"])


def centre_velocity(run):
    y, u, _ = profile(run)
    return float(u[np.abs(y - H) < 0.6 * run.scene["bodies"][0]["dp"]].mean())


def regularised_profile():
    """(s, u(s)) of the exact steady solution of the scene's regularised law (bingham plugin: mu gd = tau_y (1 -
    exp(-m gd)) + mu_p gd, i.e. hbp with n = 1), by the quadrature of herschel_bulkley_channel_2d."""
    return hbp_profile(TAU_Y, MU_P, 1.0, M, 1.0)


def plug_half_width(run):
    """Half-width of the region where u >= (1 - EPS) u_c on the row-averaged profile (both halves averaged), the
    measure herschel_bulkley_channel_2d applies to the SPH and to the exact regularised profile alike."""
    y, u, _ = profile(run)
    uc = centre_velocity(run)
    return float(np.mean([half_width(np.abs(y[side] - H), u[side], uc, EPS) for side in (y < H, y > H)]))


def error(run):
    return abs(centre_velocity(run) / analytic(np.array([H]))[0] - 1.0)


def gates(run):
    y, u, _ = profile(run)
    ua = analytic(y)
    l2 = float(np.sqrt(np.sum((u - ua) ** 2) / np.sum(ua**2)))
    w = plug_half_width(run)
    s_ref, u_ref = regularised_profile()
    w_ref = half_width(s_ref, u_ref, u_ref[0], EPS)
    w_ideal = S0 + (H - S0) * EPS**0.5  # ideal Bingham: (u_c - u)/u_c = ((s - s0)/(H - s0))^2 outside the plug
    w_err = abs(w / w_ref - 1.0)
    return [("finite velocity profile", bool(np.isfinite(l2) and np.all(np.isfinite(u))),
             f"profile relative L2 {l2:.3g} against the ideal Bingham profile"),
            (f"plug half-width (u >= (1 - {EPS:g}) u_c), not gated", bool(np.isfinite(w)),
             f"SPH {w * 1e3:.4g} mm, exact regularised (m = {M:g} s) {w_ref * 1e3:.4g} mm ({w_err:.2%}), "
             f"ideal Bingham at the same eps {w_ideal * 1e3:.4g} mm, ideal plug s0 = tau_y/(rho F) {S0 * 1e3:.4g} mm")]
