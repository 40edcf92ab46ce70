#!/usr/bin/env python3
"""Warnings raised on any rank reach rank 0: a scene whose two bodies leave the domain at opposite ends, one on each
of 2 ranks, prints and summarises the same warnings as its serial run.

    warnings_ranks.py TALUS SCENE OUTDIR"""
import json
import os
import subprocess
import sys

talus, scene, outdir = sys.argv[1:4]
os.makedirs(outdir, exist_ok=True)


def run(prefix, name):
    summary = os.path.join(outdir, name + ".summary.json")
    r = subprocess.run(prefix + [talus, "run", scene, "--out", os.path.join(outdir, name), "--summary", summary],
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {name} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    with open(summary) as f:
        return [line for line in r.stderr.splitlines() if line.startswith("talus: warning:")], json.load(f)["warnings"]


serial_printed, serial_listed = run([], "serial")
mpirun = [os.environ.get("TALUS_MPIEXEC", "mpirun"), "-np", "2", "--oversubscribe"]
printed, listed = run(mpirun, "ranks2")
failures = []
for body in ("left", "right"):
    if not any(f"of body '{body}' left the domain" in w for w in listed):
        failures.append(f"the summary of 2 ranks lacks the removal of body '{body}'")
if sorted(listed) != sorted(serial_listed):
    failures.append(f"summary warnings differ:\n  serial {serial_listed}\n  2 ranks {listed}")
if sorted(printed) != sorted(serial_printed):
    failures.append(f"printed warnings differ:\n  serial {serial_printed}\n  2 ranks {printed}")
for f in failures:
    print("FAIL:", f)
print(f"{len(listed)} warnings on 2 ranks, {len(serial_listed)} serially")
print("%d passed, %d failed" % (3 - len(failures), len(failures)))
sys.exit(1 if failures else 0)
