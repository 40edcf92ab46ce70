#!/usr/bin/python3
"""Resolution ladder of the wcsph validation cases: error against resolution
and wall time, for the speed-versus-error report (DESIGN.md, "How we know it
works").

Cases (scenes in share/scenes, run with `talus run` at several dp):
  hydrostatic   hydrostatic_2d.json: pressure at the floor (probe 'bottom',
                averaged over the last second) against rho0 g (H - y_probe).
  martin_moyce  dam_break_2d_martin_moyce.json: surge front Z = z/a against
                the two Martin & Moyce (1952) series for 1 <= T <= 3: the
                mean distance outside the measured spread, and the front
                speed dZ/dT over 1.5 <= T <= 3 against the measured speeds.

Usage: tools/ladder_sph.py [--talus build/bin/talus] [--case martin_moyce]
                           [--levels 20,30,40] [--threads 2] [--out DIR]
Writes DIR/ladder_sph.csv and prints a table. Needs h5py and numpy (Debian's
python3-h5py) for the dam break frames.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "share", "scenes")
DATA = os.path.join(ROOT, "..", "shared", "validation-data")
G = 9.81


def read_series(name):
    t, z = [], []
    with open(os.path.join(DATA, name)) as f:
        rows = [r for r in f if not r.startswith("#")][1:]
    for r in rows:
        a, b = r.strip().split(",")[:2]
        t.append(float(a))
        z.append(float(b))
    return t, z


def interp(ts, zs, t):
    if t < ts[0] or t > ts[-1]:
        return float("nan")
    for k in range(1, len(ts)):
        if t <= ts[k]:
            return zs[k - 1] + (zs[k] - zs[k - 1]) * (t - ts[k - 1]) / (ts[k] - ts[k - 1])
    return zs[-1]


def slope(ts, zs, t0, t1):
    pts = [(t, z) for t, z in zip(ts, zs) if t0 <= t <= t1]
    n = len(pts)
    st = sum(p[0] for p in pts)
    sz = sum(p[1] for p in pts)
    stt = sum(p[0] ** 2 for p in pts)
    stz = sum(p[0] * p[1] for p in pts)
    return (n * stz - st * sz) / (n * stt - st * st)


def run(talus, scene, out, threads):
    start = time.time()
    subprocess.run([talus, "run", scene, "--out", out, "--threads", str(threads), "--quiet"], check=True)
    return time.time() - start


def with_dp(scene_file, dp, outputs, tmp):
    scene = json.load(open(os.path.join(SCENES, scene_file)))
    for body in scene["bodies"]:
        if "dp" in body:
            body["dp"] = dp
    scene["outputs"] = outputs
    path = os.path.join(tmp, "%s_dp%g.json" % (scene_file[:-5], dp))
    json.dump(scene, open(path, "w"), indent=1)
    return path


def hydrostatic(talus, level, threads, tmp):
    H = 0.4
    dp = H / level
    scene = with_dp("hydrostatic_2d.json", dp,
                    [{"type": "probes", "every": 0.01, "points": [[0.2, 0.05]], "point_names": ["bottom"],
                      "fields": ["pressure"]}], tmp)
    out = os.path.join(tmp, "hs_%d" % level)
    wall = run(talus, scene, out, threads)
    rows = [r for r in open(os.path.join(out, os.path.basename(scene)[:-5] + "_probes.csv")) if not r.startswith("#")]
    head = rows[0].strip().split(",")
    col = head.index("bottom_pressure")
    vals = [list(map(float, r.strip().split(","))) for r in rows[1:]]
    last = [v[col] for v in vals if v[0] >= vals[-1][0] - 1.0]
    p = sum(last) / len(last)
    exact = 1000 * G * (H - 0.05)
    return {"case": "hydrostatic", "level": "H/%d" % level, "dp": dp, "wall_s": wall,
            "error": abs(p / exact - 1), "note": "p_probe/(rho g (H-y)) = %.4f" % (p / exact)}


def martin_moyce(talus, level, threads, tmp):
    import h5py  # noqa: deferred so that the hydrostatic case runs without it
    a = 0.1
    dp = a / level
    scene = with_dp("dam_break_2d_martin_moyce.json", dp, [{"type": "hdf5", "every": 0.004}], tmp)
    out = os.path.join(tmp, "mm_%d" % level)
    wall = run(talus, scene, out, threads)
    frames = h5py.File(os.path.join(out, os.path.basename(scene)[:-5] + ".h5part"))
    T, Z = [], []
    for key in frames:
        f = frames[key]
        T.append(f.attrs["TimeValue"][0] * math.sqrt(2 * G / a))
        Z.append((max(f["x"][:]) + 0.5 * dp) / a)
    order = sorted(range(len(T)), key=lambda k: T[k])
    T = [T[k] for k in order]
    Z = [Z[k] for k in order]
    ts, zs = read_series("dambreak_martin_moyce1952_n2eq2_a1.125in.csv")
    tl, zl = read_series("dambreak_martin_moyce1952_n2eq2_a2.25in.csv")
    outside, n = 0.0, 0
    for t, z in zip(T, Z):
        if not 1.0 <= t <= 3.0:
            continue
        lo, hi = sorted([interp(ts, zs, t), interp(tl, zl, t)])
        outside += max(0.0, z / hi - 1, 1 - z / lo)
        n += 1
    speed = slope(T, Z, 1.5, 3.0)
    return {"case": "martin_moyce", "level": "a/%d" % level, "dp": dp, "wall_s": wall, "error": outside / max(n, 1),
            "note": "dZ/dT = %.3f (measured %.3f, %.3f)" % (speed, slope(ts, zs, 1.5, 3.0), slope(tl, zl, 1.5, 3.0))}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--talus", default=os.path.join(ROOT, "build", "bin", "talus"))
    ap.add_argument("--case", choices=["hydrostatic", "martin_moyce", "all"], default="all")
    ap.add_argument("--levels", default="10,20,40", help="cells across H (hydrostatic) or a (martin_moyce)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    tmp = args.out or tempfile.mkdtemp(prefix="ladder_sph_")
    os.makedirs(tmp, exist_ok=True)
    levels = [int(x) for x in args.levels.split(",")]
    cases = ["hydrostatic", "martin_moyce"] if args.case == "all" else [args.case]
    results = []
    for case in cases:
        for level in levels:
            fn = hydrostatic if case == "hydrostatic" else martin_moyce
            r = fn(args.talus, level, args.threads, tmp)
            print("%-13s %-6s dp %-9.4g wall %7.1f s  error %.4f  %s" % (r["case"], r["level"], r["dp"], r["wall_s"],
                                                                      r["error"], r["note"]), flush=True)
            results.append(r)
    with open(os.path.join(tmp, "ladder_sph.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["case", "level", "dp", "wall_s", "error", "note"])
        w.writeheader()
        w.writerows(results)
    print("table: %s" % os.path.join(tmp, "ladder_sph.csv"))


if __name__ == "__main__":
    sys.exit(main())
