"""Hard case: stiff DDA contact springs, a stack of three cubes settling on a fixed floor."""
import itertools

import numpy as np

from verification.cases._util import cached, block_energy, block_frames, penetration_depth

HARD_CASE = True
NAME = "hard_block_stack"
TITLE = ("Stiff contact springs: three 0.2 m cubes dropped 2 mm onto a floor and onto each other (explicit DDA, "
         "penalty-Coulomb); ladder: normal stiffness k_n = 1e8, 1e10, 1e12 N/m per contact point")
STRESSES = "penalty stiffness up to 1e12 N/m: explicit step dt < 2/omega_max, impacts, resting contact"
SCENE = "share/verification/hard_block_stack.json"
LADDER = [1e8, 1e10, 1e12]
QUICK_INDEX = 1
WORST_LABEL = "deepest block interpenetration over the run (frames every 0.01 s) [m]"
# Stated tolerance: 0.1 mm = 0.05 % of the edge. The impact from 2 mm (v = 0.2 m/s) at the softest rung compresses a
# spring by about v sqrt(m / (4 k)) ~ 5e-5 m; resting, the bottom cube's springs carry 60 kg: 1.5e-6 m.
TOLERANCE = {1e8: 1e-4, 1e10: 1e-4, 1e12: 1e-4}
EDGE, GAP = 0.2, 0.002


def configure(scene, stiffness, option):
    for body in scene["bodies"]:
        body["contact"]["normal_stiffness"] = stiffness
    scene["outputs"] = [{"type": "hdf5", "every": 0.01}]
    return scene


@cached
def scan(run):
    """(deepest interpenetration and its time, energy series (t, kinetic + potential), last frame's blocks)."""
    deepest, when, energy, last = 0.0, float("nan"), [], None
    gravity = run.scene.get("gravity", [0, 0, -9.81])
    for t, blocks in block_frames(run):
        for a, b in itertools.combinations(blocks, 2):
            d = penetration_depth(a, b)
            if d > deepest:
                deepest, when = d, t
        kinetic, potential = block_energy(blocks, gravity)
        energy.append((t, kinetic + potential))
        last = blocks
    return deepest, when, energy, last


def worst(run):
    return scan(run)[0]


def gates(run):
    deepest, when, energy, last = scan(run)
    e0 = energy[0][1]
    growth = max(e - e0 for _, e in energy)
    free = [b for b in last if not b["fixed"]]
    # Energy scale: the work gravity can do over the gaps, sum m g (gaps below the block).
    scale = sum(b["mass"] * 9.81 * GAP * (k + 1) for k, b in enumerate(free))
    speed = max(float(np.linalg.norm(b["velocity"])) for b in free)
    top = free[-1]
    rest_z = 3 * EDGE - EDGE / 2  # centroid of the top cube resting on two cubes
    drift = float(abs(top["position"][2] - rest_z))
    return [("reached the end", run.summary["time"] >= run.scene["time"]["end"] * (1 - 1e-9),
             f"t = {run.summary['time']:.4g} s in {run.summary['steps']} steps"),
            ("no energy growth: kinetic + potential never above its start by 1 % of sum m g gap",
             growth <= 0.01 * scale, f"largest rise {growth:.3g} J of {scale:.3g} J"),
            ("stack at rest at the end: every cube slower than 1 mm/s", speed < 1e-3, f"max |v| {speed:.3g} m/s"),
            ("top cube rests at 3 edges - half an edge (no sinking, no bouncing off)", drift < 1e-3,
             f"|z - {rest_z:g}| = {drift:.3g} m; deepest overlap {deepest:.3g} m at t = {when:.3g} s")]
