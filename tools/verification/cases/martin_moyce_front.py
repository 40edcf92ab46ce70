"""2D dam break: surge front against Martin & Moyce (1952).

The front is the leading edge of the continuous water: the largest x of the fluid particles connected to the
column (particles within the kernel support 2h = 3 dp of each other are linked; droplets and jets
detached ahead of the surge would not count) plus half a spacing, the edge of the outermost particle's volume, so
that Z = 1 exactly at T = 0 (the column is a wide; x.max() alone reads 1 - dp/(2a)). Measured at dp = a/20 and a/40
(T <= 3.2): no particle is ever detached ahead of the front, so the connectivity never changes the result; the
half spacing adds 0.7-1.3 points to the error.

The experiment's time origin. An instantaneous release leads the measured front by a constant time offset: the
simulated front speed matches the measured one, but the curve runs ahead by Delta T ~ 0.2 from the first measured
point on (T = 0.84: Z = 1.32 simulated, 1.22-1.25 measured), i.e. within the first 10-15 ms of the collapse. This is
not particular to this model:
  - converged Navier-Stokes solutions lead the same data by the same amount: Lethe's VOF example of this experiment
    (chaos-polymtl/lethe, examples/multiphysics/dam-break/dam-break-2d.py) adds time_correction = 0.175 to the
    simulated T; an OpenFOAM interFoam validation (vamseeachanta/digitalmodel PR 1260, meshes a/36 and a/18 giving
    the same answer) reports a mean deviation of 9.8 % uncorrected and 3.0 % with that correction. Against the same
    digitisation (Lethe's 13 points, T <= 2.96) this model gives 8.6 % uncorrected at a/20, 11.0 % at a/40, 11.7 % at
    a/60, and 2.0-3.6 % corrected;
  - the model's own lead belongs to its converged solution, not to one setting. Varied one at a time (a/20 | a/40,
    uncorrected mean error and best shift; the scene: Wendland C2, h = 1.5 dp, c0 = 28 m/s, symplectic, Courant 0.2,
    Fourtakas diffusion: 10.3 % 0.20 | 13.1 % 0.23): c0 = 56 m/s 9.4 % 0.18 | 12.0 % 0.22; cubic spline 8.7 % 0.17
    | 11.8 % 0.22; Wendland C4, h = 2 dp 8.9 % 0.18 | 12.0 % 0.22; Wendland C2, h = 2 dp 7.8 % 0.15 | 11.5 % 0.21;
    no density diffusion 9.0 % 0.18 | 12.3 % 0.23; predictor-corrector and Courant 0.05 as the scene to three
    digits; a/50 13.6 % 0.24, a/60 13.9 % 0.24. Water's own viscosity (laminar, no-slip wall) instead of
    alpha = 0.01 makes the front faster, not slower: the wall's boundary layer (~0.3 mm) is not resolved, so the
    solution approaches the frictionless limit as dp falls and the lead grows towards Delta T = 0.24;
  - the initial state is right when dp divides a (the ladder's spacings): the column starts a wide and 2a high,
    hydrostatic, and its rear stays at 0.50-0.54 dp from the left wall through T = 1;
  - Koshizuka & Oka's (1996) measurement of the same column (PySPH's db_exp_data.py, not in share/validation-data)
    lies slower still (uncorrected 9.2 % | 11.4 %).
The likely cause is the release in the experiment (the barrier's removal takes a few milliseconds). One check
does not support it: fitted to each column size alone (a/50) the best shift is 0.235 for a = 1.125 in and 0.265
for a = 2.25 in, where a release of fixed duration would give the small column a shift sqrt(2) times larger
(with 4-5 points per size a weak test). No primary source prescribes a shift (the 0.175 is another project's
example), so the error is taken on the raw clock, T_sim against T_exp, and the case is a known deviation: the raw
error exceeds the experimental spread. The figure on Lethe's shifted clock (T_sim + 0.175) and the shift that
would fit best are reported beside it as a gate's diagnostic, labelled, so that a change in the lead stays
visible; neither is gated on.

Against measured data the error does not have to fall with resolution: once the discretisation error is below the
experimental scatter (the two column sizes differ by ~7 %), what is left is the model-experiment difference
(CONVERGES = False). Convergence of the wcsph stage is shown against analytic solutions (poiseuille_2d).
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
CONVERGES = False
# Lethe's correction of the time origin for this experiment (module docstring): reported, not gated on.
LETHE_SHIFT = 0.175
ERROR_LABEL = ("mean |Z_sim - Z_exp| / Z_exp over the measured points with T <= 3 (both column sizes), on the raw "
               "clock (no time shift)")
KNOWN_DEVIATION = (
    "On the raw clock the simulated front leads the measured one by Delta T ~ 0.2 from the first measured point on "
    "(module docstring: converged Navier-Stokes solutions share the lead), so the error (8-14 % over the ladder) "
    "exceeds the 7 % spread of the two column sizes. Shifting the clock would pass, but no primary source gives the "
    "shift; issue 22 stays open on it, to report the raw-clock error with mDBC and no-slip walls.")
REFERENCE = "Martin & Moyce (1952) Fig. 3, n^2 = 2, a = 1.125 in and 2.25 in (share/validation-data)"
A, G = 0.1, 9.81
OPTIONS = {"density_diffusion": ["fourtakas", "molteni"]}
DATA = os.path.join(os.path.dirname(__file__), "..", "..", "..", "share", "validation-data")


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


def deviation(T, Z, shift, data):
    """Mean relative deviation from the measured (T, Z) points `data` with the simulated time moved forward by
    `shift`."""
    simulated = np.interp(data[:, 0] - shift, T, Z)
    return float(np.mean(np.abs(simulated - data[:, 1]) / data[:, 1]))


def error(run):
    return deviation(*front_history(run), 0.0, measured())


def slope(T, Z, t0=1.5, t1=3.0):
    """Least-squares dZ/dT over [t0, t1]."""
    m = (T >= t0) & (T <= t1)
    return float(np.polyfit(T[m], Z[m], 1)[0])


def gates(run):
    T, Z = front_history(run)
    t = T / math.sqrt(2 * G / A)
    ritter = 1.0 + 2.0 * math.sqrt(G * 2 * A) * t / A
    speeds = [slope(*measured_series(name)) for name in MEASURED]
    speed = slope(T, Z)
    # Diagnostic, not gated on: the deviation on Lethe's shifted clock, and the constant shift that would fit best.
    data = measured()
    shifts = np.arange(0.0, 0.4001, 0.01)
    left = [deviation(T, Z, s, data) for s in shifts]
    best = int(np.argmin(left))
    lethe = deviation(T, Z, LETHE_SHIFT, data)
    return [("never faster than Ritter's front 2 sqrt(gH)", bool(np.all(Z <= ritter + 1e-9)),
             f"max Z - Z_Ritter {np.max(Z - ritter):.3g}"),
            ("front speed dZ/dT over 1.5 <= T <= 3 within the measured speeds +-7 %",
             min(speeds) * 0.93 <= speed <= max(speeds) * 1.07,
             f"{speed:.3f}, measured {speeds[0]:.3f} and {speeds[1]:.3f}; shifted clock T + {LETHE_SHIFT} "
             f"(Lethe, not gated): deviation {lethe:.1%}; best constant shift Delta T = {shifts[best]:.2f} leaves "
             f"{left[best]:.1%}")]
