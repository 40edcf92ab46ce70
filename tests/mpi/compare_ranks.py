#!/usr/bin/env python3
"""Runs a scene serially and on several MPI ranks and compares the last
output step particle by particle (matched by id): positions, velocities and
densities must agree to round-off, bounds given on the command line. A scene
with blocks also has their last states compared, block by block: position
and orientation to the position bound, velocity and angular velocity to the
velocity bound, and the fluid's force and torque on them to --f-tol.

With --ranks-settings JSON, the scene's "ranks" entry (partition method,
rebalancing) is replaced by JSON in a copy written to OUTDIR, which both runs
use; the scene must then name no file relative to itself. --min-rebalances K
fails a run on several ranks that made fewer than K new cuts.

usage: compare_ranks.py TALUS SCENE OUTDIR --ranks 2 3 --x-tol M --v-tol M/S --rho-tol KG/M3 [--f-tol N]
                        [--ranks-settings JSON] [--min-rebalances K]
"""
import json
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np


BLOCK_FIELDS = ("position", "orientation", "velocity", "angular_velocity", "external_force", "external_torque")


def last_group(parent):
    steps = sorted((k for k in parent.keys() if k.startswith("Step#")), key=lambda k: int(k.split("#")[1]))
    return parent[steps[-1]]


def last_step(path):
    """The last step's particles (sorted by id) and, when the file has blocks, their last states."""
    with h5py.File(path, "r") as f:
        s = last_group(f)
        names = ("id", "x", "y", "z", "velocity_0", "velocity_1", "velocity_2", "density")
        if all(k in s for k in names):
            order = np.argsort(s["id"][()])
            fields = {k: s[k][()][order] for k in names}
        else:  # a scene of blocks only
            fields = {k: np.zeros(0) for k in names}
        if "Blocks" in f:
            b = last_group(f["Blocks"])
            fields["blocks"] = {k: b[k][()] for k in BLOCK_FIELDS}
            fields["blocks"]["step"] = int(b.attrs["step"][0])
        return int(s.attrs["step"][0]), fields


def run(cmd, out):
    result = subprocess.run(cmd + ["--out", out, "--quiet"], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {result.returncode}\n{result.stdout}\n{result.stderr}")


def run_arguments(ap, ranks=None):
    """The arguments every MPI test script takes: TALUS SCENE OUTDIR, and
    --ranks (the rank counts to run) when `ranks` gives its default."""
    ap.add_argument("talus")
    ap.add_argument("scene")
    ap.add_argument("outdir")
    if ranks is not None:
        ap.add_argument("--ranks", type=int, nargs="+", default=ranks)


def edited_copy(scene_path, outdir, edit):
    """Writes the scene with edit(scene) applied to OUTDIR/NAME.json and returns
    its path; the scene must then name no file relative to itself."""
    with open(scene_path) as f:
        scene = json.load(f)
    edit(scene)
    os.makedirs(outdir, exist_ok=True)
    path = os.path.join(outdir, os.path.basename(scene_path))
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def mpirun(n):
    return [os.environ.get("TALUS_MPIEXEC", "mpirun"), "-np", str(n), "--oversubscribe"]


def compare_blocks(label, ref, got, tol):
    """Prints the largest differences of the block states; True when inside tol = (x, v, rho, f)."""
    if got is None or got["step"] != ref["step"] or got["position"].shape != ref["position"].shape:
        print(f"{label}: the block states differ in step or count: FAIL")
        return False
    d = {k: np.max(np.abs(got[k] - ref[k])) for k in BLOCK_FIELDS}
    ok = (max(d["position"], d["orientation"]) <= tol[0] and max(d["velocity"], d["angular_velocity"]) <= tol[1]
          and (tol[3] is None or max(d["external_force"], d["external_torque"]) <= tol[3]))
    print(f"{label}, step {ref['step']}, {len(ref['position'])} blocks: max |dx| {d['position']:.3e} m, "
          f"|dq| {d['orientation']:.3e}, |dv| {d['velocity']:.3e} m/s, |dw| {d['angular_velocity']:.3e} rad/s, "
          f"|dF| {d['external_force']:.3e} N, |dM| {d['external_torque']:.3e} N m: {'ok' if ok else 'FAIL'}")
    return ok


def compare(label, step0, ref, step, got, tol):
    """Prints the largest differences of `got` from `ref`; True when inside tol = (x, v, rho, f)."""
    if step != step0 or not np.array_equal(got["id"], ref["id"]):
        print(f"{label}: step {step} vs {step0}, {len(got['id'])} particles vs {len(ref['id'])}: FAIL")
        return False
    def largest(keys):
        return max((np.max(np.abs(got[k] - ref[k]), initial=0.0) for k in keys))
    dx = largest(("x", "y", "z"))
    dv = largest(("velocity_0", "velocity_1", "velocity_2"))
    drho = largest(("density",))
    ok = dx <= tol[0] and dv <= tol[1] and drho <= tol[2]
    print(f"{label}, step {step}, {len(ref['id'])} particles: max |dx| {dx:.3e} m, |dv| {dv:.3e} m/s, "
          f"|drho| {drho:.3e} kg/m^3: {'ok' if ok else 'FAIL'}")
    if "blocks" in ref:
        ok &= compare_blocks(label, ref["blocks"], got.get("blocks"), tol)
    return ok


def main():
    ap = argparse.ArgumentParser()
    run_arguments(ap, ranks=[2])
    ap.add_argument("--x-tol", type=float, required=True)
    ap.add_argument("--v-tol", type=float, required=True)
    ap.add_argument("--rho-tol", type=float, required=True)
    ap.add_argument("--f-tol", type=float, default=None, help="bound on the blocks' force and torque (N, N m)")
    ap.add_argument("--ranks-settings", default=None, help="the scene's \"ranks\" entry, as JSON")
    ap.add_argument("--min-rebalances", type=int, default=0, help="fail unless each run made this many new cuts")
    a = ap.parse_args()
    name = os.path.splitext(os.path.basename(a.scene))[0]
    if a.ranks_settings is not None:
        a.scene = edited_copy(a.scene, a.outdir, lambda scene: scene.update(ranks=json.loads(a.ranks_settings)))
    serial_out = os.path.join(a.outdir, "serial")
    run([a.talus, "run", a.scene], serial_out)
    step0, ref = last_step(os.path.join(serial_out, name + ".h5part"))
    failed = False
    for n in a.ranks:
        out = os.path.join(a.outdir, f"ranks{n}")
        summary = os.path.join(a.outdir, f"ranks{n}.summary.json")
        run(mpirun(n) + [a.talus, "run", a.scene, "--summary", summary], out)
        step, got = last_step(os.path.join(out, name + ".h5part"))
        failed |= not compare(f"{n} ranks", step0, ref, step, got, (a.x_tol, a.v_tol, a.rho_tol, a.f_tol))
        with open(summary) as f:
            r = json.load(f)["ranks"]
        enough = r["rebalances"] >= a.min_rebalances
        # The mean over the steps lies between the best possible (1) and the worst the run stepped with.
        mean_ok = 1.0 <= r["cost_imbalance_mean"] <= r["cost_imbalance"] * (1 + 1e-12)
        print(f"{n} ranks: {r['rebalances']} rebalances in {r['rebuilds']} rebuilds, cost imbalance "
              f"{r['cost_imbalance_mean']:.3f} on average{'' if mean_ok else ' (outside [1, worst]: FAIL)'}, "
              f"{r['cost_imbalance']:.3f} at worst{'' if enough else f', fewer than {a.min_rebalances}: FAIL'}")
        failed |= not enough or not mean_ok
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
