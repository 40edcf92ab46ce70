#!/usr/bin/env python3
"""A restart on another rank count continues as the run it restarts does:
runs a scene serially to the end (the reference), and on FROM ranks with
checkpoints; restarts that run's checkpoint nearest the middle step on each
of the TO rank counts (1 is serial), and the serial run's on FROM ranks; each
restarted run's last output step must match the reference particle by
particle to the bounds given. The checkpoint the ranks wrote together must be
as long as the serial run's of the same step (the same format, the same
fields and rows), and with one byte of it changed a restart on FROM ranks
must stop on every rank with the checksum error (exit 2), writing nothing.

usage: restart_ranks.py TALUS SCENE OUTDIR --from 2 --to 1 3 --x-tol M --v-tol M/S --rho-tol KG/M3 [--f-tol N]
"""
import argparse
import glob
import os
import shutil
import subprocess
import sys

from compare_ranks import compare, last_step, mpirun, run, run_arguments


def middle_checkpoint(folder, name, last):
    files = sorted(glob.glob(os.path.join(folder, name + "_*.checkpoint")))
    if not files:
        sys.exit(f"FAIL: no checkpoint in {folder}")
    step = lambda f: int(f.rsplit("_", 1)[1].split(".")[0])
    return min(files, key=lambda f: abs(step(f) - last / 2))


def main():
    ap = argparse.ArgumentParser()
    run_arguments(ap)
    ap.add_argument("--from", dest="source", type=int, default=2)
    ap.add_argument("--to", type=int, nargs="+", default=[1, 3])
    ap.add_argument("--x-tol", type=float, required=True)
    ap.add_argument("--v-tol", type=float, required=True)
    ap.add_argument("--rho-tol", type=float, required=True)
    ap.add_argument("--f-tol", type=float, default=None, help="bound on the blocks' force and torque (N, N m)")
    a = ap.parse_args()
    tol = (a.x_tol, a.v_tol, a.rho_tol, a.f_tol)
    name = os.path.splitext(os.path.basename(a.scene))[0]
    launch = lambda n: (mpirun(n) if n > 1 else []) + [a.talus, "run", a.scene]

    serial = os.path.join(a.outdir, "serial")
    run(launch(1), serial)
    step0, ref = last_step(os.path.join(serial, name + ".h5part"))
    source = os.path.join(a.outdir, f"ranks{a.source}")
    run(launch(a.source), source)
    ok = compare(f"{a.source} ranks", step0, ref, *last_step(os.path.join(source, name + ".h5part")), tol)

    restarts = [(middle_checkpoint(source, name, step0), a.source, n) for n in a.to]
    restarts.append((middle_checkpoint(serial, name, step0), 1, a.source))
    for checkpoint, written, n in restarts:
        out = os.path.join(a.outdir, f"from{written}_to{n}")
        run(launch(n) + ["--restart", checkpoint], out)
        label = f"restart of {os.path.basename(checkpoint)} ({written} -> {n} ranks)"
        ok &= compare(label, step0, ref, *last_step(os.path.join(out, name + ".h5part")), tol)
    ok &= same_size_as_serial(restarts[0][0], serial, name)
    ok &= refuses_corrupt(restarts[0][0], launch(a.source), os.path.join(a.outdir, "corrupt"))
    sys.exit(0 if ok else 1)


def same_size_as_serial(checkpoint, serial, name):
    twin = os.path.join(serial, os.path.basename(checkpoint))
    sizes = (os.path.getsize(checkpoint), os.path.getsize(twin) if os.path.exists(twin) else -1)
    ok = sizes[0] == sizes[1]
    print(f"{os.path.basename(checkpoint)}: {sizes[0]} bytes from the ranks, {sizes[1]} serially: "
          f"{'ok' if ok else 'FAIL'}")
    return ok


def refuses_corrupt(checkpoint, command, folder):
    os.makedirs(folder, exist_ok=True)
    bad = os.path.join(folder, "flipped.checkpoint")
    shutil.copyfile(checkpoint, bad)
    with open(bad, "r+b") as f:
        f.seek(os.path.getsize(bad) * 2 // 3)
        byte = f.read(1)
        f.seek(-1, os.SEEK_CUR)
        f.write(bytes([byte[0] ^ 0x10]))
    out = os.path.join(folder, "out")
    result = subprocess.run(command + ["--restart", bad, "--out", out], capture_output=True, text=True)
    ok = result.returncode == 2 and "checksum mismatch" in result.stderr and not os.path.exists(out)
    print(f"restart from a checkpoint with one byte changed: exit {result.returncode}, "
          f"{'checksum error' if 'checksum mismatch' in result.stderr else 'no checksum error'}, "
          f"{'an output folder' if os.path.exists(out) else 'nothing'} written: {'ok' if ok else 'FAIL'}")
    if not ok:
        print(result.stderr[-2000:])
    return ok


if __name__ == "__main__":
    main()
