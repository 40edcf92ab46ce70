#!/usr/bin/env python3
"""Runs a scene serially and on several MPI ranks and compares the last
output step particle by particle (matched by id): positions, velocities and
densities must agree to round-off, bounds given on the command line.

usage: compare_ranks.py TALUS SCENE OUTDIR --ranks 2 3 [--x-tol M] [--v-tol M/S] [--rho-tol KG/M3]
"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np


def last_step(path):
    with h5py.File(path, "r") as f:
        steps = sorted(f.keys(), key=lambda k: int(k.split("#")[1]))
        s = f[steps[-1]]
        order = np.argsort(s["id"][()])
        fields = {k: s[k][()][order] for k in ("id", "x", "y", "z", "velocity_0", "velocity_1", "velocity_2", "density")}
        return int(s.attrs["step"][0]), fields


def run(cmd, out):
    result = subprocess.run(cmd + ["--out", out, "--quiet"], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {result.returncode}\n{result.stdout}\n{result.stderr}")


def mpirun(n):
    return [os.environ.get("TALUS_MPIEXEC", "mpirun"), "-np", str(n), "--oversubscribe"]


def compare(label, step0, ref, step, got, tol):
    """Prints the largest differences of `got` from `ref`; True when inside tol = (x, v, rho)."""
    if step != step0 or not np.array_equal(got["id"], ref["id"]):
        print(f"{label}: step {step} vs {step0}, {len(got['id'])} particles vs {len(ref['id'])}: FAIL")
        return False
    dx = max(np.max(np.abs(got[k] - ref[k])) for k in ("x", "y", "z"))
    dv = max(np.max(np.abs(got[k] - ref[k])) for k in ("velocity_0", "velocity_1", "velocity_2"))
    drho = np.max(np.abs(got["density"] - ref["density"]))
    ok = dx <= tol[0] and dv <= tol[1] and drho <= tol[2]
    print(f"{label}, step {step}, {len(ref['id'])} particles: max |dx| {dx:.3e} m, |dv| {dv:.3e} m/s, "
          f"|drho| {drho:.3e} kg/m^3: {'ok' if ok else 'FAIL'}")
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("talus")
    ap.add_argument("scene")
    ap.add_argument("outdir")
    ap.add_argument("--ranks", type=int, nargs="+", default=[2])
    ap.add_argument("--x-tol", type=float, required=True)
    ap.add_argument("--v-tol", type=float, required=True)
    ap.add_argument("--rho-tol", type=float, required=True)
    a = ap.parse_args()
    name = os.path.splitext(os.path.basename(a.scene))[0]
    serial_out = os.path.join(a.outdir, "serial")
    run([a.talus, "run", a.scene], serial_out)
    step0, ref = last_step(os.path.join(serial_out, name + ".h5part"))
    failed = False
    for n in a.ranks:
        out = os.path.join(a.outdir, f"ranks{n}")
        run(mpirun(n) + [a.talus, "run", a.scene], out)
        step, got = last_step(os.path.join(out, name + ".h5part"))
        failed |= not compare(f"{n} ranks", step0, ref, step, got, (a.x_tol, a.v_tol, a.rho_tol))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
