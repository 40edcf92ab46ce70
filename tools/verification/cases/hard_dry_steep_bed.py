"""Hard case: depth-integrated run-out of a mass down a dry 45 degree slope onto a dry flat bed."""
import math

import numpy as np

from verification.cases._util import cached, frames, set_dp

HARD_CASE = True
NAME = "hard_dry_steep_bed"
TITLE = ("Dry steep bed: 1 m thick Coulomb mass (20 degrees) released on a dry 45 degree slope, running out onto a "
         "dry flat bed (depth-integrated SPH), 6 s")
STRESSES = "wet-dry fronts on a steep slope and at the slope break; thin layers at the front"
SCENE = "share/verification/hard_dry_steep_bed.json"
LADDER = [0.5, 0.25, 0.125]
QUICK_INDEX = 0
WORST_LABEL = "max speed over the run / free-fall speed sqrt(2 g dz) from the release top"
# Energy bound: friction only takes energy away, so no particle may be faster than free fall from the top of the
# release to the flat bed (ratio 1); a front that blows up at a dry cell or the slope break exceeds it.
TOLERANCE = {0.5: 1.0, 0.25: 1.0, 0.125: 1.0}
G, SLOPE, FOOT = 9.81, math.radians(45.0), 10.0


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["outputs"] = [{"type": "hdf5", "every": 0.1, "fields": ["depth", "velocity", "speed", "volume"]}]
    return scene


@cached
def scan(run):
    """Per frame: volume, min depth, non-finite count, max speed; plus the particle count of the first frame."""
    volumes, min_depth, bad, vmax, counts, front = [], np.inf, 0, 0.0, [], 0.0
    for _, f in frames(run):
        front = max(front, float(np.max(f["x"])))
        h, v = f["depth"], f["speed"]
        bad += int(np.sum(~np.isfinite(h)) + np.sum(~np.isfinite(v)) + np.sum(~np.isfinite(f["volume"])))
        min_depth = min(min_depth, float(np.nanmin(h)))
        vmax = max(vmax, float(np.nanmax(v)))
        volumes.append(float(np.sum(f["volume"])))
        counts.append(f["x"].size)
    return volumes, min_depth, bad, vmax, counts, front


def free_fall(run):
    box = run.scene["bodies"][0]["shape"]["box"]
    return math.sqrt(2 * G * math.tan(SLOPE) * (FOOT - box["min"][0]))


def worst(run):
    return scan(run)[3] / free_fall(run)


def gates(run):
    volumes, min_depth, bad, vmax, counts, front = scan(run)
    mass_error = max(abs(v / volumes[0] - 1.0) for v in volumes)
    return [("reached the end", run.summary["time"] >= run.scene["time"]["end"] * (1 - 1e-9),
             f"t = {run.summary['time']:.4g} s"),
            ("no non-finite depth, speed or volume (any frame)", bad == 0, f"{bad} non-finite values"),
            ("depth h >= 0 (any frame)", min_depth >= 0.0, f"min h {min_depth:.3g} m"),
            ("mass conserved: no particle lost, volume constant to 1e-9 (any frame)",
             run.summary.get("removed", 0) == 0 and min(counts) == max(counts) and mass_error <= 1e-9,
             f"{run.summary.get('removed', 0)} removed, {min(counts)}..{max(counts)} particles, "
             f"volume error {mass_error:.2g}"),
            ("runs out onto the flat bed (the front passes the slope foot)", front > FOOT,
             f"front at x = {front:.3g} m, max speed {vmax:.3g} m/s")]
