"""2D dam break: surge front against Martin & Moyce (1952).

The front is the leading edge of the continuous water: the largest x of the fluid particles connected to the
column (particles within the kernel support 2h = 3 dp of each other are linked; droplets and jets
detached ahead of the surge would not count) plus half a spacing, the edge of the outermost particle's volume, so
that Z = 1 exactly at T = 0 (the column is a wide; x.max() alone reads 1 - dp/(2a)). Measured at dp = a/20 and a/40
(T <= 3.2): no particle is ever detached ahead of the front, so the connectivity never changes the result; the
half spacing adds 0.7-1.3 points to the error.

What was checked (the numbers the issue asked for, dp = a/20 | a/40, mean |Z_sim - Z_exp| / Z_exp, T <= 3):
  - x.max(): 9.0 % | 12.4 %; this front (edge of connected water): 10.3 % | 13.1 %; the edge where the
    depth first falls below 0.1a: 6.2 % | 9.1 % (a threshold on the depth is a choice the photographs do not
    define, so it is not used; it does not remove the trend either).
  - The error is a lead in time, not in speed: shifting the simulated curve by a constant Delta T = 0.17-0.23
    leaves 1.6-1.8 % (every front definition, both resolutions); the lead is there at the first measured point
    (T = 0.84: Z = 1.32 simulated, 1.22-1.25 measured), i.e. in the first 10-15 ms of the collapse.
  - The initial state is right when dp divides a (the ladder's spacings): the column starts a wide and 2a high,
    hydrostatic; the dynamic-boundary gap does not push it off the left wall (its rear stays at 0.50-0.54 dp from
    the wall surface through T = 1). The former rung dp = 0.0035 did not divide a: 29 particles, 1.015a wide.
  - Bottom friction: water's own viscosity (laminar, 1e-3 Pa s, no-slip wall) instead of alpha = 0.01 makes the
    front faster, not slower (a/20: 9.9 % for x.max()): the wall shear of a boundary layer ~0.3 mm thick is not
    resolved at dp = 2.5-5 mm, and the front's tip slides on the dynamic-boundary gap (tip particles 2 dp above the
    floor). The error growing with resolution is the solution approaching the frictionless limit.
  - Discretisation and solver settings (a/20 | a/40, mean error and best shift Delta T; the scene: Wendland C2,
    h = 1.5 dp, c0 = 28 m/s, symplectic, Courant 0.2, Fourtakas diffusion: 10.3 % 0.20 | 13.1 % 0.23):
    c0 = 56 m/s 9.4 % 0.18 | 12.0 % 0.22; cubic spline 8.7 % 0.17 | 11.8 % 0.22; Wendland C4 with h = 2 dp
    8.9 % 0.18 | 12.0 % 0.22; Wendland C2 with h = 2 dp 7.8 % 0.15 | 11.5 % 0.21; no density diffusion
    9.0 % 0.18 | 12.3 % 0.23; predictor-corrector, and Courant 0.05 (4 times the steps), the same as the scene to
    three digits. The settings that smooth more are slower at a/20; at a/40 they all lie within 1.6 points. The
    scene at a/50 gives 13.6 % and 0.24, at a/60 13.9 % and 0.24: the lead settles near Delta T = 0.24 as the
    resolution rises, whatever the setting, so it belongs to the model's converged solution, not to one setting.
  - A second measurement of the same column (n^2 = 2), Koshizuka & Oka (1996), as digitised in PySPH's
    examples (db_exp_data.py, not in shared/validation-data), lies slower still: 9.2 % | 11.4 %.
  - Remaining likely cause, outside the model: the release of the column in the experiment (the barrier's removal
    takes a finite time; published SPH and MPS results lead by a similar offset). It is not corrected for: a time
    shift fitted to the data would be tuning. One check on that cause: fitted to each column size alone (a/50),
    the best shift is Delta T = 0.235 for a = 1.125 in and 0.265 for a = 2.25 in (9 and 14 ms). A release of
    fixed duration would give the small column a lead sqrt(2) times larger in T, so if the release is the cause,
    its duration grew with the column (4-5 points per size: a weak test).
"""
import math
import os

import numpy as np

from verification.cases._util import frames, read_csv, set_dp

NAME = "martin_moyce_front"
TITLE = "2D dam break (column height 2a), surge front against Martin & Moyce (1952)"
SCENE = "share/scenes/dam_break_2d_martin_moyce.json"
# a/20, a/25, a/40, a/50: spacings that divide a and 2a, so the column is exactly a wide and 2a high (the host fills
# a box with round(L/dp) particles per axis: dp = 0.0035 gave 29 dp = 1.015a, a front at Z = 1.015 at T = 0, ahead
# of Ritter's bound, and 1.25 % too much water).
LADDER = [0.005, 0.004, 0.0025, 0.002]
# The two measured column sizes differ by about 7 %: that spread is the tolerance.
TOLERANCE = {dp: 0.07 for dp in LADDER}
KNOWN_DEVIATION = ("the simulated front leads the measurements by a constant time offset Delta T = 0.20-0.24 "
                   "(10 % mean deviation at dp = a/20, 13-14 % at a/40-a/50, growing with resolution as the "
                   "solution nears the frictionless limit; after the shift 1.7 %); the front speed is within the "
                   "measured spread. Front definition, initial state, water's viscosity, kernel, h/dp, c0, "
                   "integrator and time step were ruled out (module docstring); the experiment's release is the "
                   "likely cause. The water SPH issue stays open on this point.")
