#!/usr/bin/python3
"""Writes the coastline seed's tank as a Talus scene (2D section or 3D tank):
sea water driven by a piston wavemaker over the trapezoidal sediment bank, the
seed's Table 3 materials, wave, surf and bed gauges, a run-up line up the
seaward flank, each phase's mass and the probes writer's waves section.

The bank is a staircase of columns one particle spacing wide, each as high as
the trapezoid at its centre rounded to whole spacings (columns of one height
merged), with sea water over the columns lower than the still water.

  tools/coastline_tank.py --dim 2 -o section.json                 # the 2D section (dp 0.0135 m)
  tools/coastline_tank.py --dim 3 --dp 0.01 -o tank_3d.json       # the seed's 3D tank at its resolution
  tools/coastline_tank.py --dim 2 --slope 30 -o section_30.json   # another seaward slope
  tools/coastline_tank.py --slope-study 20 30 45 59.5 70 -o slopes.json  # a study over the seaward slope
  tools/coastline_tank.py --dp-study 0.0135 0.009 0.00675 -o spacings.json  # a study over the particle spacing

Geometry (the seed, sec. 2.3.2): tank 1.206 x 0.454 x 0.463 m, still water 0.11 m (the 2D
section: 0.108 m, whole spacings), bank 135 mm high, 130 mm crest, toe 0.702 m from the piston,
lagoon flank at 59.5 deg. Another seaward slope keeps the crest where the seed's is and moves
the toe out (below about 12 deg it comes within 0.1 m of the piston and is refused). Standard library only.
"""
import argparse
import json
import math
import sys

LENGTH, WIDTH, HEIGHT = 1.206, 0.454, 0.463
BANK_HEIGHT, BANK_TOP, BANK_TOE, LAGOON_SLOPE = 0.135, 0.130, 0.702, 59.5
CREST = BANK_TOE + BANK_HEIGHT / math.tan(math.radians(LAGOON_SLOPE))  # the seed's bank is symmetric

MATERIALS = {
    "seawater": {"density": 1029, "eos": {"type": "tait", "c0": 20, "gamma": 7},
                 "rheology": {"type": "newtonian", "viscosity": 0.00108}},
    "sediment": {"density": 1922, "eos": {"type": "tait", "c0": 20, "gamma": 7},
                 "rheology": {"type": "hbp", "yield": "drucker_prager", "cohesion": 1, "friction_angle": 35,
                              "yield_pressure": "effective", "pore_fluid_density": 1029, "regularisation": 100,
                              "power_index": 1, "consistency": 0.126}},
}


def whole(x, dp):
    """x rounded to whole spacings."""
    return round(round(x / dp) * dp, 6)


def toe_of(slope):
    """The seaward toe: the crest stays where the seed's is, a milder slope reaches further out."""
    return CREST - BANK_HEIGHT / math.tan(math.radians(slope))


def bank_columns(dp, slope):
    """(x0, x1, height) of the staircase, columns of one height merged."""
    toe, crest = toe_of(slope), CREST
    lagoon = crest + BANK_TOP
    end = lagoon + BANK_HEIGHT / math.tan(math.radians(LAGOON_SLOPE))

    def surface(x):
        if x < crest:
            return (x - toe) * math.tan(math.radians(slope))
        if x <= lagoon:
            return BANK_HEIGHT
        return (end - x) * math.tan(math.radians(LAGOON_SLOPE))

    x0 = whole(toe, dp)
    columns = []
    while x0 < end - 1e-9:
        x1 = round(x0 + dp, 6)
        h = whole(max(0.0, min(BANK_HEIGHT, surface(0.5 * (x0 + x1)))), dp)
        if columns and columns[-1][2] == h:
            columns[-1][1] = x1
        else:
            columns.append([x0, x1, h])
        x0 = x1
    return [c for c in columns if c[2] > 0] or columns, x0


def box(dim, x0, x1, z0, z1):
    if dim == 2:
        return {"box": {"min": [x0, z0], "max": [x1, z1]}}
    return {"box": {"min": [x0, 0, z0], "max": [x1, WIDTH, z1]}}


def point(dim, x, z):
    return [x, z] if dim == 2 else [x, 0.5 * WIDTH, z]


