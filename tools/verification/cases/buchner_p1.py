"""2D dam break against a wall: pressure at sensor P1 against Buchner (2002).

Set-up of Marrone et al. (2011, CMAME 200): a column H = 0.6 m high and 2H long released in a tank 5.366H long;
P1 sits on the downstream wall at y = 0.2H (the reference file's header). The water SPH issue asks for the impact
time within 10 % and the pressure within 25 %.

What is measured, and why: P1 is a *wall* sensor (probes writer "wall_sensors"): the normal pressure force the
fluid exerts on the wall particles behind the sensor, divided by the sensor's area, i.e. the load a transducer in
the wall carries. The fluid pressure interpolated next to a wall of dynamic boundary particles is not that load:
after the impact the first wall layer holds the fluid off at a gap of 1.5-2 dp with its own pressure (4-6 rho g H at
dp = H/30), and the fluid pressure within a kernel support of the wall falls short of the load. Measured at
dp = H/30, plateau over t sqrt(g/H) in [4, 5]: fluid Shepard average dp/2 in front of the wall 0.33, 1.5 dp 0.38,
2.5 dp 0.52; wall sensor 0.51 (measured 0.54). The wall-particle pressure itself is no sensor for this boundary
model (it is a repulsion pressure, not the fluid's).

error(): relative error of the mean pressure over t sqrt(g/H) in [4, 5] (the quasi-steady plateau after the
run-up has fallen back, before the overturning jet returns near 5.5); a gate holds the impact time (first
p > 0.25 rho g H, above the +-0.16 noise of the measurement before the impact) within 10 %. A gate holds the impact
peak (largest 0.05 s running mean of the load over 2 < t sqrt(g/H) < 4; 0.05 s spans the whole measured rise, so it
filters the acoustic ringing of a weakly compressible model, not the impact) within 25 % of the measured maximum
0.69, at H/60 and finer: at H/20-H/40 the dynamic-boundary wall overshoots the peak by 11-60 % (reported there,
not gated); from H/60 on the peak is in the band (+1, -1, -11 % at H/60, H/80, H/120).

Measured (wall sensor; plateau 0.541 measured; impact 2.512 measured; wall time on a 2-core machine, two rungs side by
side at 1 thread each):
  dp = H/20: plateau 0.551 (+1.9 %), impact 2.734 (+8.8 %), fluid probe 0.113, peak (0.05 s mean) 0.82,    5 s
  dp = H/30: plateau 0.522 (-3.6 %), impact 2.774 (+10.4 %, fails the gate), fluid probe 0.287, peak 1.11, 16 s
  dp = H/40: plateau 0.574 (+6.2 %), impact 2.580 (+2.7 %), fluid probe 0.361, peak 0.77,                39 s
  dp = H/60: plateau 0.595 (+10.0 %), impact 2.733 (+8.8 %), fluid probe 0.402, peak 0.70 (+1 %),      158 s
  dp = H/80: plateau 0.590 (+9.2 %), impact 2.515 (+0.1 %), fluid probe 0.414, peak 0.68 (-1 %),       313 s
  dp = H/120: plateau 0.610 (+12.8 %), impact 2.685 (+6.9 %), fluid probe 0.449, peak 0.61 (-11 %),    908 s
The first crossing of 0.25 is a fragile measure at the coarse rungs: the run-up reaches the sensor as a thin,
noisy layer. At H/30, moving the far wall by 0.4 to 1.6 mm (0.02-0.08 dp; tank lengths 3.2180-3.2210 m) moves it
between t sqrt(g/H) = 2.701 and 2.774 (+7.5 to +10.4 %) and the raw peak between 1.5 and 4.9 rho g H; the scene's
tank (3.2196 m, the far wall on its face) gives the late end, 3.2200 m the early one. The gate stays at the issue's
10 %, and that rung fails it.
The tank is 4 m high: the run-up jet passes 3H at H/120 and, in a 3H tank, left over the open top (5 particles).
The peak settles near 0.61, 11 % under the measured 0.69 and the published delta-SPH's 0.67-0.70.
The rise itself is slower than measured (0.05 s mean at H/40: 0.10 at t sqrt(g/H) = 2.6, 0.49 at 3.0, 0.67 at 3.2;
at H/80: 0.33 at 2.7, 0.51 at 2.8, 0.43 at 2.9; measured 0.60-0.69 over 2.63-2.74; the delta-SPH of Marrone et al.
2011 at H/40-H/320 reaches 0.6 at 2.73-2.76, as digitised in TrixiParticles.jl's validation data). A wall whose
pressure is extrapolated from the fluid at every evaluation (Adami et al. 2012, eq. 27; tried, not adopted) removes
the gap: the fluid probe then reads the wall load (0.50 and 0.50 at H/30) and the plateau is 0.49-0.52 at H/20-H/40.
But it misses the impact: the load reaches 0.4-0.5 only at t sqrt(g/H) = 3.0-3.8 (and swings negative before that
when the fluid-wall pressure term may only push), and fluid particles crossed the wall surface of the tank: 1, 10
and 66 at H/20, H/30, H/40 with the published form, 2-3 with the push-only term (at most 0.2 dp beyond the surface).
The sensor height matters: Adami et al. (2012) and TrixiParticles centre P1 at ~0.26H (Greco's shift); there the
wall sensor reads 0.529 at H/30 (0.2H: 0.511).
"""
import math
import os

import numpy as np

from verification.cases._util import read_csv, set_dp

