"""What the tessellation tools' tests share: pass/fail lines, writing a scene with a tool, running talus on it, and the
chain's hand-off and run-out checks."""
import json
import os
import re
import shutil
import subprocess
import sys

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def finish():
    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)


def write_scene(tool, work, name, *args):
    """Runs tools/TOOL.py ARGS --out WORK/NAME.json (removed first); returns (process, path)."""
    path = os.path.join(work, name + ".json")
    if os.path.exists(path):
        os.remove(path)
    r = subprocess.run([sys.executable, tool, *args, "--out", path], capture_output=True, text=True)
    return r, path


def run(talus, work, scene, name, *options):
    """talus run SCENE --out WORK/NAME; returns (process, output folder, F_s or nan)."""
    out = os.path.join(work, name)
    shutil.rmtree(out, ignore_errors=True)
    r = subprocess.run([talus, "run", scene, "--out", out, *options], capture_output=True, text=True)
    m = re.search(r"F_s = ([0-9.]+) \(holds at ([0-9.]+), fails at ([0-9.]+)", r.stdout + r.stderr)
    return r, out, (float(m.group(1)) if m else float("nan"))


def check_handoff(written, ran):
    """The failing mass is more than one block and its volume reaches the thickness raster within 1 % (the issue's
    gate); returns the raster's volume (or None)."""
    text = ran.stdout + ran.stderr
    moved = re.search(r"the failing mass: (\d+) block\(s\) \(([0-9.]+) % of the free mass\)", text)
    volume = re.search(r"released volume ([0-9.e+]+) m\^3, in the thickness raster ([0-9.e+]+) m\^3", text)
    check(written.returncode == 0 and ran.returncode == 0 and moved is not None and int(moved.group(1)) > 1,
          "the failing mass: %s blocks, %s %% of the free mass" % (moved.group(1) if moved else "-",
                                                                   moved.group(2) if moved else "-"))
    check(volume is not None and abs(float(volume.group(2)) / float(volume.group(1)) - 1.0) < 0.01,
          "hand-off: %s m^3 of blocks, %s m^3 in the raster" % (volume.group(1) if volume else "-",
                                                                volume.group(2) if volume else "-"))
    return float(volume.group(2)) if volume else None


def check_runout_keeps_volume(talus, work, out, raster_volume, name):
    """Runs the hand-off's run-out scene (in OUT) for 5 s: it must keep the thickness raster's volume exactly."""
    runout = os.path.join(out, "strength_reduction_runout.json")
    if os.path.exists(runout):
        with open(runout) as f:
            s = json.load(f)
        s["time"]["end"] = 5.0
        with open(runout, "w") as f:
            json.dump(s, f)
    flowed, _, _ = run(talus, work, runout, name)
    deposit = re.search(r"deposit volume ([0-9.e+]+) m\^3", flowed.stdout + flowed.stderr)
    check(flowed.returncode == 0 and deposit is not None and raster_volume is not None
          and abs(float(deposit.group(1)) / raster_volume - 1.0) < 1e-6,
          "the run-out over the DEM keeps the raster's volume for 5 s: %s m^3" % (deposit.group(1) if deposit else "-"))
