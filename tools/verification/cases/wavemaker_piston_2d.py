"""Piston wavemaker, 2D: the wave height to stroke ratio H/S at two gauges against linear wavemaker theory.

Also holds the shared pieces of the wavemaker cases (dispersion relation, gauge records, first-harmonic fit) that
wavemaker_flap_2d imports.
"""
import math

import numpy as np

from verification.cases._util import read_csv, set_dp

NAME = "wavemaker_piston_2d"
TITLE = "Piston wavemaker, 2D, moving dynamic boundary particles: H/S against Biesel's linear theory"
SCENE = "share/scenes/wavemaker_piston_2d.json"
LADDER = [0.02, 0.2 / 15, 0.01]  # d/10, d/15, d/20 (d = 0.2 m)
# 10 %: linear theory at H/L = 0.017 (the first harmonic's Stokes correction is O((ka)^2) = 0.3 %; second-order
# free waves are at 2 omega, outside the fit), evanescent modes decay as exp(-k_1 x), k_1 h = 2.87 (< 1e-3 at
# x = 3 h), the start-up transient and the end-wall reflection (the linear solution for this paddle started at t = 0
# in this 4 m tank gives H/S over 3.0-5.0 s within 0.2 % of the steady value at both gauges, by
# tools/piston_startup.py and guarded by the tools_piston_startup tests; over 3.5-6.5 s the reflected faster,
# longer components already bias G2 by -3 %), and what
# remains is SPH: a dp-independent ~6 % deficit at generation (d/10..d/20) and the damping between the gauges
# (2 % at d/10, < 1 % at d/20 over 3 h = half a wavelength).
TOLERANCE = {LADDER[0]: 0.10, LADDER[1]: 0.10, LADDER[2]: 0.10}
# Measured (2026-11-22, 1 thread): H/S at G1 0.9335 / 0.9551 / 0.9515 (-8.0 / -5.9 / -6.3 %), at G2 -10.1 / -6.5 /
# -6.5 %, against 1.0151 at kh = 1.0365; d/20 took 16 min wall on a loaded machine.
ERROR_LABEL = "|H/S - theory| / theory, H = 2 x first-harmonic amplitude at gauge G1 (x = 3 h) over 3.0-5.0 s"
REFERENCE = ("linear wavemaker theory (Biesel & Suquet 1951; Dean & Dalrymple 1991, sec. 6.2): piston "
             "H/S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh), omega^2 = g k tanh kh")
# The error is set by the generation deficit, which does not fall from d/10 to d/20 (see above): it must stay
# within the tolerance, not fall.
CONVERGES = False
QUICK_INDEX = 0
G = 9.81
WINDOW = (3.0, 5.0)  # s: see the scene description and the tolerance note


def wavenumber(period, depth):
    """k of omega^2 = g k tanh(k h), by fixed-point iteration (converges for every kh)."""
    omega = 2.0 * math.pi / period
    k = omega * omega / G
    for _ in range(500):
        k = omega * omega / (G * math.tanh(k * depth))
    return k


def piston_ratio(kh):
    return 2.0 * (math.cosh(2 * kh) - 1.0) / (math.sinh(2 * kh) + 2 * kh)


def flap_ratio(kh):
    """Flap hinged at the bed, S = stroke at the still-water level."""
    return 4.0 * (math.sinh(kh) / kh) * (kh * math.sinh(kh) - math.cosh(kh) + 1.0) / (math.sinh(2 * kh) + 2 * kh)


def depth(scene):
    return float(scene["bodies"][0]["shape"]["box"]["max"][1] - scene["bodies"][0]["shape"]["box"]["min"][1])


def paddle(scene):
    return next(b for b in scene["bodies"] if b["name"] == "paddle")


def period(scene):
    motion = paddle(scene)["motion"]
    return float(next(iter(motion.values()))["period"])


def stroke(scene):
    """S: the paddle's horizontal excursion at the still-water level, peak to peak."""
    motion = paddle(scene)["motion"]
    if "sine" in motion:
        return 2.0 * motion["sine"]["amplitude"]
    hinge = motion["hinge"]
    return 2.0 * (depth(scene) - hinge["point"][1]) * math.sin(hinge["amplitude"])


def gauge_record(run):
    files = [f for f in run.output_files("probes") if f.endswith(".csv")]
    if not files:
        raise RuntimeError("the run wrote no probes output")
    return read_csv(files[-1])


def first_harmonic(t, eta, omega, window=WINDOW):
    """Amplitude of the component at omega of eta(t) over the window: least squares of
    a cos(omega t) + b sin(omega t) + c + d t (mean level and a slow drift removed)."""
    sel = (t >= window[0] - 1e-9) & (t <= window[1] + 1e-9)
    ts = t[sel]
    m = np.column_stack([np.cos(omega * ts), np.sin(omega * ts), np.ones_like(ts), ts - ts.mean()])
    coef, *_ = np.linalg.lstsq(m, eta[sel], rcond=None)
    return float(math.hypot(coef[0], coef[1]))


