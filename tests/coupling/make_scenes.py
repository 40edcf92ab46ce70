#!/usr/bin/env python3
"""Writes the rock-fluid seed's three scenes (share/scenes/{block_impact,wedge_slide,wavemaker_beach}[_seed].json).

The geometry is computed here (inclined blocks as polyhedra) so that the scenes stay consistent when a
dimension changes. Run from anywhere: python3 tests/coupling/make_scenes.py
"""
import json
import math
import os

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "share", "scenes")


def r(v):
    return round(v, 6)


def prism(profile, y0, y1):
    """Convex prism: the convex polygon `profile` [(x, z), ...] extruded from y0 to y1, faces counter-clockwise
    seen from outside (either winding of the profile is accepted)."""
    n = len(profile)
    verts = [[r(x), r(y0), r(z)] for x, z in profile] + [[r(x), r(y1), r(z)] for x, z in profile]
    # Orientation: compute signed area in (x, z); CCW in (x, z) means the normal x-z cross is -y.
    area = sum(profile[i][0] * profile[(i + 1) % n][1] - profile[(i + 1) % n][0] * profile[i][1] for i in range(n))
    front = list(range(n))  # at y0, outward normal -y
    back = list(range(n, 2 * n))
    # A polygon CCW in (x, z) (area > 0) has its right-hand normal along x cross z = -y: outward for the y0 face.
    if area < 0:
        front.reverse()
    else:
        back.reverse()
    faces = [front, back]
    for i in range(n):
        j = (i + 1) % n
        side = [j, i, n + i, n + j]  # runs i -> j the other way from the y0 face
        if area < 0:
            side.reverse()
        faces.append(side)
    return {"polyhedron": {"vertices": verts, "faces": faces}}


def rotated_box(origin, along, normal_len, width_y, y0, angle_deg, length):
    """Box lying on a plane descending at angle_deg toward +x: `origin` (x, z) is its lower-left corner on the
    plane (upslope end), `length` along the slope, `normal_len` thick."""
    a = math.radians(angle_deg)
    t = (math.cos(a), -math.sin(a))  # down the slope
    n = (math.sin(a), math.cos(a))   # up from the slope
    x0, z0 = origin
    p = [(x0, z0), (x0 + length * t[0], z0 + length * t[1]),
         (x0 + length * t[0] + normal_len * n[0], z0 + length * t[1] + normal_len * n[1]),
         (x0 + normal_len * n[0], z0 + normal_len * n[1])]
    return prism(p, y0, y0 + width_y)


def water_material(c0):
    return {"water": {"density": 1000, "eos": {"type": "tait", "c0": c0, "gamma": 7}}}


def contact(friction):
    return {"type": "penalty_coulomb", "normal_stiffness": 2e6, "friction_angle": friction, "damping_ratio": 0.3}


def write(name, scene):
    path = os.path.join(SCENES, name)
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
    print("wrote", os.path.normpath(path))


def block_impact(dp, end, name, note):
    # Tank 1.8 x 0.2 x 0.8 m, water 0.3 m deep; a fixed 30 degree slope (wedge) from the left wall; a
    # 0.15 x 0.12 x 0.1 m block (2500 kg/m^3) released 0.5 m up the slope above the water.
    L, W, H, depth = 1.8, 0.2, 0.8, 0.3
    WALL = 0.55  # tank walls end here (the slope rises above them): fewer wall particles
    angle = 30.0
    slope_len = 1.2
    slope_h = slope_len * math.tan(math.radians(angle))
    slope = prism([(0, 0), (slope_len, 0), (0, slope_h)], 0.0, W)
    a = math.radians(angle)
    shore = (slope_h - depth) / math.sin(a)  # along the slope from its top edge to the still-water line
    s = shore - 0.3 - 0.15  # the block's front starts 0.3 m (along the slope) above the water line
    start = (s * math.cos(a), slope_h - s * math.sin(a))
    block = rotated_box(start, None, 0.1, 0.16, 0.02, angle, 0.15)
    slope_normal = [r(math.sin(a)), 0, r(math.cos(a))]
    return {
        "talus": 1,
        "description": f"Rock-fluid seed example 3 (impacting block): a 0.15 x 0.16 x 0.1 m block, density 2500, "
                       f"released 0.3 m (along the slope) above the water line, slides down a fixed 30 degree slope "
                       f"(friction angle 10 degrees, analytic impact speed 1.43 m/s at t = 0.42 s) and impacts 0.3 m "
                       f"of still water in a 1.8 m long tank, periodic across its 0.2 m width. Blocks: slope (fixed) "
                       f"and block, both seen by the fluid as block_particles (the slope on its top face only); DDA "
                       f"sub-cycled in the SPH step. {note}",
        "domain": {"dim": 3, "min": [0, 0, 0], "max": [L, W, H], "periodic": ["y"]},
        "gravity": [0, 0, -9.81],
        "kernel": {"type": "wendland_c2", "h_over_dp": 1.3},
        "materials": water_material(20),
        "bodies": [
            {"name": "water", "kind": "fluid", "material": "water", "dp": dp, "hydrostatic": True,
             "shape": {"box": {"min": [0, 0, 0], "max": [L, W, depth]}}},
            {"name": "tank", "kind": "wall", "dp": dp, "boundary": {"type": "dynamic_particles"},
             "shape": {"box_walls": {"min": [0, 0, 0], "max": [L, W, WALL], "open": ["+z", "-y", "+y"]}}},
            {"name": "slope", "kind": "block", "density": 2500, "fixed": True, "shape": slope,
             "boundary": {"type": "block_particles", "faces": [slope_normal]}, "contact": contact(10)},
            {"name": "block", "kind": "block", "density": 2500, "shape": block,
             "boundary": {"type": "block_particles"}, "contact": contact(10)},
        ],
        "pipeline": [
            {"stage": "dda", "subcycle": True},
            {"stage": "wcsph", "viscosity": "artificial", "alpha": 0.05},
        ],
        "time": {"end": end},
        "outputs": [{"type": "hdf5", "every": 0.02}],
    }


