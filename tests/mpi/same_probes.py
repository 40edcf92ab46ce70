#!/usr/bin/env python3
"""Runs a scene serially and on several MPI ranks, with its probes writer
given every kind of column (points, gauges, bed gauges, run-up, each
material's mass, the integrals, wall forces and wall sensors), and compares
the probes files: the same comment lines and header, the same steps, and every value
within ABS + REL * (the column's largest magnitude in the serial run); NaN
where the serial run has NaN. On several ranks every rank samples the
particles it owns and the sums are added over the ranks, so the files differ
by round-off only.

usage: same_probes.py TALUS SCENE OUTDIR --ranks 2 3 --steps N --every-steps K --rel-tol R --abs-tol A
                      [--probes JSON]   (keys added to the scene's first probes writer)
"""
import argparse
import csv
import json
import math
import os
import sys

from compare_ranks import edited_copy, mpirun, run, run_arguments


def read_probes(path):
    """The '#' comment lines, the header and the rows."""
    with open(path) as f:
        lines = f.read().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    rows = list(csv.reader(line for line in lines if not line.startswith("#")))
    return comments, rows[0], [[float(v) for v in r] for r in rows[1:]]


def compare(label, header0, rows0, header, rows, rel, abs_tol):
    if header != header0 or len(rows) != len(rows0):
        print(f"{label}: header or row count differs ({len(rows)} rows against {len(rows0)}): FAIL")
        return False
    worst, where = 0.0, ""
    ok = True
    for c, name in enumerate(header0):
        scale = max((abs(r[c]) for r in rows0 if math.isfinite(r[c])), default=0.0)
        bound = abs_tol + rel * scale
        for r0, r in zip(rows0, rows):
            a, b = r0[c], r[c]
            if math.isnan(a) or math.isnan(b):
                if not (math.isnan(a) and math.isnan(b)):
                    print(f"{label}: {name} at step {r0[1]:.0f}: {b} against {a}: FAIL")
                    ok = False
                continue
            if abs(a - b) > bound:
                print(f"{label}: {name} at step {r0[1]:.0f}: {b!r} against {a!r} (bound {bound:.3g}): FAIL")
                ok = False
            share = abs(a - b) / bound
            if share > worst:
                worst, where = share, f"{name} at step {r0[1]:.0f} ({abs(a - b):.3g})"
    print(f"{label}: {len(rows)} rows, {len(header0)} columns; nearest to its bound: {where}, "
          f"{worst:.3g} of it: {'ok' if ok else 'FAIL'}")
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    run_arguments(ap, ranks=[2])
    ap.add_argument("--steps", type=int, required=True)
    ap.add_argument("--every-steps", type=int, required=True)
    ap.add_argument("--rel-tol", type=float, required=True)
    ap.add_argument("--abs-tol", type=float, required=True)
    ap.add_argument("--probes", default="{}", help="keys added to the probes writer, as JSON")
    a = ap.parse_args()
    name = os.path.splitext(os.path.basename(a.scene))[0]

    def edit(scene):
        scene["time"]["max_steps"] = a.steps
        probes = [o for o in scene["outputs"] if o["type"] == "probes"]
        if not probes:
            sys.exit(f"FAIL: {a.scene} has no probes writer")
        probes[0].pop("every", None)
        probes[0]["every_steps"] = a.every_steps
        probes[0].update(json.loads(a.probes))
        scene["outputs"] = probes[:1]

    scene = edited_copy(a.scene, a.outdir, edit)
    serial = os.path.join(a.outdir, "serial")
    run([a.talus, "run", scene], serial)
    comments0, header0, rows0 = read_probes(os.path.join(serial, name + "_probes.csv"))
    ok = True
    for n in a.ranks:
        out = os.path.join(a.outdir, f"ranks{n}")
        run(mpirun(n) + [a.talus, "run", scene], out)
        comments, header, rows = read_probes(os.path.join(out, name + "_probes.csv"))
        for line0, line in zip(comments0, comments + [""] * len(comments0)):
            if line != line0:  # what the file says of its columns (a sensor's particles) is the serial run's
                print(f"{n} ranks: comment line {line!r} against {line0!r}: FAIL")
                ok = False
                break
        ok &= compare(f"{n} ranks", header0, rows0, header, rows, a.rel_tol, a.abs_tol)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
