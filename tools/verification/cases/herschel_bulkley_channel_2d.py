"""Steady shear-thinning Herschel-Bulkley channel flow (hbp, n = 0.5): centre velocity, profile and plug width."""
import functools
import math

import numpy as np

from verification.cases._util import frames, last_frame, periodic_strip, row_averages, set_dp

NAME = "herschel_bulkley_channel_2d"
TITLE = "Herschel-Bulkley (n = 0.5) channel flow, 2D, hbp rheology, three-pass viscosity, dynamic boundary particles"
SCENE = "share/scenes/herschel_bulkley_channel_2d.json"
# The Bingham channel's set-up (body-force-driven plane Poiseuille flow between DBC plates with the extrapolated
# no-slip wall, harmonic pair viscosity, h = 1.5 dp) with tau_y = 3e-5 Pa (plug half-width s0 = 0.3 H),
# K = 2.5e-4 Pa s^0.5, n = 0.5 (wall shear rate 0.078 1/s, mu_eff 1.3e-3 Pa s there), m = 2000 s. The power-law
# floor min_shear_rate = 1e-3 1/s keeps K gd^(n-1) <= 7.9e-3 Pa s in the plug (the default 1e-6 would make it
# 0.25 Pa s and cut the viscous step h^2 rho/mu 4x); the reference below contains the floor, and it moves the
# regularised u_c by < 0.1 %. The plug viscosity tau_y m + 7.9e-3 = 0.068 Pa s bounds dt (~1.8e-5 s at L/20).
# Steady by t = 1 s at every rung (u_c changes < 0.05 % over the last 0.1 s).
# L/10, L/20, L/30, L/40, L/60. Measured 2026-11-22 (1 thread, t = 1 s): u_c error 40.6 %, 10.0 %, 3.75 %, 1.65 %,
# 0.25 % (order ~2-4.7), 9188 / 55305 / 129570 / 233402 / 531451 steps, 1.9 / 23 / 73 / 178 s CPU for the first
# four (harness wall on the loaded 2-core machine 4 / 47 / 152 / 260 / 1940 s). The SPH runs slow near the walls: the strain-rate pass sums fluid
# neighbours only, so in the kernel support next to the wall |D| is underestimated (first row at L/30: 0.054 vs
# 0.071 1/s exact) and mu_eff = K |D|^(n-1) + ... overestimated (+20 %). The 3 % is met from L/40 on
# (L/30: 3.75 %, allowed 5 % so that rung still catches regressions); L/10 and L/20 (10 and 20 particles
# across; the yielded layer H - s0 is 7 dp at L/20) carry no tolerance and must show the error falling.
LADDER = [1e-4, 5e-5, 3.3333e-5, 2.5e-5, 1.6667e-5]
TOLERANCE = {1e-4: float("nan"), 5e-5: float("nan"), 3.3333e-5: 0.05, 2.5e-5: 0.03, 1.6667e-5: 0.03}
# Profile relative L2 (against the exact regularised profile) and plug half-width, gated at the finest rung only,
# with the 3 %. Measured: L2 44.4 %, 13.2 %, 5.80 %, 3.07 %, 1.11 %; plug width (EPS = 0.05) 31.5 %,
# 13.7 %, 7.3 %, 4.8 %, 2.5 % narrow. Both need L/60: the near-wall |D| error above shapes the whole yielded layer
# and the profile is flat at the plug edge, u_c - u ~ (s - s0)^3, so a small shape error moves the width a lot
# (a velocity gradient that sees the wall would likely meet 3 % sooner).
L2_TOL, W_TOL = 0.03, 0.03
ERROR_LABEL = "relative error of the steady centre (plug) velocity against the exact regularised (same m) solution"
REFERENCE = ("steady regularised Herschel-Bulkley plane Poiseuille flow by quadrature: rho F s = tau_y (1 - "
             "exp(-m gd)) + K max(gd, gd_min)^(n-1) gd, u(s) = int_s^H gd ds; ideal HB: s0 = tau_y/(rho F), "
             "u_c = n/(n+1) (rho F H - tau_y)^((n+1)/n) / (rho F K^(1/n)) (regularised u_c +0.89 % from it)")
QUICK_INDEX = 0  # L/10 (2 s CPU): no rung below L/30 carries a tolerance, so --quick checks the run and gates only
RHO, F, L = 1000.0, 2e-4, 1e-3
H = L / 2
# Plug edge from the velocity profile: the half-width of the region where u >= (1 - EPS) u_c, computed alike on
# the SPH rows and on the exact regularised profile (and given for the ideal HB profile and s0). EPS = 0.05 is
# about the smallest at which the regularised and ideal widths agree within 3 % (0.271 vs 0.279 mm; at 0.02
# 0.229 vs 0.245 mm, the regularised plug's creep): the measure then stands for the HB plug, not for m. It is
# not s0 itself: the ideal profile reaches u_c only at s0 with zero slope of order (n+1)/n = 3, so any
# velocity threshold lies outside s0 (s0 + (H - s0) EPS^(n/(n+1)) = 0.279 mm vs s0 = 0.15 mm).
EPS = 0.05


def _law(scene):
    r = scene["materials"]["paste"]["rheology"]
    return r["yield_stress"], r["consistency"], r["power_index"], r["regularisation"], r["min_shear_rate"]


