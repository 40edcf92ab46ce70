#!/usr/bin/env python3
"""A front history on several MPI ranks against the serial run's, to the end
of the run: the scene's copy runs to its end time (its max_steps dropped, or
to --end) with a frame every --every-steps steps, and at every frame the
front (the largest coordinate of a fluid particle along --axis) on each rank
count must be within --rel-tol of the serial front. Frames go by steps, not
by time: the ranks' clock differs from the serial one by round-off, which can
move a frame due at a time by one step. The same can end a run one step
earlier or later: the last frames are then compared only if at one step. With blocks, so must each
block's distance from where it started (to 1e-9 m for blocks that stay put).
Round-off differences grow over thousands of steps; the front and a block's
travel, integrals of the flow, must not move with them.

usage: front_ranks.py TALUS SCENE OUTDIR --ranks 2 3 4 [--every-steps N] [--end S] [--axis 0|1|2] [--rel-tol R]
"""
import argparse
import os
import sys

import h5py
import numpy as np

from compare_ranks import edited_copy, mpirun, run, run_arguments


def fronts(path, axis):
    """(step, time, front, block travels) of every frame."""
    out = []
    with h5py.File(path, "r") as f:
        steps = sorted((k for k in f.keys() if k.startswith("Step#")), key=lambda k: int(k.split("#")[1]))
        start = None
        for k in steps:
            g = f[k]
            travel = np.zeros(0)
            if "Blocks" in f and k in f["Blocks"]:
                at = f["Blocks"][k]["position"][()]
                start = at if start is None else start
                travel = np.linalg.norm(at - start, axis=1)
            front = float(np.max(g["xyz"[axis]][()]))
            out.append((int(g.attrs["step"][0]), float(g.attrs["TimeValue"][0]), front, travel))
    return out


def largest_difference(ref, got, rel_tol):
    """The frame where the front or a block's travel is nearest its bound, and that share of it."""
    worst = (0.0, 0, "front")
    for k, (r, g) in enumerate(zip(ref, got)):
        worst = max(worst, (abs(g[2] - r[2]) / (rel_tol * abs(r[2])), k, "front"))
        for b in range(len(r[3])):
            bound = max(rel_tol * r[3][b], 1e-9)
            worst = max(worst, (abs(g[3][b] - r[3][b]) / bound, k, f"block {b}'s travel"))
    return worst


def main():
    ap = argparse.ArgumentParser()
    run_arguments(ap, ranks=[2, 3, 4])
    ap.add_argument("--every-steps", type=int, default=200)
    ap.add_argument("--end", type=float, default=None, help="end time, s (default: the scene's)")
    ap.add_argument("--axis", type=int, default=0, choices=(0, 1, 2))
    ap.add_argument("--rel-tol", type=float, default=1e-3)
    a = ap.parse_args()
    name = os.path.splitext(os.path.basename(a.scene))[0]
    def edit(scene):
        scene["time"].pop("max_steps", None)
        if a.end is not None:
            scene["time"]["end"] = a.end
        scene["outputs"] = [{"type": "hdf5", "every_steps": a.every_steps, "fields": ["id"]}]

    scene_copy = edited_copy(a.scene, a.outdir, edit)
    serial_out = os.path.join(a.outdir, "serial")
    run([a.talus, "run", scene_copy], serial_out)
    ref = fronts(os.path.join(serial_out, name + ".h5part"), a.axis)
    failed = False
    for n in a.ranks:
        out = os.path.join(a.outdir, f"ranks{n}")
        run(mpirun(n) + [a.talus, "run", scene_copy], out)
        got = fronts(os.path.join(out, name + ".h5part"), a.axis)
        steps, ref_steps = [s for s, *_ in got], [s for s, *_ in ref]
        if steps[:-1] != ref_steps[:-1]:
            print(f"{n} ranks: frames at steps {steps}, serially {ref_steps}: FAIL")
            failed = True
            continue
        if steps[-1] != ref_steps[-1]:  # the last step, one earlier or later
            print(f"{n} ranks: the run ended at step {steps[-1]}, serially at {ref_steps[-1]}: last frame not compared")
            got, ref_n = got[:-1], ref[:-1]
        else:
            ref_n = ref
        share, k, what = largest_difference(ref_n, got, a.rel_tol)
        ok = share <= 1.0
        travel = f", blocks travel up to {max(ref_n[-1][3]):.4f} m" if len(ref_n[-1][3]) else ""
        print(f"{n} ranks: {len(ref_n)} frames to t = {ref_n[-1][1]:.4f} s (step {ref_n[-1][0]}), front "
              f"{ref_n[0][2]:.4f} -> {ref_n[-1][2]:.4f} m{travel}; nearest its bound: {what} at "
              f"t = {ref_n[k][1]:.4f} s, {share:.2e} of it: {'ok' if ok else 'FAIL'}")
        failed |= not ok
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
