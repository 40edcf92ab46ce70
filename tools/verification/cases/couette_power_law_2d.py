"""Plane Couette-Poiseuille flow of a power-law fluid: steady profile against the analytic solution."""
import numpy as np

from verification.cases._util import frames, last_frame, periodic_strip, row_averages, set_dp

NAME = "couette_power_law_2d"
TITLE = "Power-law Couette flow (moving lid + opposing body force), 2D, three-pass viscosity, moving DBC wall"
SCENE = "share/scenes/couette_power_law_2d.json"
LADDER = [1e-4, 5e-5, 2.5e-5]  # H/10, H/20, H/40
# The profile error has two parts: the discretisation (falls with dp) and a resolution-independent bias of
# about -1.2 % in the viscous operator from its regularisation eta^2 = 0.01 h^2 (sph/pair_loop.hpp), which the
# body-force part of this flow feels (the Couette part does not: its steady profile is independent of mu).
# 3 % at H/10 (10 particles across, two-sided kernel truncation), 1.5 % at H/20 and H/40.
TOLERANCE = {1e-4: 0.03, 5e-5: 0.015, 2.5e-5: 0.015}
ERROR_LABEL = "relative L2 of the steady row-averaged u_x(y) at t = 2.5 s (lid and body force both on)"
REFERENCE = ("analytic steady power-law Couette-Poiseuille flow: tau(y) = tau_w + rho |F| y, du/dy = (tau/K)^(1/n), "
             "tau_w from u(H) = U (n = 0.5, K = 3.162e-4 Pa s^0.5, U = 1e-4 m/s, F = -5e-5 m/s^2, H = 1 mm)")
EXPECTED_ORDER = 1.0
QUICK_INDEX = 1
RHO, H = 1000.0, 1e-3


def _params(scene):
    rheo = scene["materials"]["paste"]["rheology"]
    lid = next(b for b in scene["bodies"] if b["name"] == "lid")
    return (rheo["power_index"], rheo["consistency"], lid["motion"]["velocity"]["velocity"][0],
            scene["gravity"][0])


def analytic(y, n, k, u_lid, force):
    """Steady u(y) for a body force `force` opposing the lid (force * u_lid < 0), so tau > 0 throughout."""
    g = RHO * abs(force)
    e = (n + 1.0) / n

    def u_of(tau_w, yy):
        return n / ((n + 1.0) * g * k ** (1.0 / n)) * ((tau_w + g * yy) ** e - tau_w**e)

    lo, hi = 0.0, 1.0
    while u_of(hi, H) < u_lid:
        hi *= 2.0
    for _ in range(200):  # bisection for the wall stress tau_w
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if u_of(mid, H) < u_lid else (lo, mid)
    return u_of(0.5 * (lo + hi), np.asarray(y))


def configure(scene, dp, option):
    periodic_strip(set_dp(scene, dp), dp)
    scene["outputs"] = [{"type": "hdf5", "every": 0.25, "fields": ["velocity", "shear_rate", "mu_eff"]}]
    return scene


def _l2(run, f):
    y, u = row_averages(f, run.scene["bodies"][0]["dp"], f["velocity_0"])
    ua = analytic(y, *_params(run.scene))
    return float(np.sqrt(np.sum((u - ua) ** 2) / np.sum(ua**2)))


def error(run):
    _, f = last_frame(run)
    return _l2(run, f)


def gates(run):
    history = [(t, _l2(run, f)) for t, f in frames(run) if t > 0]
    t_end, f = last_frame(run)
    # Steady: the error moved by less than 1e-3 (a tenth of the finest tolerance) over the last output interval.
    steady = len(history) >= 2 and abs(history[-1][1] - history[-2][1]) < 1e-3
    gd = f["shear_rate"]
    return [("finite velocities", bool(np.all(np.isfinite(f["velocity_0"]))), f"L2 at t = {t_end:g} s: {history[-1][1]:.4g}"),
            ("steady (L2 changed < 1e-3 over the last 0.25 s)", bool(steady),
             ", ".join(f"t={t:g}: {e:.3g}" for t, e in history)),
            ("finite shear rate", bool(np.all(np.isfinite(gd))),
             f"min |D| {float(np.min(gd)):.3g} 1/s, max {float(np.max(gd)):.3g} 1/s (analytic 0.055 .. 0.154)")]