NAME = "buchner_p1"
TITLE = "2D dam break against a wall (Buchner 2002), wall pressure at P1 (y = 0.2H)"
SCENE = "share/scenes/dam_break_2d_buchner.json"
LADDER = [0.03, 0.02, 0.015, 0.01, 0.0075, 0.005]  # H/20, H/30, H/40, H/60, H/80, H/120
TOLERANCE = {0.03: 0.25, 0.02: 0.25, 0.015: 0.25, 0.01: 0.25, 0.0075: 0.25, 0.005: 0.25}
ERROR_LABEL = "|mean p_P1 - mean p_exp| / mean p_exp over t sqrt(g/H) in [4, 5] (wall sensor)"
REFERENCE = "Buchner (2002) P1, digitised in pypr/pysph (share/validation-data/dambreak2d_buchner2002_P1_pysph.csv)"
# The plateau's error is set by the measurement's scatter and the wall model's load noise, not by dp along this
# ladder: it must stay within 25 %, not fall (5-11 % on every rung, without a trend).
CONVERGES = False
QUICK_INDEX = 0
G, H, RHO0, LENGTH = 9.81, 0.6, 1000.0, 3.2196
SENSOR_Y = 0.2 * H
PLATEAU = (4.0, 5.0)
IMPACT_LEVEL = 0.25  # p / (rho g H)
SAMPLE_EVERY = 0.002  # s, the probes' output interval
PEAK_MEAN = 0.05  # s, the running mean the impact peak is taken over
IMPACT_WINDOW = (2.0, 4.0)  # t sqrt(g/H) in which the impact peak is sought
PEAK_TOLERANCE = 0.25
PEAK_GATED_FROM = 0.01  # dp = H/60: the coarser rungs' wall overshoot is reported, not gated
DATA = os.path.join(os.path.dirname(__file__), "..", "..", "..", "share", "validation-data",
                    "dambreak2d_buchner2002_P1_pysph.csv")


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["time"]["end"] = 7.0 * math.sqrt(H / G)
    scene["outputs"] = [{"type": "probes", "every": SAMPLE_EVERY, "file": "p1.csv",
                         "wall_sensors": [[LENGTH, SENSOR_Y]], "wall_sensor_normals": [[-1, 0]],
                         "wall_sensor_names": ["P1"],
                         "points": [[LENGTH - 0.5 * dp, SENSOR_Y]], "point_names": ["P1_fluid"],
                         "fields": ["pressure"], "integrals": ["particles", "removed"]}]
    if option:
        scene["pipeline"][0].update(option)
    return scene


def measured():
    """(t sqrt(g/H), p / (rho g H)) of the measurement, sorted by time."""
    rows = read_csv(DATA)
    t, p = rows["t_star"], rows["p_over_rhogH"]
    order = np.argsort(t, kind="stable")
    return t[order], p[order]


def simulated(run, column="P1_pressure"):
    files = [f for f in run.output_files("probes") if f.endswith("p1.csv")]
    rows = read_csv(files[0])
    return rows["time"] * math.sqrt(G / H), rows[column] / (RHO0 * G * H)


def plateau(t, p):
    """Time mean over PLATEAU of a series (linear between samples: the digitised points are uneven)."""
    grid = np.linspace(PLATEAU[0], PLATEAU[1], 201)
    return float(np.mean(np.interp(grid, t, np.nan_to_num(p))))


def impact_time(t, p):
    above = np.nonzero(np.nan_to_num(p) > IMPACT_LEVEL)[0]
    return float(t[above[0]]) if len(above) else float("nan")


def error(run):
    return abs(plateau(*simulated(run)) - plateau(*measured())) / plateau(*measured())


def in_impact_window(t):
    return (t > IMPACT_WINDOW[0]) & (t < IMPACT_WINDOW[1])


def peak(t, p):
    """Largest PEAK_MEAN running mean over IMPACT_WINDOW of a simulated series (sampled every SAMPLE_EVERY)."""
    samples = round(PEAK_MEAN / SAMPLE_EVERY)
    smooth = np.convolve(np.nan_to_num(p), np.ones(samples) / samples, mode="same")
    return float(smooth[in_impact_window(t)].max())


def gates(run):
    t, p = simulated(run)
    te, pe = measured()
    ti, tie = impact_time(t, p), impact_time(te, pe)
    fluid = plateau(*simulated(run, "P1_fluid_pressure"))
    simulated_peak, measured_peak = peak(t, p), float(pe[in_impact_window(te)].max())
    peak_error = (simulated_peak - measured_peak) / measured_peak
    peak_gated = run.resolution <= PEAK_GATED_FROM * (1 + 1e-9)
    return [("impact time within 10 % (first p > 0.25 rho g H)", abs(ti - tie) <= 0.10 * tie,
             f"t sqrt(g/H) = {ti:.3f} vs {tie:.3f} measured ({(ti - tie) / tie:+.1%}); plateau {plateau(t, p):.3f} "
             f"vs {plateau(te, pe):.3f}, fluid probe dp/2 off the wall {fluid:.3f}"),
            (f"impact peak ({PEAK_MEAN} s mean) within {PEAK_TOLERANCE:.0%} of the measured maximum"
             + ("" if peak_gated else " (not gated at this rung)"),
             bool(not peak_gated or abs(peak_error) <= PEAK_TOLERANCE),
             f"{simulated_peak:.2f} vs {measured_peak:.2f} ({peak_error:+.0%})"),
            ("no particle lost", run.summary.get("removed", 0) == 0, f"{run.summary.get('removed', 0)} removed")]
