"""Markdown tables, CSV and log-log plots of error against wall time."""
import csv
import json
import math
import os
import platform
import subprocess
from collections import defaultdict


def processor():
    """The CPU and its core count, as a row of results.csv records where it ran."""
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores"


def machine():
    return f"{processor()}, {platform.system()} {platform.release()}, commit {checkout_commit()}"


def stored_machine(out):
    """The machine line of the report already in out (without "Machine: "), or None."""
    try:
        with open(os.path.join(out, "README.md")) as f:
            for line in f:
                if line.startswith("Machine: "):
                    return line[len("Machine: "):].strip().rstrip(".")
    except OSError:
        pass
    return None


def checkout_commit():
    """The short commit of the checkout this harness runs from ("?" outside git)."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    try:
        commit = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip()
    except OSError:
        commit = ""
    return commit or "?"


def fmt(x, spec=".3g"):
    return "—" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, spec)


COLUMNS = ["case", "option", "resolution", "particles", "steps", "wall_s", "particle_steps_per_s",
           "peak_memory_mib", "error", "tolerance", "observed_order", "passed", "known_deviation", "failure", "gates",
           "sim_time_s", "bytes_per_particle", "hard_case", "stable", "worst_density_deviation", "in_float", "commit", "machine"]


def number(row, key):
    """A float column of results.csv; nan when an older file lacks it."""
    try:
        return float(row.get(key) or "nan")
    except ValueError:
        return float("nan")


def cell(text):
    """Text safe inside a Markdown table cell (labels such as max |rho/rho0 - 1| carry pipes)."""
    return str(text).replace("|", "\\|").replace("\n", " ")


def marginal_bytes(coarse, fine):
    """(peak memory difference) / (particle difference) between two rungs: the cost of one more particle, without
    the process's fixed cost; nan for the first rung or when the count does not grow by at least half."""
    if coarse is None or not (fine.particles > 1.5 * coarse.particles > 0):
        return float("nan")
    return (fine.memory - coarse.memory) * 1024 * 1024 / (fine.particles - coarse.particles)


def fmt_bytes(x):
    if not math.isfinite(x):
        return "—"
    if x <= 0:
        return "≈0 (under the fixed cost)"
    if x >= 1024 * 1024:
        return f"{x / 1024 / 1024:.3g} MiB"
    return f"{x / 1024:.3g} KiB" if x >= 1024 else f"{x:.0f} B"


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
                                  gates=[tuple(g) for g in json.loads(row.get("gates") or "[]")],
                                  sim_time=number(row, "sim_time_s"), bytes_per_particle=number(row, "bytes_per_particle"),
                                  hard=row.get("hard_case") == "True", stable=row.get("stable") == "True",
                                  worst_density=number(row, "worst_density_deviation"),
                                  in_float=row.get("in_float") or "", commit=row.get("commit") or "",
                                  machine=row.get("machine") or ""))
    return results