def scene(dim, dp, slope, period, stroke, end):
    depth = whole(0.11, dp)
    length = whole(LENGTH, dp)
    columns, bank_end = bank_columns(dp, slope)
    fluid = lambda name, material, shape: {"name": name, "kind": "fluid", "material": material, "dp": dp,
                                           "hydrostatic": True, "shape": shape}
    bodies = [fluid("water_sea", "seawater", box(dim, 0.0, columns[0][0], 0.0, depth))]
    for k, (x0, x1, h) in enumerate(columns):
        bodies.append(fluid("bank%d" % k, "sediment", box(dim, x0, x1, 0.0, h)))
        if h < depth:
            bodies.append(fluid("water_over_bank%d" % k, "seawater", box(dim, x0, x1, h, depth)))
    bodies.append(fluid("water_lagoon", "seawater", box(dim, bank_end, length, 0.0, depth)))
    top = whole(HEIGHT, dp)
    lo = [-0.06, 0] if dim == 2 else [-0.06, 0, 0]
    hi = [length, top] if dim == 2 else [length, WIDTH, top]
    up = "+y" if dim == 2 else "+z"
    bodies.append({"name": "tank", "kind": "wall", "material": "seawater", "dp": dp, "layers": 3,
                   "boundary": {"type": "dynamic_particles"},
                   "shape": {"box_walls": {"min": lo, "max": hi, "open": [up]}}})
    piston = box(dim, -3 * dp, 0.0, 0.0, 0.25)
    bodies.append({"name": "piston", "kind": "wall", "material": "seawater", "dp": dp, "layers": 3,
                   "boundary": {"type": "dynamic_particles"}, "shape": piston,
                   "motion": {"sine": {"direction": [1, 0] if dim == 2 else [1, 0, 0], "amplitude": 0.5 * stroke,
                                       "period": period}}})
    # Gauges: offshore halfway to the toe (at most 0.35 m out), surf gauges before the toe and over the flank.
    toe, crest = toe_of(slope), CREST
    if toe < 0.1:
        sys.exit("coastline_tank.py: at %g deg the seaward flank reaches %.3f m from the piston: no room offshore" % (
            slope, toe))
    surf = [toe - 0.04 * min(1.0, toe / 0.2)] + [toe + f * (crest - toe) for f in (0.25, 0.5, 0.75, 1.0)]
    gauges = [point(dim, round(min(0.35, 0.5 * toe), 4), 0.1)] + [point(dim, round(x, 4), 0.1) for x in surf]
    names = ["OFF"] + ["S%d" % (k + 1) for k in range(len(surf))]
    beds = [point(dim, round(columns[0][0] - dp + k * dp, 4), 0.1)
            for k in range(int(round((bank_end - columns[0][0]) / dp)) + 3)]
    # Run-up: half a spacing above the seaward flank, from its toe to past its crest.
    t = math.radians(slope)
    normal = (-math.sin(t), math.cos(t))
    a = (toe + 0.5 * dp * normal[0], 0.5 * dp * normal[1])
    b = (crest + 0.02 * math.cos(t) + 0.5 * dp * normal[0], BANK_HEIGHT + 0.02 * math.sin(t) + 0.5 * dp * normal[1])
    probes = {"type": "probes", "every": 0.005, "gauges": gauges, "gauge_names": names,
              "bed_gauges": beds, "bed_material": "sediment",
              "runup_line": [point(dim, round(a[0], 4), round(a[1], 4)), point(dim, round(b[0], 4), round(b[1], 4))],
              "runup_material": "seawater", "material_masses": True,
              "integrals": ["mass", "kinetic_energy", "max_speed", "particles", "removed"],
              "waves": {"offshore": "OFF", "surf": names[1:], "slope": slope, "water_depth": depth,
                        "from": max(2.0, period)}}
    return {
        "talus": 1,
        "description": ("Coastline seed tank (sec. 2.3.2, Table 3), %dD, written by tools/coastline_tank.py: sea water %.4g m "
                        "deep driven by a piston (stroke %.3g m, period %.4g s) over the trapezoidal sediment bank "
                        "(%.0f mm high, %.0f mm crest, seaward flank %.4g deg, lagoon flank %.4g deg), dp = %.4g m; "
                        "wave, surf and bed gauges, run-up up the seaward flank, each phase's mass, and the waves "
                        "section (breaker analysis from t = %.4g s)." % (
                            dim, depth, stroke, period, 1000 * BANK_HEIGHT, 1000 * BANK_TOP, slope, LAGOON_SLOPE, dp,
                            max(2.0, period))),
        "domain": {"dim": dim, "min": lo, "max": hi},
        "gravity": [0, -9.81] if dim == 2 else [0, 0, -9.81],
        "kernel": {"type": "wendland_c2", "h_over_dp": 1.5},
        "materials": MATERIALS,
        "bodies": bodies,
        "pipeline": [{"stage": "wcsph", "integrator": "symplectic", "courant": 0.2, "viscosity": "laminar",
                      "viscosity_mean": "harmonic", "density_diffusion": "none", "stiff_viscosity": "point_implicit"}],
        "time": {"end": end},
        "checkpoint": {"every_minutes": 10},
        "outputs": [probes],
    }


