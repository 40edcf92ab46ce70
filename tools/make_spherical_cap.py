#!/usr/bin/env python3
"""Writes the seed's spherical-cap slope (pfe-ie-depth-integrated-sph-landslide §3.2) as a block scene.

A slope 40 m high at 45 deg, toe at x = 0, rising towards +x (face plane z = x). The slip surface is
a sphere of radius R = 40 m centred above the toe at crest height, C = (0, 0, 40): it passes through
the toe and the crest edge. The sliding mass is the part of the slope inside the ball: a spherical
cap cut off by the face plane (height R - R/sqrt(2), rim radius R/sqrt(2)), convex, one rigid block.

Its curved side is faceted on a latitude-longitude grid about the cap's axis (rings x segments;
each quad's four corners lie on the sphere and in one plane). Under each facet a fixed base block:
the facet and its copy pushed out radially from C by `--base-depth`, a convex frustum. The joints
are the facets: c = 30 kPa, phi = 30 deg (the seed's Table 1), perfectly plastic, with a normal
stiffness of 1e9 Pa/m per unit area (tools/make_ellipsoid_slide.py builds it).

    /usr/bin/python3 tools/make_spherical_cap.py                      # share/scenes/spherical_cap.json
    /usr/bin/python3 tools/make_spherical_cap.py --rings 6 --segments 24 --out /tmp/cap.json
"""
import argparse
import math
import os

from block_geometry import strength_reduction_scene, write_scene
from make_ellipsoid_slide import Ellipsoid, slide_bodies

R = 40.0
CENTRE = (0.0, 0.0, 40.0)
# A point of the face plane z = x and its unit normal pointing out of the slope (towards C).
TOE, UP = (0.0, 0.0, 0.0), (-1.0 / math.sqrt(2.0), 0.0, 1.0 / math.sqrt(2.0))
CAP_DENSITY, BASE_DENSITY = 2000.0, 2300.0
COHESION, FRICTION = 30e3, 30.0
JOINT_STIFFNESS = 1e9  # Pa/m: normal stiffness per unit joint area


def scene(rings, segments, base_depth):
    bodies, _ = slide_bodies(Ellipsoid(CENTRE, (R, R, R), 0.0), TOE, UP, rings, segments, base_depth / R,
                             CAP_DENSITY, BASE_DENSITY, COHESION, FRICTION, JOINT_STIFFNESS)
    bodies[-1]["name"] = "cap"
    height = R * (1.0 - math.sqrt(0.5))
    volume = math.pi * height * height * (3.0 * R - height) / 3.0
    description = (
        "The seed's spherical-cap slope (pfe-ie-depth-integrated-sph-landslide §3.2): a slope 40 m high at 45 deg "
        "(toe at x = 0, face plane z = x); slip surface the sphere of radius 40 m centred above the toe at crest "
        "height (0, 0, 40), through the toe and the crest edge. The sliding mass, the slope inside the ball, is a "
        "spherical cap %.2f m high and %.0f m^3 (one rigid block, density 2000 kg/m^3), its curved side in %d facets "
        "(%d rings x %d segments), each on a fixed base block %.0f m deep. Joints c = 30 kPa, phi = 30 deg, perfectly "
        "plastic (the seed's Table 1), normal stiffness %g Pa/m per unit area. The seed reports F_s = 1.45 (its "
        "landslide rigid, 397 contact pairs); limit equilibrium: simplified Bishop 1.30, 3D Spencer 1.34, simplified "
        "Janbu 1.25, 3D Sarma 1.48. Written by tools/make_spherical_cap.py."
        % (height, volume, rings * segments, rings, segments, base_depth, JOINT_STIFFNESS))
    stage = {"stage": "strength_reduction", "bracket": [0.5, 4.0], "tolerance": 0.005, "monitors": [[22.0, 0.0, 18.0]]}
    return strength_reduction_scene(description, [-20.0, -50.0, -10.0], [70.0, 50.0, 90.0], bodies, stage)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rings", type=int, default=4, help="rings of facets from the apex to the rim (default 4)")
    ap.add_argument("--segments", type=int, default=16, help="facets round each ring (default 16)")
    ap.add_argument("--base-depth", type=float, default=5.0, help="radial depth of the base blocks, m (default 5)")
    ap.add_argument("--out", default=os.path.join(root, "share", "scenes", "spherical_cap.json"))
    args = ap.parse_args()
    if args.rings < 1 or args.segments < 3:
        ap.error("need at least 1 ring and 3 segments")
    write_scene(args.out, scene(args.rings, args.segments, args.base_depth))
    print("wrote %s: %d blocks" % (args.out, args.rings * args.segments + 1))


if __name__ == "__main__":
    main()
