"""Runs one case over its ladder and option sweep as a `talus study` (one variant per rung and option), and judges
each run."""
import copy
import itertools
import json
import math
import os
import re
import shutil
import subprocess
from dataclasses import dataclass, field

from verification.registry import is_hard
from verification.report import checkout_commit, processor


@dataclass
class Run:
    """A finished talus run: what error() and gates() look at."""
    case: str
    resolution: float
    option: dict
    directory: str  # output folder of the run
    scene: dict
    summary: dict
    log: str

    def output_files(self, writer):
        return self.summary.get("outputs", {}).get(writer, [])

    def hdf5(self):
        """The run's HDF5 file (H5Part layout), opened with h5py."""
        import h5py
        files = self.output_files("hdf5")
        if not files:
            raise RuntimeError("the run wrote no hdf5 output")
        return h5py.File(files[-1], "r")


@dataclass
class Result:
    case: str
    option_label: str
    resolution: float
    particles: int = 0
    steps: int = 0
    wall: float = float("nan")
    rate: float = float("nan")  # particle-steps per second
    memory: float = float("nan")  # MiB
    bytes_per_particle: float = float("nan")  # peak memory / particles (includes the process's fixed cost)
    sim_time: float = float("nan")  # simulated time reached, s
    error: float = float("nan")
    tolerance: float = float("nan")
    order: float = float("nan")  # observed, against the previous rung
    passed: bool = False
    failure: str = ""
    known: bool = False  # failed only its accuracy tolerance, a documented open deviation
    gates: list = field(default_factory=list)
    worst_density: float = float("nan")  # SPH runs: the wcsph stage's max |rho/rho0 - 1| over the whole run
    hard: bool = False  # a stability-only case: error is its worst() measure, tolerance the limit on it
    stable: bool = False  # hard cases: finished, worst() finite and within its limit, every gate passed
    directory: str = ""  # the run's folder (its scene, log, summary and outputs)
    in_float: str = ""  # the fields the run kept in float (summary "precision"); "none" in double
    commit: str = ""  # the checkout verify.py started the run's study from
    machine: str = ""  # the CPU and cores it ran on


def option_grid(case, quick):
    options = getattr(case, "OPTIONS", {}) if not quick else {}
    if not options:
        return [{}]
    keys = sorted(options)
    return [dict(zip(keys, values)) for values in itertools.product(*(options[k] for k in keys))]


def label(option):
    return ", ".join(f"{k}={v}" for k, v in sorted(option.items())) or "default"


def fields_in_float(summary):
    """The fields a run kept in float, from its summary's "precision" entry: "fluid: velocity_n, density_n; walls:
    density", or "none"; "" for a summary without the entry."""
    precision = summary.get("precision")
    if not isinstance(precision, dict):
        return ""
    parts = [f"{store}: {precision[key]}" for store, key in (("fluid", "fluid_in_float"), ("walls", "walls_in_float"))
             if precision.get(key, "none") != "none"]
    return "; ".join(parts) or "none"


def failed_at(text):
    """'step N (t = T s)' of a run that talus stopped, as (steps, time), else (0, nan)."""
    m = re.search(r"step (\d+) \(t = ([0-9.eE+-]+) s\)", text or "")
    return (int(m.group(1)), float(m.group(2))) if m else (0, float("nan"))


# The particle wall models that take a "method" (dynamic_particles, block_particles: dbc or mdbc).
PARTICLE_WALLS = ("dynamic_particles", "block_particles")


def with_wall_method(scene, method):
    """The scene with every particle wall's boundary "method" set to `method` (verify.py --walls); the number of
    walls changed (0: the case has none, and --walls does not apply to it)."""
    changed = 0
    for body in scene.get("bodies", []):
        boundary = body.get("boundary")
        if isinstance(boundary, dict) and boundary.get("type") in PARTICLE_WALLS:
            boundary["method"] = method
            changed += 1
    return changed


def with_prepared_files(scene, directory):
    """The scene with every relative file name that the case's prepare() wrote into `directory` made absolute: the
    study resolves relative names against its base scene's folder, which all variants share."""
    def walk(value):
        if isinstance(value, dict):
            return {k: walk(v) for k, v in value.items()}
        if isinstance(value, list):
            return [walk(v) for v in value]
        if isinstance(value, str) and value and not os.path.isabs(value) and os.path.isfile(os.path.join(directory, value)):
            return os.path.abspath(os.path.join(directory, value))
        return value
    return walk(scene)