def wedge_slide(dp, end, name, note):
    # Tank 2.0 x 0.3 x 0.8 m, water 0.35 m deep; fixed 25 degree slope; a wedge (right triangle 0.25 long on the
    # slope, top face horizontal) of density 2500 slides freely down it into the water.
    L, W, H, depth = 2.0, 0.3, 0.8, 0.35
    WALL = 0.6
    angle = 25.0
    a = math.radians(angle)
    slope_len = 1.4
    slope_h = slope_len * math.tan(a)
    slope = prism([(0, 0), (slope_len, 0), (0, slope_h)], 0.0, W)
    # Wedge: bottom edge on the slope from s0 to s0 + l, top face horizontal through the upper corner.
    s0, l = 0.1, 0.3
    p0 = (s0 * math.cos(a), slope_h - s0 * math.sin(a))
    p1 = (p0[0] + l * math.cos(a), p0[1] - l * math.sin(a))
    p2 = (p0[0] + l * math.cos(a), p0[1])  # vertical back face at the downslope end: top face horizontal
    wedge = prism([p0, p1, p2], 0.05, W - 0.05)
    slope_normal = [r(math.sin(a)), 0, r(math.cos(a))]
    return {
        "talus": 1,
        "description": f"Rock-fluid seed example 2 (sliding wedge): a wedge (0.3 m along the slope, 0.2 m wide, density "
                       f"2500) slides freely down a fixed 25 degree plane (friction angle 10 degrees) into 0.35 m "
                       f"of still water in a 2.0 m long tank, periodic across its 0.3 m width. {note}",
        "domain": {"dim": 3, "min": [0, 0, 0], "max": [L, W, H], "periodic": ["y"]},
        "gravity": [0, 0, -9.81],
        "kernel": {"type": "wendland_c2", "h_over_dp": 1.3},
        "materials": water_material(20),
        "bodies": [
            {"name": "water", "kind": "fluid", "material": "water", "dp": dp, "hydrostatic": True,
             "shape": {"box": {"min": [0, 0, 0], "max": [L, W, depth]}}},
            {"name": "tank", "kind": "wall", "dp": dp, "boundary": {"type": "dynamic_particles"},
             "shape": {"box_walls": {"min": [0, 0, 0], "max": [L, W, WALL], "open": ["+z", "-y", "+y"]}}},
            {"name": "slope", "kind": "block", "density": 2500, "fixed": True, "shape": slope,
             "boundary": {"type": "block_particles", "faces": [slope_normal]}, "contact": contact(10)},
            {"name": "wedge", "kind": "block", "density": 2500, "shape": wedge,
             "boundary": {"type": "block_particles"}, "contact": contact(10)},
        ],
        "pipeline": [
            {"stage": "dda", "subcycle": True},
            {"stage": "wcsph", "viscosity": "artificial", "alpha": 0.05},
        ],
        "time": {"end": end},
        "outputs": [{"type": "hdf5", "every": 0.02}],
    }