def write(results, cases, out, quick=False, header=None, with_plots=True):
    """The report in out: README.md, results.csv and a plot per case. header is the machine line of the report's
    own run (default: this machine and checkout); a case whose rows ran elsewhere says where."""
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in results:
            w.writerow([r.case, r.option_label, r.resolution, r.particles, r.steps, r.wall, r.rate, r.memory,
                        r.error, r.tolerance, r.order, r.passed, r.known, r.failure, json.dumps(r.gates),
                        r.sim_time, r.bytes_per_particle, r.hard, r.stable, r.worst_density, r.in_float, r.commit,
                        r.machine])

    by_case = defaultdict(list)
    for r in results:
        by_case[r.case].append(r)
    header = header or machine()
    plots = plot_cases(by_case, out) if with_plots else {}

    lines = ["# Talus verification report", "",
             f"Machine: {header}.", "",
             "Each case runs its resolution ladder as a `talus study` (a run per rung and option); error is against the reference named below; "
             "wall time and throughput are from the run summary; the observed order compares each rung with the "
             "previous one. Regenerate with `python3 tools/verify.py` (full) or `--quick` (smallest rungs).", ""]
    if quick:
        lines += ["**Quick mode: smallest rung only, no option sweeps.**", ""]
    if os.path.exists(os.path.join(out, "precision.md")):
        lines += ["Precision: every run here is in double. [precision.md](precision.md) sets the same rungs run in "
                  "mixed precision beside them, and says which precision is the default and why.", ""]
    lines += ["Memory is the run's peak resident set (whole process, so small runs are dominated by the fixed cost "
              "of the binary and its plugins); per particle is that peak divided by the fluid + wall particles "
              "(blocks for DDA-only runs); marginal per particle is the growth of the peak from the previous rung "
              "divided by the growth of the particle count (the cost of one more particle).", ""]
    hard_cases = [c for c in cases if getattr(c, "HARD_CASE", False)]
    for case in cases:
        if getattr(case, "HARD_CASE", False):
            continue
        rs = by_case.get(case.NAME, [])
        lines += [f"## {case.NAME}: {case.TITLE}", "", f"Reference: {case.REFERENCE}. Error: {case.ERROR_LABEL}.", ""]
        where = sorted({(r.commit, r.machine) for r in rs if r.commit})
        if where and not all(header.endswith(f"commit {commit}") and header.startswith(cpu) for commit, cpu in where):
            lines += ["Run " + "; ".join(f"at commit {commit}" + (f" on {cpu}" if cpu else "") for commit, cpu in where)
                      + " (the rest of the report as named at the top).", ""]
        if getattr(case, "KNOWN_DEVIATION", ""):
            lines += [f"**Known deviation (open):** {case.KNOWN_DEVIATION}", ""]
        if hasattr(case, "EXPECTED_ORDER"):
            lines += [f"Expected order of convergence: {case.EXPECTED_ORDER}.", ""]
        sph = any(math.isfinite(r.worst_density) for r in rs)
        lines += ["| option | resolution | particles (blocks) | steps | wall [s] | M particle-steps/s | memory [MiB] | memory per particle | marginal per particle | "
                  + ("worst \\|rho/rho0 - 1\\| | " if sph else "") + "error | tolerance | order | result |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|" + ("---|" if sph else "")]
        previous = {}
        for r in rs:
            marginal = marginal_bytes(previous.get(r.option_label), r)
            previous[r.option_label] = r
            status = cell("pass" if r.passed else (f"FAIL (known deviation): {r.failure}" if r.known else f"FAIL: {r.failure}"))
            lines.append(f"| {r.option_label} | {r.resolution:g} | {r.particles} | {r.steps} | {fmt(r.wall)} | "
                         f"{fmt(r.rate / 1e6 if math.isfinite(r.rate) else r.rate)} | {fmt(r.memory, '.0f')} | "
                         f"{fmt_bytes(r.bytes_per_particle)} | {fmt_bytes(marginal)} | " + (f"{fmt(r.worst_density * 100, '.3g')} % | " if sph else "") +
                         f"{fmt(r.error, '.4g')} | {fmt(r.tolerance)} | {fmt(r.order, '.2f')} | {status} |")
        gates = [(r, g) for r in rs for g in r.gates]
        if gates:
            lines += ["", "Stability gates:", ""]
            for r, (name, ok, value) in gates:
                lines.append(f"- {r.option_label}, resolution {r.resolution:g}: {name}: {'ok' if ok else 'FAILED'} ({value})")
        if case.NAME in plots:
            lines += ["", f"![error against wall time for {case.NAME}]({plots[case.NAME]})"]
        lines.append("")
    if hard_cases:
        lines += hard_case_section(hard_cases, by_case)
    with open(os.path.join(out, "README.md"), "w") as f:
        f.write("\n".join(lines))
    print(f"verify: report in {os.path.join(out, 'README.md')}")


def plot_cases(by_case, out):
    """A log-log plot of error against wall time per case with errors (PNG in out): {case: file name}."""
    plots = {}
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        for name, rs in by_case.items():
            if any(r.hard for r in rs):
                continue  # stability only: no error to plot against wall time
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
    return plots


def hard_case_section(cases, by_case):
    """The "Hard cases (stability)" table: one row per rung; stable means talus finished, the worst measure over
    the whole run stayed within its limit and every gate passed."""
    lines = ["## Hard cases (stability)", "",
             "Stability only, no reference solution: each run must finish without a non-finite state, keep its worst "
             "measure over the whole run (not only at the end) within the limit, and pass every gate. For SPH cases "
             "the worst measure is the wcsph stage's running maximum of max |rho/rho0 - 1|, checked after every "
             "step; the other cases name theirs.", "",
             "| case | what it stresses | resolution | particles (blocks) | steps | simulated [s] | wall [s] | memory [MiB] | memory per particle | stable | worst measure | worst | limit | gates |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in cases:
        for r in by_case.get(case.NAME, []):
            gates = cell("; ".join(f"{name}: {'ok' if ok else 'FAILED'} ({value})" for name, ok, value in r.gates) or "—")
            stable = "yes" if r.stable else f"**NO**: {cell(r.failure)}"
            option = "" if r.option_label == "default" else f" [{r.option_label}]"
            lines.append(f"| {case.NAME}{option} | {cell(case.STRESSES)} | {r.resolution:g} | {r.particles} | {r.steps} | "
                         f"{fmt(r.sim_time, '.4g')} | {fmt(r.wall)} | {fmt(r.memory, '.0f')} | "
                         f"{fmt_bytes(r.bytes_per_particle)} | {stable} | {cell(case.WORST_LABEL)} | {fmt(r.error, '.3g')} | "
                         f"{fmt(r.tolerance, '.3g')} | {gates} |")
    lines += [""]
    for case in cases:
        lines += [f"- **{case.NAME}**: {case.TITLE}. Scene: `{case.SCENE}`."]
    return lines + [""]