def study_of(scenes):
    """(base scene, study) whose zipped variants are `scenes`: the first scene is the base, and an axis runs over
    each top-level key in which the scenes differ (a single scene: over its format version, one value)."""
    base = scenes[0]
    for scene in scenes[1:]:
        if set(scene) != set(base):
            raise ValueError("the case's variants differ in their top-level keys: "
                             f"{sorted(set(scene) ^ set(base))}")
    keys = [k for k in base if any(scene[k] != base[k] for scene in scenes[1:])] or ["talus"]
    token = lambda key: key.replace("~", "~0").replace("/", "~1")  # RFC 6901
    axes = [{"pointer": "/" + token(k), "name": k, "values": [scene[k] for scene in scenes]} for k in keys]
    return base, {"base": "base.json", "combine": "zip", "axes": axes,
                  "measures": [{"name": "steps", "summary": "/steps"}]}


def run_study(talus, directory, scenes, threads, jobs, reuse):
    """Runs the scenes as a study in `directory` (its variants in directory/variants/ID); the table's rows, in the
    order of the scenes. With reuse the study resumes (finished variants are not run again) when it is the one
    stored there; otherwise it starts afresh."""
    base, study = study_of(scenes)
    base_text, study_text = json.dumps(base, indent=1), json.dumps(study, indent=1)
    study_path, base_path = os.path.join(directory, "study.json"), os.path.join(directory, "base.json")
    variants = os.path.join(directory, "variants")
    stored = [open(p).read() if os.path.exists(p) else None for p in (base_path, study_path)]
    fresh = not (reuse and stored == [base_text, study_text])
    if fresh:
        shutil.rmtree(variants, ignore_errors=True)
    # Where the runs come from: this checkout and CPU when the study starts afresh; a reused study keeps what its
    # start recorded (runs it resumes now are counted to that start).
    origin_path = os.path.join(directory, "origin.json")
    if fresh or not os.path.exists(origin_path):
        with open(origin_path, "w") as f:
            json.dump({"commit": checkout_commit(), "machine": processor()}, f)
    with open(origin_path) as f:
        origin = json.load(f)
    with open(base_path, "w") as f:
        f.write(base_text)
    with open(study_path, "w") as f:
        f.write(study_text)
    command = [talus, "study", study_path, "--out", variants, "--jobs", str(jobs), "--threads", str(threads * jobs),
               "--retry-failed"]
    proc = subprocess.run(command, stderr=subprocess.PIPE, text=True)  # its progress lines go to our stdout
    if proc.returncode in (130, 143):
        raise KeyboardInterrupt(f"talus study stopped ({proc.returncode}): {proc.stderr.strip()}")
    table = os.path.join(variants, "table.json")
    if proc.returncode not in (0, 1) or not os.path.exists(table):
        message = f"talus study exited {proc.returncode}: {proc.stderr.strip()[:1000]}"
        return [{"status": "failed", "error": message}] * len(scenes)
    with open(table) as f:
        rows = json.load(f)["rows"]
    for row in rows:
        row["directory"] = os.path.join(variants, row["variant"])
        row.update(origin)
    return rows


