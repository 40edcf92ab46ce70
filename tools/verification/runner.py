"""Runs one case over its ladder and option sweep with the talus binary."""
import copy
import itertools
import json
import math
import os
import subprocess
import time
from dataclasses import dataclass, field


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
    error: float = float("nan")
    tolerance: float = float("nan")
    order: float = float("nan")  # observed, against the previous rung
    passed: bool = False
    failure: str = ""
    known: bool = False  # failed only its accuracy tolerance, a documented open deviation
    gates: list = field(default_factory=list)


def option_grid(case, quick):
    options = getattr(case, "OPTIONS", {}) if not quick else {}
    if not options:
        return [{}]
    keys = sorted(options)
    return [dict(zip(keys, values)) for values in itertools.product(*(options[k] for k in keys))]


def label(option):
    return ", ".join(f"{k}={v}" for k, v in sorted(option.items())) or "default"


def run_case(case, talus, root, out, quick=False, threads=2):
    ladder = list(case.LADDER)
    if quick:
        ladder = [ladder[getattr(case, "QUICK_INDEX", 0)]]
    results = []
    for option in option_grid(case, quick):
        previous = None
        for resolution in ladder:
            result = Result(case.NAME, label(option), resolution, tolerance=case.TOLERANCE.get(resolution, float("nan")))
            tag = "".join(c if c.isalnum() or c in "-_." else "_" for c in label(option))
            directory = os.path.join(out, "runs", case.NAME, tag, f"res_{resolution:g}")
            os.makedirs(directory, exist_ok=True)
            with open(os.path.join(root, case.SCENE)) as f:
                template = json.load(f)
            scene = case.configure(copy.deepcopy(template), resolution, option)
            scene_path = os.path.join(directory, "scene.json")
            with open(scene_path, "w") as f:
                json.dump(scene, f, indent=1)
            summary_path = os.path.join(directory, "summary.json")
            command = [talus, "run", scene_path, "--out", os.path.join(directory, "out"), "--quiet",
                       "--threads", str(threads), "--summary", summary_path]
            print(f"verify: {case.NAME} [{label(option)}] resolution {resolution:g} ...", flush=True)
            start = time.monotonic()
            proc = subprocess.run(command, capture_output=True, text=True)
            elapsed = time.monotonic() - start
            if proc.returncode != 0:
                result.failure = f"talus exited {proc.returncode}: {(proc.stderr or proc.stdout).strip()[:400]}"
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
            try:
                result.error = float(case.error(run))
                result.gates = list(case.gates(run)) if hasattr(case, "gates") else []
            except Exception as e:  # a metric that cannot be computed is a failure, with its reason
                result.failure = f"error metric failed: {e}"
                results.append(result)
                continue
            problems = []
            accuracy = []
            if not math.isfinite(result.error):
                problems.append("error is not finite")
            elif math.isfinite(result.tolerance) and result.error > result.tolerance:
                accuracy.append(f"error {result.error:.4g} above tolerance {result.tolerance:.4g}")
            problems += [f"gate '{g[0]}' failed ({g[2]})" for g in result.gates if not g[1]]
            if previous is not None and math.isfinite(previous.error) and result.error > 0 and previous.error > 0:
                result.order = math.log(previous.error / result.error) / math.log(previous.resolution / resolution)
                # A rung well inside its tolerance may plateau; one without a tolerance must fall.
                small = math.isfinite(result.tolerance) and result.error <= 0.5 * result.tolerance
                if getattr(case, "CONVERGES", True) and result.error > previous.error * 1.05 and not small:
                    accuracy.append(f"error does not fall with resolution ({previous.error:.4g} -> {result.error:.4g})")
            result.failure = "; ".join(problems + accuracy)
            result.passed = not problems and not accuracy
            result.known = not problems and bool(accuracy) and bool(getattr(case, "KNOWN_DEVIATION", ""))
            results.append(result)
            previous = result
    return results
