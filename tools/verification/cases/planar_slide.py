"""Strength reduction: the seed's planar slide, a rigid slab on a 30 degree slip plane (closed-form safety factor)."""
import csv
import math
import os
import re

NAME = "planar_slide"
TITLE = ("Safety factor of a rigid slab on a planar joint by strength reduction (seed §3.1: beta = 30 deg, c = 10 kPa, "
         "phi = 30 deg), against the closed form; ladder: the bisection tolerance on F")
SCENE = "share/scenes/planar_slide.json"
LADDER = [0.02, 0.01, 0.005]
# The bisection leaves F_s within tolerance / 2 of the factor at which the trials change from holding to failing;
# where inside that interval the middle falls is luck, so the error is bounded by the ladder but need not fall
# rung by rung.
CONVERGES = False
# The gate: 1 % of F. The joint's discretisation adds nothing measurable (4 equal contact points whose
# tributary areas sum to the base area exactly; friction equals N tan(phi) whatever the spring stiffness).
TOLERANCE = {0.02: 0.01, 0.01: 0.01, 0.005: 0.01}
ERROR_LABEL = "|F_s / F - 1|"
REFERENCE = "F = tan(phi)/tan(beta) + c/(gamma t sin(beta)) (limit equilibrium of a slab on a plane)"
BETA = 30.0
LENGTH, WIDTH, DENSITY, G = 20.0, 4.0, 1960.0, 9.81
# Slab thickness t normal to the slip plane, cohesion c (Pa) and friction angle phi (deg) of each variant.
VARIANTS = {"t=4.33": (4.330127, 1e4, 30.0), "t=8.66": (8.660254, 1e4, 30.0), "t=17.3": (17.320508, 1e4, 30.0),
            "cohesion only, t=1": (1.0, 1e4, 0.0), "friction only, phi=40": (8.660254, 0.0, 40.0)}
OPTIONS = {"joint": list(VARIANTS)}
# --quick runs no option sweep: the seed's own slab (F_s = 1.12).
DEFAULT_JOINT = "t=8.66"


def exact(option):
    t, c, phi = VARIANTS[option.get("joint", DEFAULT_JOINT)]
    b = math.radians(BETA)
    return math.tan(math.radians(phi)) / math.tan(b) + c / (DENSITY * G * t * math.sin(b))


def slab_vertices(t):
    """The slab's corners: the base on the slip plane through the origin, ends vertical (the box vertex order)."""
    b = math.radians(BETA)
    down = (LENGTH * math.cos(b), 0.0, -LENGTH * math.sin(b))
    height = t / math.cos(b)
    vertices = []
    for k in range(8):
        v = [down[i] if k & 1 else 0.0 for i in range(3)]
        v[1] += WIDTH if k & 2 else 0.0
        v[2] += height if k & 4 else 0.0
        vertices.append([round(x, 9) for x in v])
    return vertices


def configure(scene, tolerance, option):
    t, c, phi = VARIANTS[option.get("joint", DEFAULT_JOINT)]
    for body in scene["bodies"]:
        body["contact"].update({"cohesion": c, "friction_angle": phi})
        if body["name"] == "slab":
            body["shape"]["polyhedron"]["vertices"] = slab_vertices(t)
    stage = scene["pipeline"][0]
    stage["tolerance"] = tolerance
    b = math.radians(BETA)
    # The slab's middle: half way down the slope, half way up its vertical height.
    stage["monitors"] = [[0.5 * LENGTH * math.cos(b), 0.5 * WIDTH, -0.5 * LENGTH * math.sin(b) + 0.5 * t / math.cos(b)]]
    scene["outputs"] = []
    return scene


def safety_factor(run):
    """(F_s, holds at, fails at) from the stage's summary line."""
    for line in run.summary.get("finish", []):
        m = re.search(r"F_s = ([0-9.]+) \(holds at ([0-9.]+), fails at ([0-9.]+)", line)
        if m:
            return tuple(float(x) for x in m.groups())
    raise RuntimeError("the run reported no safety factor: " + "; ".join(run.summary.get("finish", [])))


def trials(run):
    with open(os.path.join(run.directory, "strength_reduction.csv")) as f:
        return list(csv.DictReader(f))


def error(run):
    return abs(safety_factor(run)[0] / exact(run.option) - 1.0)


def gates(run):
    fs, holds, fails = safety_factor(run)
    f = exact(run.option)
    rows = [r for r in trials(run) if r["factor"] != "elastic"]
    stable_clean = all(int(r["slip"]) == 0 for r in rows if r["outcome"] == "stable")
    failed_slide = all(int(r["slip"]) == int(r["contacts"]) and int(r["released_blocks"]) == 1
                       for r in rows if r["outcome"] == "failed")
    return [("the closed-form F lies inside the final bracket", holds <= f <= fails,
             f"F = {f:.4f} in [{holds:.4f}, {fails:.4f}]"),
            ("every holding trial has no joint in slip", stable_clean, f"{len(rows)} trials"),
            ("every failing trial has all joints in slip and the slab released", failed_slide,
             f"{sum(r['outcome'] == 'failed' for r in rows)} failing trials")]
