"""Hard case: a Bingham layer on a 30 degree slope below its yield stress must stay at rest (issue 6: "yield stress
holds a slope without creep"), with the regularised plug's stiff viscous time-step limit."""
import math

import numpy as np

from verification.cases._util import frames, worst_density_deviation

HARD_CASE = True
NAME = "hard_yield_slope"
TITLE = ("Stiff yield stress: Bingham layer (tau_y = 1000 Pa, basal shear 294 Pa) at rest on a 30 degree slope, "
         "2D periodic, 1 s; ladder: Papanastasiou m = 5, 10, 20 s")
STRESSES = "yield stress far above the driving stress; viscous step limit h^2 rho / (tau_y m)"
SCENE = "share/verification/hard_yield_slope.json"
# The ladder stiffens the plug: the regularisation m (s) sets its viscosity mu_p + tau_y m, hence the explicit step
# (proportional to 1/m) and the creep the regularised model allows (proportional to 1/m).
LADDER = [5.0, 10.0, 20.0]
QUICK_INDEX = 0
QUICK_END = 0.3  # --quick: 0.3 s (~32 000 steps), many times the creep set-up time H^2 rho / (tau_y m) ~ 1e-3 s
WORST_LABEL = "max |rho/rho0 - 1| over the run"
# At rest the layer is compressed by rho g H / (rho0 c0^2) ~ 0.5 % (c0 = 10 m/s); 2 % catches a collapsing layer.
TOLERANCE = {5.0: 0.02, 10.0: 0.02, 20.0: 0.02}
RHO, G, THETA, H, DP = 1000.0, 9.81, math.radians(30.0), 0.06, 0.01
TAU_Y, MU_P = 1000.0, 0.1


def creep_speed(m):
    """Surface speed of the regularised plug: a Newtonian layer of viscosity mu_p + tau_y m under rho g sin(theta)."""
    return RHO * G * math.sin(THETA) * H**2 / (2 * (MU_P + TAU_Y * m))


def configure(scene, m, option):
    scene["materials"]["mud"]["rheology"]["regularisation"] = m
    return scene


def worst(run):
    return worst_density_deviation(run)


def creep(run):
    """(max over frames of the mean downslope speed of the top row, mean downslope displacement of the top row's
    particles from the first frame to the last (followed by id, unwrapped across the period), worst |v| of any
    particle in any frame)."""
    top_speed, worst_speed, first, last = 0.0, 0.0, None, None
    for _, f in frames(run):
        top = f["y"] > f["y"].max() - 0.5 * DP
        top_speed = max(top_speed, abs(float(np.mean(f["velocity_0"][top]))))
        worst_speed = max(worst_speed, float(np.max(np.hypot(f["velocity_0"], f["velocity_1"]))))
        if first is None:
            first = dict(zip(f["id"][top].tolist(), f["x"][top].tolist()))
        last = dict(zip(f["id"].tolist(), f["x"].tolist()))
    length = run.scene["domain"]["max"][0] - run.scene["domain"]["min"][0]
    moved = np.array([last[i] - x for i, x in first.items() if i in last])
    moved = (moved + 0.5 * length) % length - 0.5 * length
    return top_speed, float(np.mean(moved)) if moved.size else float("nan"), worst_speed


def gates(run):
    m = run.resolution
    uc = creep_speed(m)
    t = run.summary["time"]
    top_speed, displacement, worst_speed = creep(run)
    # Stated tolerance: the layer may creep no faster than 1.5 x the regularised model's own creep u_c (the plug's
    # finite viscosity, not a numerical error), and over the run no further than 1.5 u_c t + 0.05 dp.
    # A layer that yields moves at rho g sin(theta) H^2 / (2 mu_p) ~ 90 m/s scale: many orders above.
    disp_limit = 1.5 * uc * t + 0.05 * DP
    return [("reached the end", t >= run.scene["time"]["end"] * (1 - 1e-9), f"t = {t:.4g} s"),
            ("creep speed of the surface below 1.5 u_c (regularised creep)", top_speed <= 1.5 * uc,
             f"max surface speed {top_speed:.3g} m/s, u_c {uc:.3g} m/s, ratio {top_speed / uc:.3g}"),
            ("creep displacement below 1.5 u_c t + 0.05 dp", math.isfinite(displacement) and abs(displacement) <= disp_limit,
             f"surface moved {displacement * 1e3:.3g} mm downslope, limit {disp_limit * 1e3:.3g} mm "
             f"({abs(displacement) / H * 100:.3g} % of H)"),
            ("no particle faster than 10 u_c (no local yielding or noise bursts)", worst_speed <= 10 * uc,
             f"worst |v| {worst_speed:.3g} m/s"),
            ("no particle lost", run.summary.get("removed", 0) == 0, f"{run.summary.get('removed', 0)} removed")]