@functools.lru_cache(maxsize=8)
def regularised_profile(tau_y, k, n, m, gd_min, cells=4000):
    """(s, u(s)) on [0, H] of the law the hbp plugin computes, mu gd = tau_y (1 - exp(-m gd)) + K max(gd, gd_min)^(n-1)
    gd (monotonic in gd): gd(tau) by bisection at tau = rho F s, u(s) = int_s^H gd by the trapezoidal rule."""
    def stress(gd):
        return tau_y * -math.expm1(-m * gd) + k * max(gd, gd_min) ** (n - 1.0) * gd

    def shear_rate(tau):
        lo, hi = 0.0, 1.0
        while stress(hi) < tau:
            hi *= 2.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if stress(mid) < tau else (lo, mid)
        return 0.5 * (lo + hi)

    s = np.linspace(0.0, H, cells + 1)
    gd = np.array([shear_rate(RHO * F * x) for x in s])
    seg = 0.5 * (gd[1:] + gd[:-1]) * np.diff(s)
    return s, np.append(np.cumsum(seg[::-1])[::-1], 0.0)


def ideal_centre_velocity(tau_y, k, n):
    return n / (n + 1.0) * (RHO * F * H - tau_y) ** ((n + 1.0) / n) / (RHO * F * k ** (1.0 / n))


def ideal_plug_width(tau_y, n, eps=None):
    """Ideal HB: s0 = tau_y/(rho F); with eps, the half-width where u = (1 - eps) u_c, since
    (u_c - u)/u_c = ((s - s0)/(H - s0))^((n+1)/n) outside the plug."""
    s0 = tau_y / (RHO * F)
    return s0 if eps is None else s0 + (H - s0) * eps ** (n / (n + 1.0))


def configure(scene, dp, option):
    periodic_strip(set_dp(scene, dp), dp)
    scene["outputs"] = [{"type": "hdf5", "every": 0.1, "fields": ["velocity", "shear_rate", "mu_eff"]}]
    return scene


def centre_velocity(y, u, dp):
    return float(u[np.abs(y - H) < 0.6 * dp].mean())


def half_width(s, u, uc, eps=EPS):
    """|s| where u first falls below (1 - eps) uc walking out from the centre (linear interpolation)."""
    order = np.argsort(s)
    s, u = s[order], u[order]
    target = (1.0 - eps) * uc
    k = int(np.argmax(u < target))
    if k == 0:
        return float("nan")
    return float(s[k - 1] + (u[k - 1] - target) * (s[k] - s[k - 1]) / (u[k - 1] - u[k]))


def sph_plug_width(y, u, dp):
    uc = centre_velocity(y, u, dp)
    widths = [half_width(np.abs(y[side] - H), u[side], uc) for side in (y < H, y > H)]
    return float(np.mean(widths))


def _measures(run, f):
    dp = run.scene["bodies"][0]["dp"]
    y, u = row_averages(f, dp, f["velocity_0"])
    s_ref, u_ref = regularised_profile(*_law(run.scene))
    ua = np.interp(np.abs(y - H), s_ref, u_ref)
    return {"uc": centre_velocity(y, u, dp), "uc_ref": float(u_ref[0]),
            "l2": float(np.sqrt(np.sum((u - ua) ** 2) / np.sum(ua**2))),
            "w": sph_plug_width(y, u, dp), "w_ref": half_width(s_ref, u_ref, u_ref[0])}


def error(run):
    m = _measures(run, last_frame(run)[1])
    return abs(m["uc"] / m["uc_ref"] - 1.0)


def gates(run):
    tau_y, k, n, _, _ = _law(run.scene)
    gated = run.resolution == LADDER[-1]
    history = [(t, _measures(run, f)["uc"]) for t, f in frames(run) if t > 0]
    t_end, f = last_frame(run)
    m = _measures(run, f)
    uc_ideal, s0 = ideal_centre_velocity(tau_y, k, n), ideal_plug_width(tau_y, n)
    w_ideal = ideal_plug_width(tau_y, n, EPS)
    w_err = abs(m["w"] / m["w_ref"] - 1.0)
    drift = abs(history[-1][1] / history[-2][1] - 1.0) if len(history) >= 2 else float("nan")
    note = "" if gated else " (not gated at this rung)"
    return [
        ("finite velocities", bool(np.all(np.isfinite(f["velocity_0"]))),
         f"t = {t_end:g} s: u_c SPH {m['uc']:.5g}, exact regularised {m['uc_ref']:.5g} "
         f"({m['uc_ref'] / uc_ideal - 1:+.2%} from ideal HB {uc_ideal:.5g}), "
         f"SPH {m['uc'] / uc_ideal - 1:+.2%} from ideal"),
        # Steady: u_c moved by less than a tenth of the 3 % tolerance over the last output interval.
        ("steady (u_c changed < 0.3 % over the last 0.1 s)", bool(drift < 3e-3),
         ", ".join(f"t={t:g}: {u:.4g}" for t, u in history)),
        (f"profile relative L2 <= {L2_TOL:g}{note}", bool(not gated or m["l2"] <= L2_TOL), f"L2 {m['l2']:.4g}"),
        (f"plug half-width (u >= (1 - {EPS:g}) u_c) within {W_TOL:g} of the regularised solution's{note}",
         bool(not gated or w_err <= W_TOL),
         f"SPH {m['w'] * 1e3:.4g} mm, exact regularised {m['w_ref'] * 1e3:.4g} mm ({w_err:.2%}), ideal HB at the same "
         f"eps {w_ideal * 1e3:.4g} mm, ideal plug s0 = tau_y/(rho F) {s0 * 1e3:.4g} mm"),
    ]
