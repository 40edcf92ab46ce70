"""Steady Bingham channel flow (Papanastasiou-regularised) against the analytic plug-flow solution."""
import numpy as np

from verification.cases._util import last_frame, set_dp

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
QUICK_INDEX = 2  # the rung that carries the tolerance


def analytic(y):
    s = np.abs(y - H)
    u = RHO * F * (H**2 - s**2) / (2 * MU_P) - TAU_Y * (H - s) / MU_P
    return np.where(s < S0, RHO * F * (H - S0) ** 2 / (2 * MU_P), u)


def configure(scene, dp, option):
    set_dp(scene, dp)
    # The periodic strip along x keeps 8 particles at every rung (it must span the kernel support).
    length = 8 * dp
    scene["domain"]["max"][0] = length
    for body in scene["bodies"]:
        next(iter(body["shape"].values()))["max"][0] = length
    scene["outputs"] = [{"type": "hdf5", "every": 0.2, "fields": ["velocity", "shear_rate", "mu_eff"]}]
    return scene


def profile(run):
    """Row averages (y, u, stress mu_eff |D|) of the last frame."""
    _, f = last_frame(run)
    y, u, tau = f["y"], f["velocity_0"], f["mu_eff"] * f["shear_rate"]
    dp = run.scene["bodies"][0]["dp"]
    rows = np.round(y / dp - 0.5).astype(int)
    ids = np.unique(rows)
    return (np.array([y[rows == r].mean() for r in ids]), np.array([u[rows == r].mean() for r in ids]),
            np.array([tau[rows == r].mean() for r in ids]))


def centre_velocity(run):
    y, u, _ = profile(run)
    return float(u[np.abs(y - H) < 0.6 * run.scene["bodies"][0]["dp"]].mean())


def plug_half_width(run):
    """|s| where the computed shear stress mu_eff |D| crosses tau_y (linear interpolation, both halves averaged)."""
    y, _, tau = profile(run)
    widths = []
    for side in (y < H, y > H):
        s, t = np.abs(y[side] - H), tau[side]
        order = np.argsort(s)
        s, t = s[order], t[order]
        k = np.argmax(t > TAU_Y)
        if k == 0:
            continue
        widths.append(s[k - 1] + (TAU_Y - t[k - 1]) * (s[k] - s[k - 1]) / (t[k] - t[k - 1]))
    return float(np.mean(widths)) if widths else float("nan")


def error(run):
    return abs(centre_velocity(run) / analytic(np.array([H]))[0] - 1.0)


def gates(run):
    y, u, _ = profile(run)
    ua = analytic(y)
    l2 = float(np.sqrt(np.sum((u - ua) ** 2) / np.sum(ua**2)))
    w = plug_half_width(run)
    return [("finite velocity profile", bool(np.isfinite(l2) and np.all(np.isfinite(u))),
             f"profile relative L2 {l2:.3g}; plug half-width {w:.4g} m vs {S0:.4g} m analytic, measured where "
             f"mu_eff |D| = tau_y (not gated: the regularised stress blurs the plug edge)")]
