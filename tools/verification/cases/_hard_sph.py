"""Shared gates of the SPH hard cases: every frame inside the tank, nothing removed, energy not growing."""
import numpy as np

from verification.cases._util import frames


def fluid_energy(f, gravity):
    """Kinetic + gravitational potential energy of the fluid particles of one frame, J (per metre in 2D)."""
    dim = len(gravity)
    m = f["mass"]
    v2 = sum(f[f"velocity_{k}"] ** 2 for k in range(dim))
    pos = [f["x"], f["y"], f.get("z")][:dim]
    potential = -sum(m * gravity[k] * pos[k] for k in range(dim))
    return float(np.sum(0.5 * m * v2) + np.sum(potential))


def scan(run, lo, hi, axes):
    """Over every frame: (particles outside the box [lo, hi] on the given axes, worst frame's time), the energy
    series (t, E), the max speed and the largest non-finite count."""
    names = ["x", "y", "z"]
    outside, outside_t, energy, vmax, bad = 0, float("nan"), [], 0.0, 0
    gravity = run.scene.get("gravity", [0, -9.81] if run.scene["domain"]["dim"] == 2 else [0, 0, -9.81])
    dim = run.scene["domain"]["dim"]
    for t, f in frames(run):
        n_out = 0
        for a in axes:
            p = f[names[a]]
            n_out += int(np.sum((p < lo[a]) | (p > hi[a])))
        if n_out > outside:
            outside, outside_t = n_out, t
        v = np.sqrt(sum(f[f"velocity_{k}"] ** 2 for k in range(dim)))
        bad = max(bad, int(np.sum(~np.isfinite(v))) + int(np.sum(~np.isfinite(f["density"]))))
        vmax = max(vmax, float(np.nanmax(v)) if v.size else 0.0)
        energy.append((t, fluid_energy(f, gravity)))
    return outside, outside_t, energy, vmax, bad


def energy_growth(energy):
    """Largest rise of E(t) above E(0), J."""
    e0 = energy[0][1]
    return max(e - e0 for _, e in energy)