def study(base, variants, named_axes, more_results=(), series=()):
    """A study of the variants' scenes (zipped: domain, bodies and probes of each), with the named axes for the
    table; measures: the breaker analysis, the bed's change, the run's wall time, and `series` (name, probes
    column, reduction)."""
    measures = [{"name": name, "summary": "/results/probes/" + key} for name, key in (
        ("H_surf", "surf_height"), ("T", "period"), ("xi", "iribarren"), ("Fn", "froude"),
        ("type", "breaker_type"), ("observed", "observed_type"), ("u_over_c", "kinematic_ratio"),
        ("runup", "runup_max"), ("eroded", "bed_eroded_area")) + tuple(more_results)]
    measures += [{"name": name, "series": column, "reduce": reduce} for name, column, reduce in series]
    measures.append({"name": "wall_s", "summary": "/wall_seconds"})
    axes = [{"pointer": "/domain", "name": "domain", "values": [v["domain"] for v in variants]},
            {"pointer": "/bodies", "name": "bank", "values": [v["bodies"] for v in variants]},
            {"pointer": "/outputs", "name": "probes", "values": [v["outputs"] for v in variants]}]
    if len({json.dumps(v["domain"]) for v in variants}) == 1:
        axes = axes[1:]  # one domain for all
    return {"base": base, "combine": "zip", "axes": axes + named_axes, "measures": measures}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dim", type=int, choices=[2, 3], default=2)
    p.add_argument("--dp", type=float, help="particle spacing, m (default 0.0135 in 2D, 0.01 in 3D)")
    p.add_argument("--slope", type=float, default=59.5, help="seaward flank angle, deg (default 59.5, the seed's)")
    p.add_argument("--period", type=float, default=1.0, help="piston period, s (default 1)")
    p.add_argument("--stroke", type=float, default=0.04, help="piston stroke, m (default 0.04)")
    p.add_argument("--end", type=float, default=6.0, help="simulated time, s (default 6)")
    p.add_argument("--slope-study", type=float, nargs="+", metavar="DEG",
                   help="write a study over these seaward slopes instead (its base: --base)")
    p.add_argument("--dp-study", type=float, nargs="+", metavar="DP",
                   help="write a study over these particle spacings instead (its base: --base)")
    p.add_argument("--base", default="../scenes/coastline_breaker_2d.json",
                   help="--slope-study, --dp-study: the base scene, relative to the study file")
    p.add_argument("-o", "--output", required=True)
    a = p.parse_args(argv)
    dp = a.dp or (0.0135 if a.dim == 2 else 0.01)
    if a.slope_study and a.dp_study:
        p.error("--slope-study and --dp-study: one study at a time")
    if a.slope_study:
        variants = [scene(a.dim, dp, s, a.period, a.stroke, a.end) for s in a.slope_study]
        doc = study(a.base, variants, [{"pointer": "/outputs/0/waves/slope", "name": "slope", "values": a.slope_study}])
    elif a.dp_study:
        variants = [scene(a.dim, d, a.slope, a.period, a.stroke, a.end) for d in a.dp_study]
        doc = study(a.base, variants, [{"pointer": "/bodies/0/dp", "name": "dp", "values": a.dp_study}],
                    [("deposited", "bed_deposited_area")],
                    [("sediment_mass_first", "mass_sediment", "first"), ("sediment_mass_last", "mass_sediment", "last"),
                     ("water_mass_first", "mass_seawater", "first"), ("water_mass_last", "mass_seawater", "last")])
    else:
        doc = scene(a.dim, dp, a.slope, a.period, a.stroke, a.end)
    with open(a.output, "w", encoding="utf-8") as f:
        f.write(json.dumps(doc, indent=1) + "\n")
    print("coastline_tank.py: wrote %s" % a.output)


if __name__ == "__main__":
    sys.exit(main())