ERROR_LABEL = "mean |Z_sim - Z_exp| / Z_exp over the measured points with T <= 3 (both column sizes)"
REFERENCE = "Martin & Moyce (1952) Fig. 3, n^2 = 2, a = 1.125 in and 2.25 in (shared/validation-data)"
A, G = 0.1, 9.81
OPTIONS = {"density_diffusion": ["fourtakas", "molteni"]}
DATA = os.path.join(os.path.dirname(__file__), "..", "..", "..", "..", "shared", "validation-data")


def configure(scene, dp, option):
    set_dp(scene, dp)
    scene["outputs"] = [{"type": "hdf5", "every": 0.005, "fields": ["velocity"]}]
    scene["time"]["end"] = 3.2 / math.sqrt(2 * G / A)
    if option:
        scene["pipeline"][0].update(option)
    return scene


MEASURED = ("dambreak_martin_moyce1952_n2eq2_a1.125in.csv", "dambreak_martin_moyce1952_n2eq2_a2.25in.csv")


def measured_series(name):
    """(T, Z) of one measured column size, every point."""
    rows = read_csv(os.path.join(DATA, name))
    return rows["T"], rows["Z"]


def measured():
    """(T, Z) points of both column sizes with T <= 3."""
    points = np.concatenate([np.column_stack(measured_series(name)) for name in MEASURED])
    return points[points[:, 0] <= 3.0]


def connected(x, y, dp):
    """Mask of the particles connected to the column's rear at the left wall: two particles are linked when they
    are within the kernel support 2h = 3 dp (h = 1.5 dp in the scene) of each other."""
    reach = 3.0 * dp
    points = np.column_stack([x, y])
    try:
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components
        from scipy.spatial import cKDTree
        pairs = cKDTree(points).query_pairs(reach, output_type="ndarray")
        n = len(x)
        graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
        _, label = connected_components(graph, directed=False)
    except ImportError:  # without scipy: cells of size `reach`, linked to their 8 neighbours (a little generous)
        cell = [tuple(c) for c in np.floor(points / reach).astype(int).tolist()]
        ids = {c: k for k, c in enumerate(dict.fromkeys(cell))}
        parent = list(range(len(ids)))

        def root(k):
            while parent[k] != k:
                parent[k] = parent[parent[k]]
                k = parent[k]
            return k
        for c, k in ids.items():
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    other = ids.get((c[0] + dx, c[1] + dy))
                    if other is not None:
                        parent[root(other)] = root(k)
        label = np.array([root(ids[c]) for c in cell])
    rear = label[np.argmin(x)]
    return label == rear


def front_history(run):
    """T and Z of the leading edge of the continuous water (module docstring)."""
    dp = run.scene["bodies"][0]["dp"]
    t, z = [], []
    for time, f in frames(run):
        x = f["x"]
        t.append(time * math.sqrt(2 * G / A))
        z.append((x[connected(x, f["y"], dp)].max() + 0.5 * dp) / A)
    return np.array(t), np.array(z)


def error(run):
    T, Z = front_history(run)
    data = measured()
    simulated = np.interp(data[:, 0], T, Z)
    return float(np.mean(np.abs(simulated - data[:, 1]) / data[:, 1]))


def slope(T, Z, t0=1.5, t1=3.0):
    """Least-squares dZ/dT over [t0, t1]."""
    m = (T >= t0) & (T <= t1)
    return float(np.polyfit(T[m], Z[m], 1)[0])


def gates(run):
    T, Z = front_history(run)
    t = T / math.sqrt(2 * G / A)
    ritter = 1.0 + 2.0 * math.sqrt(G * 2 * A) * t / A
    data = measured()
    speeds = [slope(*measured_series(name)) for name in MEASURED]
    speed = slope(T, Z)
    # Diagnostic: the constant time shift that best aligns the curves, and what it leaves (not the error).
    shifts = np.arange(0.0, 0.4001, 0.01)
    left = [np.mean(np.abs(np.interp(data[:, 0] - s, T, Z) - data[:, 1]) / data[:, 1]) for s in shifts]
    best = int(np.argmin(left))
    return [("never faster than Ritter's front 2 sqrt(gH)", bool(np.all(Z <= ritter + 1e-9)),
             f"max Z - Z_Ritter {np.max(Z - ritter):.3g}"),
            ("front speed dZ/dT over 1.5 <= T <= 3 within the measured speeds +-7 %",
             min(speeds) * 0.93 <= speed <= max(speeds) * 1.07,
             f"{speed:.3f}, measured {speeds[0]:.3f} and {speeds[1]:.3f}; best constant time shift "
             f"Delta T = {shifts[best]:.2f} leaves {left[best]:.1%}")]
