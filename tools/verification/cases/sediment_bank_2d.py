"""Hard case: the coastline seed's water-sediment tank in 2D (share/scenes/sediment_bank_2d.json): sea water driven by a
piston over the seed's trapezoidal HBP sediment bank (Drucker-Prager yield on the effective pressure, capped plug
viscosity). Stability of both phases, no dispersion of sediment into the water, and yielding where the criterion
predicts: the bank's flanks (59.5 deg) are steeper than phi = 35 deg, so with c = 1 Pa the material above the
phi-lines through the toes must fail, while the core below those lines (the triangle of base angle phi) can hold."""
import math

import numpy as np

from verification.cases._util import cached, frames, worst_density_deviation

HARD_CASE = True
NAME = "sediment_bank_2d"
TITLE = ("Water over a sediment bank (coastline seed, 2D): piston waves, HBP sediment with Drucker-Prager yield on the "
         "effective pressure, plug viscosity capped at max_viscosity, 2 s")
STRESSES = "two phases (1029 / 1922 kg/m^3) with a 1e6 viscosity jump at the interface; a failing bank; piston waves"
SCENE = "share/scenes/sediment_bank_2d.json"
# One rung: the scene's dp (10 particles over the bank's height). The ladder is short: a hard case is about a stable
# two-phase run, not convergence.
LADDER = [0.0135]
QUICK_INDEX = 0
QUICK_END = 1.0
WORST_LABEL = "max |rho/rho0 - 1| over the run, both phases"
# Tait with c0 = 20 m/s and flow speeds <= 0.7 m/s: ~1 %; the interface instability of a density jump without the
# multiphase continuity term reaches 20-30 % within 0.3 s (measured 2026-11-22), so 3 % separates the two.
TOLERANCE = {0.0135: 0.03}

SEDIMENT, WATER = 1, 0  # material indices in the scene (declaration order)
RHO_W, C, PHI = 1029.0, 1.0, math.radians(35.0)


def yield_stress(p, rho):
    """Drucker-Prager yield stress of the hbp model on the effective pressure p (1 - rho_w / rho), p >= 0 (as in
    plugins/rheology/hbp_formula.hpp)."""
    t = math.tan(PHI)
    s = math.sqrt(9.0 + 12.0 * t * t)
    pe = np.maximum(p, 0.0) * (1.0 - RHO_W / rho)
    return math.sqrt(3.0) * (3.0 * C + pe * t) / s


def bank_toes(scene):
    """x of the bank's toes (the sediment bodies' extent along the floor)."""
    lo = min(b["shape"]["box"]["min"][0] for b in scene["bodies"] if b.get("material") == "sediment")
    hi = max(b["shape"]["box"]["max"][0] for b in scene["bodies"] if b.get("material") == "sediment")
    return lo, hi


def in_core(x, y, toes):
    """Below the phi-lines through both toes: the part of the bank the criterion lets stand."""
    return y < math.tan(PHI) * np.minimum(x - toes[0], toes[1] - x)


def isolated(x, y, mat, radius):
    """Sediment particles with fewer than 3 sediment neighbours within `radius` (carried off into the water)."""
    s = np.flatnonzero(mat == SEDIMENT)
    xs, ys = x[s], y[s]
    d2 = (xs[:, None] - xs[None, :]) ** 2 + (ys[:, None] - ys[None, :]) ** 2
    return int(np.sum((d2 < radius * radius).sum(axis=1) - 1 < 3))


@cached
def scan(run):
    """Per-run measures over all frames: yielded fractions in the core / outside it, core displacement, dispersion."""
    dp = run.scene["bodies"][0]["dp"]
    radius = 2 * run.scene["kernel"]["h_over_dp"] * dp
    toes = bank_toes(run.scene)
    start, core_ids, outer_ids = None, None, None
    ever_yielded, core_yield_worst, dispersed_worst, frames_n = set(), 0.0, 0, 0
    last = None
    for _, f in frames(run):
        mat, ids = f["material"], f["id"]
        s = mat == SEDIMENT
        if start is None:
            start = dict(zip(ids[s].tolist(), zip(f["x"][s].tolist(), f["y"][s].tolist())))
            core = in_core(f["x"][s], f["y"][s], toes)
            core_ids, outer_ids = set(ids[s][core].tolist()), set(ids[s][~core].tolist())
            continue
        frames_n += 1
        yielded = s & (f["mu_eff"] * f["shear_rate"] >= yield_stress(f["pressure"], f["density"]))
        ys = set(ids[yielded].tolist())
        ever_yielded |= ys
        core_yield_worst = max(core_yield_worst, len(ys & core_ids) / max(len(core_ids), 1))
        dispersed_worst = max(dispersed_worst, isolated(f["x"], f["y"], mat, radius))
        last = f
    s = last["material"] == SEDIMENT
    moved = [math.hypot(x - start[i][0], y - start[i][1])
             for i, x, y in zip(last["id"][s].tolist(), last["x"][s].tolist(), last["y"][s].tolist()) if i in core_ids]
    return {"core": len(core_ids), "outer": len(outer_ids),
            "outer_yielded": len(ever_yielded & outer_ids) / max(len(outer_ids), 1),
            "core_yield_worst": core_yield_worst, "core_moved": float(np.mean(moved)) / dp if moved else float("nan"),
            "dispersed_worst": dispersed_worst, "sediment_end": int(s.sum()), "sediment_start": len(start)}


def configure(scene, dp, option):
    return scene


def worst(run):
    return worst_density_deviation(run)


def gates(run):
    m = scan(run)
    t = run.summary["time"]
    return [("reached the end", t >= run.scene["time"]["end"] * (1 - 1e-9), f"t = {t:.4g} s"),
            ("no particle lost", run.summary.get("removed", 0) == 0 and m["sediment_end"] == m["sediment_start"],
             f"{run.summary.get('removed', 0)} removed, sediment {m['sediment_start']} -> {m['sediment_end']}"),
            # The criterion: tan(59.5 deg) > tan(phi) with c = 1 Pa, so (nearly) all of the material above the
            # phi-lines must yield at some time during the run. The core below the phi-lines should hold, but is
            # not gated: with max_viscosity = 2000 Pa s the yield shear rate tau_y / mu_max (~0.1 1/s) is below the
            # SPH velocity noise, so 27-88 % of it reads as yielded in some frame and it creeps ~1.5 dp (measured
            # 2026-11-22); holding it needs mu_max ~ 2e4 Pa s, 10x the steps. Issue 6 stays open on this.
            ("the flanks above the phi-lines yield (criterion predicts failure)", m["outer_yielded"] >= 0.8,
             f"{100 * m['outer_yielded']:.3g} % of {m['outer']} outer particles yielded at some frame; core (not "
             f"gated): worst frame {100 * m['core_yield_worst']:.3g} % of {m['core']} at yield, mean displacement "
             f"{m['core_moved']:.3g} dp"),
            ("no sediment dispersed into the water", m["dispersed_worst"] == 0,
             f"worst frame: {m['dispersed_worst']} sediment particles with < 3 sediment neighbours")]