def run_case(case, talus, root, out, quick=False, threads=2, reuse=False, walls=None, precision=None, jobs=1):
    """Runs the case's ladder (one rung with quick) over its options as one `talus study` in out/runs/CASE, `jobs`
    runs side by side with `threads` each, and judges each run. With reuse, a study stored there with the same
    variants is not run again (finished runs are judged again: new tolerances or gates). With walls ("dbc" or
    "mdbc"), every particle wall of the case's scenes uses that method, and the option label says so; a case
    without particle walls is skipped. With precision ("double" or "mixed"), every scene has that "precision"."""
    ladder = list(case.LADDER)
    if quick:
        ladder = [ladder[getattr(case, "QUICK_INDEX", 0)]]
    hard = is_hard(case)
    measure = case.worst if hard else case.error
    directory = os.path.join(out, "runs", case.NAME)
    planned = []  # (option, label, resolution, scene)
    for option in option_grid(case, quick):
        for resolution in ladder:
            with open(os.path.join(root, case.SCENE)) as f:
                template = json.load(f)
            scene = case.configure(copy.deepcopy(template), resolution, option)
            shown = dict(option)
            if walls:
                if not with_wall_method(scene, walls):
                    print(f"verify: {case.NAME}: no particle walls, --walls {walls} does not apply", flush=True)
                    return []
                shown["walls"] = walls
            if precision:
                scene["precision"] = precision
                shown["precision"] = precision
            if hasattr(case, "prepare"):  # files the scene names beside it (a release raster)
                files = os.path.join(directory, "files", f"{len(planned) + 1:03d}")
                os.makedirs(files, exist_ok=True)
                case.prepare(files, scene, resolution)
                scene = with_prepared_files(scene, files)
            if quick and hasattr(case, "QUICK_END"):
                scene["time"]["end"] = case.QUICK_END  # the short variant --quick runs (still through the hard part)
            planned.append((option, label(shown), resolution, scene))
    os.makedirs(directory, exist_ok=True)
    print(f"verify: {case.NAME}: " + ", ".join(f"{k + 1:03d} [{p[1]}] resolution {p[2]:g}" for k, p in enumerate(planned)),
          flush=True)
    rows = run_study(talus, directory, [p[3] for p in planned], threads, jobs, reuse)

    results = []
    previous, ladder_of = None, None
    for (option, shown, resolution, scene), row in zip(planned, rows):
        if shown != ladder_of:
            previous, ladder_of = None, shown  # the ladder starts again for the next option
        result = Result(case.NAME, shown, resolution, tolerance=case.TOLERANCE.get(resolution, float("nan")),
                        hard=hard, directory=row.get("directory", ""), commit=row.get("commit", ""),
                        machine=row.get("machine", ""))
        log = ""
        if result.directory and os.path.exists(os.path.join(result.directory, "run.log")):
            with open(os.path.join(result.directory, "run.log")) as f:
                log = f.read()
        if row["status"] != "done":
            result.failure = f"talus run failed: {str(row.get('error') or row['status']).strip()[:400]}"
            result.steps, result.sim_time = failed_at(log)
            results.append(result)
            continue
        with open(os.path.join(result.directory, "summary.json")) as f:
            summary = json.load(f)
        run = Run(case.NAME, resolution, option, result.directory, scene, summary, log)
        result.particles = summary["fluid_particles"] + summary.get("wall_particles", 0) or summary.get("blocks", 0)
        result.steps = summary["steps"]
        result.wall = summary["wall_seconds"]
        result.rate = summary["particle_steps"] / result.wall if result.wall > 0 else float("nan")
        result.memory = summary["peak_memory_mib"]
        result.sim_time = summary.get("time", float("nan"))
        result.in_float = fields_in_float(summary)
        match = re.search(r"worst ([0-9.eE+-]+)%", summary.get("stages", {}).get("wcsph", ""))
        if match:
            result.worst_density = float(match.group(1)) / 100.0
        if result.particles > 0:
            result.bytes_per_particle = result.memory * 1024 * 1024 / result.particles
        try:
            result.error = float(measure(run))
            result.gates = list(case.gates(run)) if hasattr(case, "gates") else []
        except Exception as e:  # a metric that cannot be computed is a failure, with its reason
            result.failure = f"{'worst measure' if hard else 'error metric'} failed: {e}"
            results.append(result)
            continue
        problems = []
        accuracy = []
        if not math.isfinite(result.error):
            problems.append(f"worst {case.WORST_LABEL} is not finite" if hard else "error is not finite")
        elif math.isfinite(result.tolerance) and result.error > result.tolerance:
            accuracy.append(f"error {result.error:.4g} above tolerance {result.tolerance:.4g}")
        problems += [f"gate '{g[0]}' failed ({g[2]})" for g in result.gates if not g[1]]
        if hard:
            # Stability only: the worst measure must stay within its limit; no convergence is asked.
            problems += [f"worst {case.WORST_LABEL} {a[len('error '):]}" for a in accuracy]
            accuracy = []
        elif previous is not None and math.isfinite(previous.error) and result.error > 0 and previous.error > 0:
            result.order = math.log(previous.error / result.error) / math.log(previous.resolution / resolution)
            # A rung well inside its tolerance may plateau; one without a tolerance must fall.
            small = math.isfinite(result.tolerance) and result.error <= 0.5 * result.tolerance
            if getattr(case, "CONVERGES", True) and result.error > previous.error * 1.05 and not small:
                accuracy.append(f"error does not fall with resolution ({previous.error:.4g} -> {result.error:.4g})")
        result.failure = "; ".join(problems + accuracy)
        result.passed = not problems and not accuracy
        result.known = not problems and bool(accuracy) and bool(getattr(case, "KNOWN_DEVIATION", ""))
        result.stable = hard and result.passed
        results.append(result)
        previous = result
    return results
