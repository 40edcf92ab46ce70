"""Markdown tables, CSV and log-log plots of error against wall time."""
import csv
import json
import math
import os
import platform
import subprocess
from collections import defaultdict


def machine():
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    except OSError:
        commit = "?"
    return f"{cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}, commit {commit or '?'}"


def fmt(x, spec=".3g"):
    return "—" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, spec)


COLUMNS = ["case", "option", "resolution", "particles", "steps", "wall_s", "particle_steps_per_s",
           "peak_memory_mib", "error", "tolerance", "observed_order", "passed", "known_deviation", "failure", "gates"]


def read_previous(out, exclude, known):
    """Results of earlier runs stored in out/results.csv, for the cases not re-run now."""
    from verification.runner import Result
    path = os.path.join(out, "results.csv")
    if not os.path.exists(path):
        return []
    results = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["case"] in exclude or row["case"] not in known:
                continue
            results.append(Result(case=row["case"], option_label=row["option"], resolution=float(row["resolution"]),
                                  particles=int(row["particles"]), steps=int(row["steps"]), wall=float(row["wall_s"]),
                                  rate=float(row["particle_steps_per_s"]), memory=float(row["peak_memory_mib"]),
                                  error=float(row["error"]), tolerance=float(row["tolerance"]),
                                  order=float(row["observed_order"]), passed=row["passed"] == "True",
                                  failure=row["failure"], known=row.get("known_deviation") == "True",
                                  gates=[tuple(g) for g in json.loads(row.get("gates") or "[]")]))
    return results


def write(results, cases, out, quick=False):
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in results:
            w.writerow([r.case, r.option_label, r.resolution, r.particles, r.steps, r.wall, r.rate, r.memory,
                        r.error, r.tolerance, r.order, r.passed, r.known, r.failure, json.dumps(r.gates)])

    by_case = defaultdict(list)
    for r in results:
        by_case[r.case].append(r)
    plots = {}
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        for name, rs in by_case.items():
            fig, ax = plt.subplots(figsize=(5.5, 4))
            lines = defaultdict(list)
            for r in rs:
                if math.isfinite(r.error) and r.error > 0 and math.isfinite(r.wall):
                    lines[r.option_label].append((r.wall, r.error))
            if not lines:
                plt.close(fig)
                continue
            for option, points in sorted(lines.items()):
                points.sort()
                ax.loglog([p[0] for p in points], [p[1] for p in points], "o-", label=option)
            ax.set_xlabel("wall time [s]")
            ax.set_ylabel("error")
            ax.set_title(name)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
            fig.tight_layout()
            path = os.path.join(out, f"{name}.png")
            fig.savefig(path, dpi=110)
            plt.close(fig)
            plots[name] = os.path.basename(path)
    except ImportError:
        pass

    lines = ["# Talus verification report", "",
             f"Machine: {machine()}.", "",
             "Each case runs a resolution ladder with `talus run`; error is against the reference named below; "
             "wall time and throughput are from the run summary; the observed order compares each rung with the "
             "previous one. Regenerate with `python3 tools/verify.py` (full) or `--quick` (smallest rungs).", ""]
    if quick:
        lines += ["**Quick mode: smallest rung only, no option sweeps.**", ""]
    for case in cases:
        rs = by_case.get(case.NAME, [])
        lines += [f"## {case.NAME}: {case.TITLE}", "", f"Reference: {case.REFERENCE}. Error: {case.ERROR_LABEL}.", ""]
        if getattr(case, "KNOWN_DEVIATION", ""):
            lines += [f"**Known deviation (open):** {case.KNOWN_DEVIATION}", ""]
        if hasattr(case, "EXPECTED_ORDER"):
            lines += [f"Expected order of convergence: {case.EXPECTED_ORDER}.", ""]
        lines += ["| option | resolution | particles (blocks) | steps | wall [s] | M particle-steps/s | memory [MiB] | error | tolerance | order | result |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in rs:
            status = "pass" if r.passed else (f"FAIL (known deviation): {r.failure}" if r.known else f"FAIL: {r.failure}")
            lines.append(f"| {r.option_label} | {r.resolution:g} | {r.particles} | {r.steps} | {fmt(r.wall)} | "
                         f"{fmt(r.rate / 1e6 if math.isfinite(r.rate) else r.rate)} | {fmt(r.memory, '.0f')} | "
                         f"{fmt(r.error, '.4g')} | {fmt(r.tolerance)} | {fmt(r.order, '.2f')} | {status} |")
        gates = [(r, g) for r in rs for g in r.gates]
        if gates:
            lines += ["", "Stability gates:", ""]
            for r, (name, ok, value) in gates:
                lines.append(f"- {r.option_label}, resolution {r.resolution:g}: {name}: {'ok' if ok else 'FAILED'} ({value})")
        if case.NAME in plots:
            lines += ["", f"![error against wall time for {case.NAME}]({plots[case.NAME]})"]
        lines.append("")
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write("\n".join(lines))
    print(f"verify: report in {os.path.join(out, 'README.md')}")
