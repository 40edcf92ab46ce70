#!/usr/bin/env python3
"""Runs a scene serially and on several MPI ranks, with the hdf5 writer also
writing the wall particles, and compares the H5Part files whole: the same
root attributes, the same frames with the same attributes, the same datasets
(type, shape, attributes) and, rows matched by id, the same values: integers
and texts exactly, reals (attributes too) to --rel-tol of the dataset's
largest magnitude or --abs-tol, whichever is larger (the ranks sum a
particle's neighbours and the time step's bounds in another order). The block
states of each frame too, row by row. A serial run writes its rows in the store's order and the
ranks theirs in rank order, so only the row order may differ.

usage: same_file.py TALUS SCENE OUTDIR --ranks 2 3 [--rel-tol R] [--abs-tol A]
"""
import argparse
import os
import sys

import h5py
import numpy as np

from compare_ranks import edited_copy, mpirun, run, run_arguments


def attributes_differ(ref, got, tol):
    """The attributes that differ: texts and integers at all, reals beyond tol."""
    if sorted(ref.attrs.keys()) != sorted(got.attrs.keys()):
        return f"attribute names {sorted(got.attrs.keys())} against {sorted(ref.attrs.keys())}"
    for k in ref.attrs.keys():
        a, b = ref.attrs[k], got.attrs[k]
        if isinstance(a, np.ndarray) and a.dtype.kind == "f" and isinstance(b, np.ndarray) and a.shape == b.shape:
            if np.max(np.abs(a - b), initial=0.0) > tol(np.max(np.abs(a), initial=0.0)):
                return f"attribute {k}: {b.tolist()} against {a.tolist()}"
        elif not np.array_equal(np.asarray(a), np.asarray(b)):
            return f"attribute {k}: {b} against {a}"
    return None


def compare_values(label, ref, got, tol, order_ref=None, order_got=None):
    """Problems with one dataset (type, shape, attributes, values), and its
    largest difference as a share of the bound."""
    if ref.dtype != got.dtype or ref.shape != got.shape:
        return [f"{label}: {got.dtype} {got.shape} against {ref.dtype} {ref.shape}"], 0.0
    problems = []
    if (why := attributes_differ(ref, got, tol)) is not None:
        problems.append(f"{label}: {why}")
    a, b = ref[()], got[()]
    if order_ref is not None:
        a, b = a[order_ref], b[order_got]
    if a.dtype.kind not in "f":
        if not np.array_equal(a, b):
            problems.append(f"{label}: values differ")
        return problems, 0.0
    scale = float(np.max(np.abs(a), initial=0.0))
    worst = float(np.max(np.abs(b - a), initial=0.0))
    if worst > tol(scale):
        problems.append(f"{label}: largest difference {worst:.3e} for values up to {scale:.3e}")
    return problems, worst / tol(scale)


def compare_files(ref_path, got_path, tol):
    """Problems found, and the real dataset closest to its bound (share, name)."""
    problems, worst = [], (0.0, "")

    def values(label, r, g, *orders):
        nonlocal worst
        found, share = compare_values(label, r, g, tol, *orders)
        problems.extend(found)
        worst = max(worst, (share, label))

    def groups(label, r, g):
        """True when both groups have the same attributes and datasets."""
        if (why := attributes_differ(r, g, tol)) is not None:
            problems.append(f"{label}: {why}")
        if sorted(r.keys()) != sorted(g.keys()):
            problems.append(f"{label}: members {sorted(g.keys())} against {sorted(r.keys())}")
            return False
        return True

    with h5py.File(ref_path, "r") as ref, h5py.File(got_path, "r") as got:
        if not groups("/", ref, got):
            return problems, worst
        for name in ref.keys():
            if name == "Blocks":
                continue
            r, g = ref[name], got[name]
            if groups(name, r, g):
                order_r, order_g = np.argsort(r["id"][()]), np.argsort(g["id"][()])
                for k in r.keys():
                    values(f"{name}/{k}", r[k], g[k], order_r, order_g)
        if "Blocks" in ref and groups("Blocks", ref["Blocks"], got["Blocks"]):
            for name in ref["Blocks"].keys():
                r, g = ref["Blocks"][name], got["Blocks"][name]
                if groups(f"Blocks/{name}", r, g):
                    for k in r.keys():
                        values(f"Blocks/{name}/{k}", r[k], g[k])
    return problems, worst


def main():
    ap = argparse.ArgumentParser()
    run_arguments(ap, ranks=[2])
    ap.add_argument("--rel-tol", type=float, default=1e-9)
    ap.add_argument("--abs-tol", type=float, default=1e-12)
    a = ap.parse_args()
    tol = lambda scale: max(a.rel_tol * scale, a.abs_tol)
    name = os.path.splitext(os.path.basename(a.scene))[0]
    def with_wall_files(scene):
        for out in scene["outputs"]:
            if out["type"] == "hdf5":
                out["boundary"] = True

    scene_copy = edited_copy(a.scene, a.outdir, with_wall_files)
    serial = os.path.join(a.outdir, "serial")
    run([a.talus, "run", scene_copy], serial)
    failed = False
    for n in a.ranks:
        out = os.path.join(a.outdir, f"ranks{n}")
        run(mpirun(n) + [a.talus, "run", scene_copy], out)
        for suffix in ("", "_boundary"):
            file = name + suffix + ".h5part"
            problems, worst = compare_files(os.path.join(serial, file), os.path.join(out, file), tol)
            with h5py.File(os.path.join(out, file), "r") as f:
                frames = sum(1 for k in f.keys() if k.startswith("Step#"))
            print(f"{n} ranks, {file}: {frames} frames, closest to its bound: {worst[1]} at {worst[0]:.2g} of it: "
                  f"{'FAIL' if problems else 'ok'}")
            for p in problems[:20]:
                print("   ", p)
            failed |= bool(problems)
            leftovers = [f for f in os.listdir(out) if f.endswith((".tmp", ".prev"))]
            if leftovers:
                print(f"{n} ranks: working copies left behind: {leftovers}: FAIL")
                failed = True
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
