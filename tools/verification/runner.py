"""Runs one case over its ladder and option sweep with the talus binary."""
import copy
import itertools
import json
import math
import os
import re
import subprocess
import time
from dataclasses import dataclass, field

from verification.registry import is_hard


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


def option_grid(case, quick):
    options = getattr(case, "OPTIONS", {}) if not quick else {}
    if not options:
        return [{}]
    keys = sorted(options)
    return [dict(zip(keys, values)) for values in itertools.product(*(options[k] for k in keys))]


def label(option):
    return ", ".join(f"{k}={v}" for k, v in sorted(option.items())) or "default"


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


def run_case(case, talus, root, out, quick=False, threads=2, reuse=False, walls=None):
    """Runs the case's ladder (one rung with quick) and judges each run. With reuse, a rung whose folder already
    holds a summary of the same scene is judged again without running talus (new tolerances or gates). With walls
    ("dbc" or "mdbc"), every particle wall of the case's scenes uses that method, and the option label says so; a
    case without particle walls is skipped."""
    ladder = list(case.LADDER)
    if quick:
        ladder = [ladder[getattr(case, "QUICK_INDEX", 0)]]
    hard = is_hard(case)
    measure = case.worst if hard else case.error
    results = []
    for option in option_grid(case, quick):
        previous = None
        for resolution in ladder:
            with open(os.path.join(root, case.SCENE)) as f:
                template = json.load(f)
            scene = case.configure(copy.deepcopy(template), resolution, option)
            shown = dict(option)
            if walls:
                if not with_wall_method(scene, walls):
                    print(f"verify: {case.NAME}: no particle walls, --walls {walls} does not apply", flush=True)
                    return results
                shown["walls"] = walls
            result = Result(case.NAME, label(shown), resolution, tolerance=case.TOLERANCE.get(resolution, float("nan")),
                            hard=hard)
            tag = "".join(c if c.isalnum() or c in "-_." else "_" for c in label(shown))
            directory = os.path.join(out, "runs", case.NAME, tag, f"res_{resolution:g}")
            os.makedirs(directory, exist_ok=True)
            if hasattr(case, "prepare"):
                case.prepare(directory, scene, resolution)  # files the scene names beside it (a release raster)
            if quick and hasattr(case, "QUICK_END"):
                scene["time"]["end"] = case.QUICK_END  # the short variant --quick runs (still through the hard part)
            scene_path = os.path.join(directory, "scene.json")
            summary_path = os.path.join(directory, "summary.json")
            previous_scene = None
            if reuse and os.path.exists(summary_path) and os.path.exists(scene_path):
                with open(scene_path) as f:
                    previous_scene = json.load(f)
            if previous_scene == scene:
                print(f"verify: {case.NAME} [{label(shown)}] resolution {resolution:g}: judging the stored run", flush=True)
                proc = subprocess.CompletedProcess([], 0, "", "")
                elapsed = float("nan")
            else:
                with open(scene_path, "w") as f:
                    json.dump(scene, f, indent=1)
                if os.path.exists(summary_path):
                    os.remove(summary_path)  # never judge a stale summary
                command = [talus, "run", scene_path, "--out", os.path.join(directory, "out"), "--quiet",
                           "--threads", str(threads), "--summary", summary_path]
                print(f"verify: {case.NAME} [{label(shown)}] resolution {resolution:g} ...", flush=True)
                start = time.monotonic()
                proc = subprocess.run(command, capture_output=True, text=True)
                elapsed = time.monotonic() - start
            if proc.returncode != 0:
                result.failure = f"talus exited {proc.returncode}: {(proc.stderr or proc.stdout).strip()[:400]}"
                result.steps, result.sim_time = failed_at(proc.stderr)
                result.wall = elapsed
                results.append(result)
                continue
            with open(summary_path) as f:
                summary = json.load(f)
            run = Run(case.NAME, resolution, option, directory, scene, summary, proc.stdout)
            result.particles = summary["fluid_particles"] + summary.get("wall_particles", 0) or summary.get("blocks", 0)
            result.steps = summary["steps"]
            result.wall = summary["wall_seconds"] or elapsed
            result.rate = summary["particle_steps"] / result.wall if result.wall > 0 else float("nan")
            result.memory = summary["peak_memory_mib"]
            result.sim_time = summary.get("time", float("nan"))
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