def wavemaker_beach(dp, end, name, note):
    # Tank 6.0 x 0.2 x 0.4 m, water 0.2 m deep; piston (kinematic block, sinusoidal stroke) at the left; flat
    # section of 1.0 m, then a 4 % beach (fixed block) rising to 0.24 m at the far wall.
    L, W, H, depth = 6.0, 0.2, 0.4, 0.2
    WALL = H
    flat = 1.0
    beach_top = (L - 0.2 - flat) * 0.04
    beach = prism([(0.2 + flat, 0), (L, 0), (L, beach_top)], 0.0, W)
    piston = {"box": {"min": [0.0, 0.0, 0.0], "max": [0.2, W, H * 0.9]}}
    b = math.atan(0.04)
    beach_normal = [r(-math.sin(b)), 0, r(math.cos(b))]
    return {
        "talus": 1,
        "description": f"Rock-fluid seed example 1 (wave maker): a piston (kinematic block, stroke 0.04 m, period 1.2 s) "
                       f"drives waves along 1.0 m of flat bottom onto a 4 % beach (fixed block) in a 6.0 x 0.2 m "
                       f"tank (periodic across its width) with 0.2 m of water. {note}",
        "domain": {"dim": 3, "min": [0, 0, 0], "max": [L, W, H], "periodic": ["y"]},
        "gravity": [0, 0, -9.81],
        "kernel": {"type": "wendland_c2", "h_over_dp": 1.3},
        "materials": water_material(15),
        "bodies": [
            {"name": "water", "kind": "fluid", "material": "water", "dp": dp, "hydrostatic": True,
             "shape": {"box": {"min": [0.2, 0, 0], "max": [L, W, depth]}}},
            {"name": "tank", "kind": "wall", "dp": dp, "boundary": {"type": "dynamic_particles"},
             "shape": {"box_walls": {"min": [0, 0, 0], "max": [L, W, WALL], "open": ["+z", "-y", "+y"]}}},
            {"name": "piston", "kind": "block", "density": 2500, "shape": piston,
             "motion": {"sine": {"direction": [1, 0, 0], "amplitude": 0.04, "period": 1.2}},
             "boundary": {"type": "block_particles", "faces": [[1, 0, 0]]}, "contact": contact(20)},
            {"name": "beach", "kind": "block", "density": 2500, "fixed": True, "shape": beach,
             "boundary": {"type": "block_particles", "faces": [beach_normal]}, "contact": contact(20)},
        ],
        "pipeline": [
            {"stage": "dda", "subcycle": True},
            {"stage": "wcsph", "viscosity": "artificial", "alpha": 0.05},
        ],
        "time": {"end": end},
        "outputs": [{"type": "hdf5", "every": 0.05}],
    }


# Particle counts after setup, from `talus validate` (fluid after the blocks' volume is cleared; wall = tank walls
# plus block particles). Update them when a dimension or dp changes.
COUNTS = {
    "block_impact": (6300, 6864), "block_impact_seed": (101575, 43915),
    "wedge_slide": (6348, 7128), "wedge_slide_seed": (25042, 17984),
    "wavemaker_beach": (8160, 10872), "wavemaker_beach_seed": (68480, 44384),
}


def counts(name, dp, seed_count):
    c = COUNTS.get(name)
    text = f"dp = {dp} m" + (f": {c[0]} fluid particles, {c[1]} wall and block particles" if c else "")
    text += f", 2 blocks. The seed used about {seed_count} particles"
    return text + ("; this is the seed's resolution (validates and starts; a long run)." if name.endswith("_seed")
                   else (f"; {name}_seed.json has the seed's resolution."))


if __name__ == "__main__":
    write("block_impact.json", block_impact(0.02, 1.2, "block_impact", counts("block_impact", 0.02, "100 000")))
    write("block_impact_seed.json", block_impact(0.008, 1.2, "block_impact_seed", counts("block_impact_seed", 0.008, "100 000")))
    write("wedge_slide.json", wedge_slide(0.025, 1.5, "wedge_slide", counts("wedge_slide", 0.025, "25 000")))
    write("wedge_slide_seed.json", wedge_slide(0.016, 1.5, "wedge_slide_seed", counts("wedge_slide_seed", 0.016, "25 000")))
    write("wavemaker_beach.json", wavemaker_beach(0.025, 6.0, "wavemaker_beach", counts("wavemaker_beach", 0.025, "65 000")))
    write("wavemaker_beach_seed.json", wavemaker_beach(0.0125, 6.0, "wavemaker_beach_seed", counts("wavemaker_beach_seed", 0.0125, "65 000")))
