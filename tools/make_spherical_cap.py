#!/usr/bin/env python3
"""Writes the seed's spherical-cap slope (pfe-ie-depth-integrated-sph-landslide §3.2) as a block scene.

A slope 40 m high at 45 deg, toe at x = 0, rising towards +x (face plane z = x). The slip surface is
a sphere of radius R = 40 m centred above the toe at crest height, C = (0, 0, 40): it passes through
the toe and the crest edge. The sliding mass is the part of the slope inside the ball: a spherical
cap cut off by the face plane (height R - R/sqrt(2), rim radius R/sqrt(2)), convex, one rigid block.

Its curved side is faceted on a latitude-longitude grid about the cap's axis (rings x segments;
each quad's four corners lie on the sphere and in one plane). Under each facet a fixed base block:
the facet and its copy pushed out radially from C by `--base-depth`, a convex frustum. The joints
are the facets: c = 30 kPa, phi = 30 deg (the seed's Table 1), perfectly plastic.

    /usr/bin/python3 tools/make_spherical_cap.py                      # share/scenes/spherical_cap.json
    /usr/bin/python3 tools/make_spherical_cap.py --rings 6 --segments 24 --out /tmp/cap.json
"""
import argparse
import json
import math
import os

R = 40.0
CENTRE = (0.0, 0.0, 40.0)
# Unit normal of the face plane z = x pointing out of the slope (towards C); the cap lies against it.
UP = (-1.0 / math.sqrt(2.0), 0.0, 1.0 / math.sqrt(2.0))
CAP_DENSITY, BASE_DENSITY = 2000.0, 2300.0
COHESION, FRICTION = 30e3, 30.0


def add(a, b, s=1.0):
    return tuple(a[i] + s * b[i] for i in range(3))


def sub(a, b):
    return tuple(a[i] - b[i] for i in range(3))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def unit(a):
    n = math.sqrt(dot(a, a))
    return tuple(x / n for x in a)


def cap_vertices(rings, segments):
    """Apex first, then ring k = 1..rings of `segments` points; the last ring is the rim on the face plane."""
    axis = tuple(-x for x in UP)  # from C towards the apex
    e1 = unit(cross(axis, (0.0, 1.0, 0.0)))
    e2 = cross(axis, e1)
    theta_max = math.acos(math.sqrt(0.5))  # the rim: distance R cos(theta) = R / sqrt(2) from C to the plane
    points = [add(CENTRE, axis, R)]
    for k in range(1, rings + 1):
        theta = theta_max * k / rings
        for j in range(segments):
            phi = 2.0 * math.pi * j / segments
            d = add(add(tuple(math.cos(theta) * x for x in axis), e1, math.sin(theta) * math.cos(phi)),
                    e2, math.sin(theta) * math.sin(phi))
            points.append(add(CENTRE, d, R))
    return points


def curved_facets(rings, segments):
    """Vertex indices of the curved facets: triangles round the apex, then quads between rings."""
    ring = lambda k, j: 1 + (k - 1) * segments + j % segments
    facets = [[0, ring(1, j), ring(1, j + 1)] for j in range(segments)]
    for k in range(1, rings):
        facets += [[ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1)] for j in range(segments)]
    return facets


def oriented(vertices, faces):
    """Faces turned counter-clockwise seen from outside (the polyhedron is convex: outside is away from its centroid)."""
    centroid = tuple(sum(v[i] for v in vertices) / len(vertices) for i in range(3))
    out = []
    for f in faces:
        p = [vertices[i] for i in f]
        normal = (0.0, 0.0, 0.0)
        for a in range(len(p)):
            normal = add(normal, cross(p[a], p[(a + 1) % len(p)]))
        middle = tuple(sum(q[i] for q in p) / len(p) for i in range(3))
        out.append(list(f) if dot(normal, sub(middle, centroid)) > 0 else list(reversed(f)))
    return out


def rounded(points):
    return [[round(x, 9) for x in p] for p in points]


def contact():
    return {"type": "mohr_coulomb", "normal_stiffness": 1e10, "friction_angle": FRICTION, "cohesion": COHESION,
            "damping_ratio": 0.0, "shear_softening": "none"}


def scene(rings, segments, base_depth):
    vertices = cap_vertices(rings, segments)
    facets = curved_facets(rings, segments)
    rim = [1 + (rings - 1) * segments + j for j in range(segments)]
    bodies = []
    for n, f in enumerate(facets):
        inner = [vertices[i] for i in f]
        outer = [add(CENTRE, sub(v, CENTRE), 1.0 + base_depth / R) for v in inner]
        m = len(f)
        faces = [list(range(m)), list(range(m, 2 * m))] + [[a, (a + 1) % m, m + (a + 1) % m, m + a] for a in range(m)]
        points = inner + outer
        bodies.append({"name": "base_%d" % n, "kind": "block", "density": BASE_DENSITY, "fixed": True,
                       "shape": {"polyhedron": {"vertices": rounded(points), "faces": oriented(points, faces)}},
                       "contact": contact()})
    cap_faces = oriented(vertices, facets + [rim])
    bodies.append({"name": "cap", "kind": "block", "density": CAP_DENSITY,
                   "shape": {"polyhedron": {"vertices": rounded(vertices), "faces": cap_faces}}, "contact": contact()})
    height = R * (1.0 - math.sqrt(0.5))
    volume = math.pi * height * height * (3.0 * R - height) / 3.0
    description = (
        "The seed's spherical-cap slope (pfe-ie-depth-integrated-sph-landslide §3.2): a slope 40 m high at 45 deg "
        "(toe at x = 0, face plane z = x); slip surface the sphere of radius 40 m centred above the toe at crest "
        "height (0, 0, 40), through the toe and the crest edge. The sliding mass, the slope inside the ball, is a "
        "spherical cap %.2f m high and %.0f m^3 (one rigid block, density 2000 kg/m^3), its curved side in %d facets "
        "(%d rings x %d segments), each on a fixed base block %.0f m deep. Joints c = 30 kPa, phi = 30 deg, perfectly "
        "plastic (the seed's Table 1). The seed reports F_s = 1.45 (deformable blocks); limit equilibrium: simplified "
        "Bishop 1.30, 3D Spencer 1.34, simplified Janbu 1.25, 3D Sarma 1.48. Written by tools/make_spherical_cap.py."
        % (height, volume, len(facets), rings, segments, base_depth))
    return {
        "talus": 1,
        "description": description,
        "domain": {"dim": 3, "min": [-20.0, -50.0, -10.0], "max": [70.0, 50.0, 90.0]},
        "gravity": [0, 0, -9.81],
        "bodies": bodies,
        "pipeline": [{"stage": "strength_reduction", "bracket": [0.5, 4.0], "tolerance": 0.005,
                      "monitors": [[22.0, 0.0, 18.0]]}],
        "time": {"end": 1.0},
        "outputs": [{"type": "hdf5", "every": 1.0}],
    }


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
    with open(args.out, "w") as f:
        json.dump(scene(args.rings, args.segments, args.base_depth), f, indent=1)
        f.write("\n")
    print("wrote %s: %d blocks" % (args.out, args.rings * args.segments + 1))


if __name__ == "__main__":
    main()
