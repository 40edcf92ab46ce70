#!/usr/bin/env python3
"""Scaling on this machine, and the cost model (tools/mpi_model.py) measured
and checked against it (docs/mpi.md, "Cost model").

  tools/bench_ranks.py build/bin/talus --out /tmp/bench_ranks [--repeats 5]

Scenes (written to OUT, no output files, a fixed number of steps, 1 thread
per rank unless said):
  slab    a 3D dam break that does not change along y: a water column across
          a tank periodic in y (0.6 m), walls at both ends and below
  slab2   the same, 1.2 m along y: twice the particles, so that on 2 ranks
          each rank holds what one rank holds of `slab` (weak scaling)
  tank    share/scenes/dam_break_3d.json at the same dp (strong scaling of a
          scene that does change along every axis)
Runs, in turn, `repeats` times; each figure is the median over the repeats of
the time per step from the run summary (the set-up left out):
  slab on 1 rank alone, and two such runs at once (the rate with both cores
  busy); slab on 1 rank x 2 threads; slab and slab2 on 2 ranks; tank on 1 and
  2 ranks. bench/bench_pingpong gives this machine's latency and bandwidth.

The model's rate is a scene's serial rate with every core busy; halo_cost and
rebuild_cost come from the weak-scaling run (its imbalance: the summary's
cost_imbalance_mean, the measured cost of the busiest rank over the mean) (the host phase's extra time per
step is the rebuilds; what remains beyond the owned rows' time and the
messages is the halo's); the model then predicts the two strong-scaling runs
from their own halo share, imbalance and rebuild count, and must come within
--tolerance of both (exit 1 otherwise). Last, the projection to 64 ranks of
1 M particles with the measured parameters.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_model  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def dam_break(dp, steps):
    with open(os.path.join(ROOT, "share", "scenes", "dam_break_3d.json")) as f:
        scene = json.load(f)
    for body in scene["bodies"]:
        body["dp"] = dp
    scene["outputs"] = []
    scene["time"] = {"end": 100.0, "max_steps": steps}
    return scene


def slab(dp, steps, length):
    scene = dam_break(dp, steps)
    scene["description"] = "bench_ranks.py: a dam break that does not change along the periodic y axis"
    # x: a whole number of spacings, so that the walls fit the box as written.
    x_end = round(0.8 / dp) * dp
    scene["domain"] = {"dim": 3, "min": [0, 0, 0], "max": [x_end, length, 0.6], "periodic": ["y"]}
    fluid, tank = scene["bodies"]
    fluid["shape"] = {"box": {"min": [0, 0, 0], "max": [0.3, length, 0.3]}}
    tank["shape"] = {"box_walls": {"min": [0, 0, 0], "max": [x_end, length, 0.42], "open": ["+z", "-y", "+y"]}}
    return scene


def write_scene(out, name, scene):
    path = os.path.join(out, name + ".json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def command(a, scene, ranks, threads, out, summary):
    cmd = [a.talus, "run", scene, "--threads", str(threads), "--out", out, "--summary", summary, "--quiet"]
    if ranks > 1:
        cmd = [a.mpiexec, "-n", str(ranks), "--oversubscribe"] + cmd
    return cmd


def figures(summary_path):
    with open(summary_path) as f:
        s = json.load(f)
    steps = s["steps"]
    return {
        "t": s["wall_seconds"] / steps,
        "rows": (s["particle_steps"] + s["wall_particle_steps"]) / steps,
        "host": s["phases_s"]["host"] / steps,
        "halo_share": s["ranks"]["halo_share"],
        "imbalance": s["ranks"]["cost_imbalance_mean"],
        # The first rebuild shares the particles out before the first step (set-up, not host time).
        "rebuild_every": steps / (s["ranks"]["rebuilds"] - 1) if s["ranks"]["rebuilds"] > 1 else float("inf"),
    }


def run(a, tag, scene, ranks=1, threads=1, together=1):
    """Runs `together` copies at once; their figures, averaged over the copies."""
    procs, paths = [], []
    for k in range(together):
        out = os.path.join(a.out, f"{tag}.{k}")
        summary = out + ".summary.json"
        procs.append(subprocess.Popen(command(a, scene, ranks, threads, out, summary),
                                      stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True))
        paths.append(summary)
    for p in procs:
        text, _ = p.communicate()
        if p.returncode != 0:
            sys.exit(f"bench_ranks: {' '.join(p.args)} exited {p.returncode}\n{text}")
    runs = [figures(path) for path in paths]
    return {key: statistics.fmean(r[key] for r in runs) for key in runs[0]}


def ping_pong(a):
    line = subprocess.run([a.mpiexec, "-n", "2", "--oversubscribe", a.pingpong], capture_output=True, text=True,
                          check=True).stdout
    words = line.split()  # "latency L s, bandwidth B B/s"
    return float(words[1]), float(words[4])


def predict(p, run):
    owned = run["rows"] / 2
    q = mpi_model.parameters(**{**vars(p), "imbalance": run["imbalance"], "rebuild_every": run["rebuild_every"]})
    return mpi_model.step_time(q, 2, owned, run["halo_share"] * owned, 1)[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("talus")
    ap.add_argument("--out", required=True)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--dp", type=float, default=0.015)
    ap.add_argument("--tolerance", type=float, default=0.10, help="the model's largest relative error allowed")
    ap.add_argument("--mpiexec", default=os.environ.get("TALUS_MPIEXEC", "mpiexec"))
    ap.add_argument("--pingpong", default=None, help="bench_pingpong (default: build/bench/ beside bin/talus)")
    a = ap.parse_args()
    a.talus = os.path.abspath(a.talus)
    if a.pingpong is None:
        a.pingpong = os.path.join(os.path.dirname(os.path.dirname(a.talus)), "bench", "bench_pingpong")
    os.makedirs(a.out, exist_ok=True)
    scenes = {"slab": write_scene(a.out, "slab", slab(a.dp, a.steps, 0.6)),
              "slab2": write_scene(a.out, "slab2", slab(a.dp, a.steps, 1.2)),
              "tank": write_scene(a.out, "tank", dam_break(a.dp, a.steps))}
    configs = {  # name: (scene, ranks, threads, copies at once)
        "slab 1x1": ("slab", 1, 1, 1),
        "slab 1x1, both cores busy": ("slab", 1, 1, 2),
        "slab 1x2": ("slab", 1, 2, 1),
        "slab 2x1": ("slab", 2, 1, 1),
        "slab2 2x1": ("slab2", 2, 1, 1),
        "tank 1x1": ("tank", 1, 1, 1),
        "tank 2x1": ("tank", 2, 1, 1),
    }
    latency, bandwidth = ping_pong(a)
    print(f"messages between 2 ranks here: latency {latency:.3g} s, bandwidth {bandwidth:.3g} B/s")
    runs = {name: [] for name in configs}
    for r in range(a.repeats):
        for name, (scene, ranks, threads, together) in configs.items():
            runs[name].append(run(a, name.replace(" ", "_").replace(",", ""), scenes[scene], ranks, threads, together))
        print(f"repeat {r + 1} of {a.repeats} done", flush=True)
    m = {name: {key: statistics.median(x[key] for x in rs) for key in rs[0]} for name, rs in runs.items()}
    for name, f in m.items():
        spread = [x["t"] for x in runs[name]]
        print(f"{name:28s} {1e3 * f['t']:8.2f} ms per step (min {1e3 * min(spread):.2f}, max {1e3 * max(spread):.2f}), "
              f"{f['rows']:.0f} rows, halo {100 * f['halo_share']:.1f} %, imbalance {f['imbalance']:.3f}, "
              f"a rebuild every {f['rebuild_every']:.1f} steps, host {1e3 * f['host']:.2f} ms per step")

    one, busy, threads2 = m["slab 1x1"], m["slab 1x1, both cores busy"], m["slab 1x2"]
    strong, weak = m["slab 2x1"], m["slab2 2x1"]
    tank1, tank2 = m["tank 1x1"], m["tank 2x1"]
    print(f"strong scaling, time on 2 ranks over 1 rank: slab {strong['t'] / one['t']:.3f}, "
          f"tank {tank2['t'] / tank1['t']:.3f}")
    print(f"2 ranks x 1 thread over 1 rank x 2 threads (slab): {strong['t'] / threads2['t']:.3f}")
    print(f"weak scaling, 1 rank over 2 ranks of twice the particles: {100 * one['t'] / weak['t']:.1f} % "
          f"(2 OpenMP threads over twice 1 thread: {100 * one['t'] / (2 * threads2['t']):.1f} %)")

    # The model's parameters: the rate with both cores busy, the rest from the weak-scaling run.
    sharing = busy["t"] / one["t"]
    p = mpi_model.parameters(latency=latency, bandwidth=bandwidth, rate=busy["rows"] / busy["t"])
    owned = weak["rows"] / 2
    halo = weak["halo_share"] * owned
    # The host phase's time per step beyond the serial run's (with both cores busy, as the rate): the
    # rebuilds, on the busiest rank.
    rebuild = max(0.0, weak["host"] - busy["host"]) / weak["imbalance"]
    p.rebuild_cost = rebuild * p.rate * weak["rebuild_every"] / (owned + halo)
    p.rebuild_every = weak["rebuild_every"]
    _, messages = mpi_model.step_time(mpi_model.parameters(**{**vars(p), "halo_cost": 0.0}), 2, owned, halo, 1)
    p.halo_cost = ((weak["t"] - messages) * p.rate / weak["imbalance"] - owned
                   - p.rebuild_cost * (owned + halo) / p.rebuild_every) / halo
    print(f"model: rate {p.rate:.4g} particle-steps/s with both cores busy ({sharing:.3f} of the time alone), "
          f"halo_cost {p.halo_cost:.3f}, rebuild_cost {p.rebuild_cost:.3f} (a rebuild every "
          f"{p.rebuild_every:.1f} steps), from the weak-scaling run")

    worst = 0.0
    for name, run2, run1 in (("slab 2x1", strong, one), ("tank 2x1", tank2, tank1)):
        q = mpi_model.parameters(**{**vars(p), "rate": run1["rows"] / (run1["t"] * sharing)})
        predicted = predict(q, run2)
        error = predicted / run2["t"] - 1.0
        worst = max(worst, abs(error))
        print(f"model against {name}: {1e3 * predicted:.2f} ms per step predicted, {1e3 * run2['t']:.2f} measured "
              f"({100 * error:+.1f} %)")
    kernel = dam_break(a.dp, a.steps)["kernel"]
    reach_dp = 2 * kernel["h_over_dp"] + 1  # cubic spline support 2h, and a skin of one dp
    halo64 = mpi_model.shell_halo(1e6, 3, reach_dp)
    p64 = mpi_model.parameters(**{**vars(p), "latency": 1.5e-6, "bandwidth": 12.5e9})
    t64, messages64 = mpi_model.step_time(p64, 64, 1e6, halo64, 26)
    base64, _ = mpi_model.step_time(p64, 1, 1e6, 0.0, 0)
    print(f"projection, 64 ranks of 1 M particles (HDR100 InfiniBand, halo {100 * halo64 / 1e6:.1f} % of owned): "
          f"{t64:.4g} s per step, messages {messages64:.3g} s, weak-scaling efficiency {100 * base64 / t64:.1f} %")
    if worst > a.tolerance:
        print(f"bench_ranks: the model is off by {100 * worst:.1f} %, more than {100 * a.tolerance:.0f} %")
        return 1
    print(f"bench_ranks: the model is within {100 * worst:.1f} % of both strong-scaling runs "
          f"(tolerance {100 * a.tolerance:.0f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