def measure(run):
    """kh, theory H/S, and per gauge H/S (first harmonic over the window and over its two halves)."""
    scene = run.scene
    d, T = depth(scene), period(scene)
    kh = wavenumber(T, d) * d
    theory = piston_ratio(kh) if "sine" in paddle(scene)["motion"] else flap_ratio(kh)
    rec = gauge_record(run)
    omega, S = 2 * math.pi / T, stroke(scene)
    out = {"kh": kh, "theory": theory, "S": S}
    mid = 0.5 * (WINDOW[0] + WINDOW[1])
    for g in ("G1", "G2"):
        t, eta = rec["time"], rec[g + "_elevation"]
        out[g] = 2 * first_harmonic(t, eta, omega) / S
        out[g + "_early"] = 2 * first_harmonic(t, eta, omega, (WINDOW[0], mid)) / S
        out[g + "_late"] = 2 * first_harmonic(t, eta, omega, (mid, WINDOW[1])) / S
    out["mass_drift"] = float(abs(rec["mass"][-1] / rec["mass"][0] - 1.0))
    out["removed"] = float(rec["removed"][-1])
    return out


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["time"]["end"] = WINDOW[1]
    return scene


def error(run):
    m = measure(run)
    return abs(m["G1"] / m["theory"] - 1.0)


def crest_kinematics(run):
    """The probes writer's crest speed (G1 -> G2) and fastest crest particle at G2, with linear theory's: the phase
    speed omega / k and the orbital velocity at the crest of the wave measured at G2, (H/2) omega cosh k(d + H/2) /
    sinh kd."""
    scene, r = run.scene, run.summary["results"]["probes"]
    d, T = depth(scene), period(scene)
    k, omega = wavenumber(T, d), 2 * math.pi / T
    a = 0.5 * r["surf_height"]
    return {"c": r["crest_speed"], "c_theory": omega / k, "u": r["crest_particle_speed"],
            "u_theory": a * omega * math.cosh(k * (d + a)) / math.sinh(k * d), "waves": r["kinematic_waves"]}


def within(value, theory, tolerance):
    return value is not None and abs(value / theory - 1.0) < tolerance


def speed(value):
    return "none" if value is None else f"{value:.4f} m/s"


def wave_gates(run):
    m = measure(run)
    crest = crest_kinematics(run)
    steady = max(abs(m[g + "_early"] / m[g + "_late"] - 1.0) for g in ("G1", "G2"))
    decay = m["G2"] / m["G1"]
    # H at the paddle with the decay G1 -> G2 undone (exponential decay, the gauges 3 h apart, G1 3 h from the paddle).
    at_paddle = m["G1"] * m["G1"] / m["G2"]
    return [
        ("gauge values", True, f"kh {m['kh']:.4f}, theory H/S {m['theory']:.4f}, G1 (x = 3 h) {m['G1']:.4f}, "
                               f"G2 (x = 6 h) {m['G2']:.4f}, G1^2/G2 (decay undone) {at_paddle:.4f}, S {m['S']:.4g} m"),
        ("steady waves in the window: H of its two halves within 10 %", steady < 0.10, f"{100 * steady:.1f} %"),
        ("wave decay from G1 to G2 (3 h = 0.5 L) below 10 %", 0.90 < decay < 1.05, f"H(G2)/H(G1) {decay:.3f}"),
        ("G2 within 15 % of theory", abs(m["G2"] / m["theory"] - 1.0) < 0.15,
         f"{100 * (m['G2'] / m['theory'] - 1.0):+.1f} %"),
        ("mass conserved, no particle removed", m["mass_drift"] < 1e-9 and m["removed"] == 0,
         f"drift {m['mass_drift']:.2g}, removed {m['removed']:.0f}"),
        # Linear theory to O((ka)^2) = 0.2 %; the paddle's free second harmonic (its own speed) moves each gauge's
        # crest by up to a few hundredths of a period, several % of the 0.5 T delay between the gauges.
        ("crest speed G1 -> G2 (probes waves section) within 10 % of linear theory's phase speed",
         within(crest["c"], crest["c_theory"], 0.10), f"{speed(crest['c'])} against {speed(crest['c_theory'])} "
                                                      f"({crest['waves']:.0f} crests)"),
    ]


def crest_particle_line(run):
    crest = crest_kinematics(run)
    return f"{speed(crest['u'])} against {speed(crest['u_theory'])}"


def gates(run):
    crest = crest_kinematics(run)
    # The top particles sit about dp/2 below the crest (-4 % at d/10), and the largest of the ~10 particles within a
    # kernel support carries the particles' velocity noise upward; the waves at G2 are steady in the window (their
    # crests' particle speeds within a few % of each other).
    return wave_gates(run) + [
        ("fastest crest particle at G2 within 15 % of linear theory's orbital velocity at the crest",
         within(crest["u"], crest["u_theory"], 0.15), crest_particle_line(run))]
