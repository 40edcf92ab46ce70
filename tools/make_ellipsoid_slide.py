#!/usr/bin/env python3
"""Writes a block scene for strength reduction: a slope face cut by an ellipsoidal slip surface.

The slip surface is an ellipsoid (the seed's eq. 31, pfe-ie-depth-integrated-sph-landslide §3.2: centre, semi-axes
a, b, c along x, y, z, its horizontal axes turned by --azimuth). The sliding mass is the part of the ground inside
it, below the slope face: an ellipsoidal cap cut off by the face plane, convex, one rigid block (the seed: "landslide
was assumed to be rigid"). The face is a plane: given (--plane, a point and the outward normal), or fitted by least
squares to a DEM over the cap's outline (--dem); the fit's largest departure is printed, because the block's top is
that plane where the terrain is not.

The construction maps the ellipsoid onto the unit sphere (x' = A^-1 (x - centre), A = R diag(a, b, c)), where the
cap is a spherical cap; its curved side is faceted on a latitude-longitude grid about the cap's axis (--rings x
--segments; every quad's corners lie on the sphere and in one plane, and the affine map back keeps faces planar and
the solid convex). Under each facet a fixed base block: the facet and its copy pushed away from the centre by the
fraction --base-depth of the way to the surface, a convex frustum. The joints are the facets: c, phi, perfectly
plastic, with a stiffness per unit area (--joint-stiffness, Pa/m): the contact model of each base gives its facet's
contact points (one per corner) the stiffness times their share of the facet's area. Springs of equal stiffness at
points of unequal area would load the small facets (round the apex) as hard as the large ones, so their cohesion
would give way first.

    /usr/bin/python3 tools/make_ellipsoid_slide.py --ellipsoid 0 0 40 40 40 40 --plane 0 0 0 -1 0 1 --out cap.json
    /usr/bin/python3 tools/make_ellipsoid_slide.py --dem share/dem/hillside_valley.asc \\
        --ellipsoid 38 0 47 42 30 42 --cohesion 25e3 --friction 20 --out slide.json

tools/make_spherical_cap.py writes the seed's spherical cap with this construction."""
import argparse
import math
import os
import sys

from block_geometry import (add, cross, dot, oriented, polygon_area, rounded, strength_reduction_scene, sub, unit, volume,
                            write_scene)



def mat_vec(m, v):
    return tuple(sum(m[i][k] * v[k] for k in range(3)) for i in range(3))


def transpose(m):
    return [[m[k][i] for k in range(3)] for i in range(3)]


class Ellipsoid:
    """x = centre + A u for u on the unit sphere, A = R diag(a, b, c), R a turn about z by the azimuth."""

    def __init__(self, centre, axes, azimuth_deg):
        self.centre = tuple(centre)
        self.axes = tuple(axes)
        ca, sa = math.cos(math.radians(azimuth_deg)), math.sin(math.radians(azimuth_deg))
        self.turn = [[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]]

    def to_world(self, u):
        return add(self.centre, mat_vec(self.turn, tuple(self.axes[i] * u[i] for i in range(3))))

    def to_sphere(self, x):
        local = mat_vec(transpose(self.turn), sub(x, self.centre))
        return tuple(local[i] / self.axes[i] for i in range(3))

    def plane_to_sphere(self, point, normal):
        """The plane n.(x - p) = 0 as n'.u = d' in sphere space, |n'| = 1."""
        n = mat_vec(transpose(self.turn), normal)
        n = tuple(n[i] * self.axes[i] for i in range(3))  # n.A u = n.(x - c)
        length = math.sqrt(dot(n, n))
        d = dot(normal, sub(point, self.centre)) / length
        return tuple(x / length for x in n), d


def cap_in_sphere(out_normal, distance, rings, segments):
    """Vertices (unit sphere) of the cap u.out_normal <= distance of the unit ball (the ground side of the face):
    apex first, then `rings` rings of `segments` points; the last ring is the rim on the plane."""
    axis = tuple(-x for x in out_normal)  # from the centre towards the apex, into the ground
    helper = (0.0, 1.0, 0.0) if abs(axis[1]) < 0.9 else (1.0, 0.0, 0.0)
    e1 = unit(cross(axis, helper))
    e2 = cross(axis, e1)
    theta_max = math.acos(-distance)  # the rim lies at axis-coordinate -distance
    points = [axis]
    for k in range(1, rings + 1):
        theta = theta_max * k / rings
        for j in range(segments):
            phi = 2.0 * math.pi * j / segments
            points.append(add(add(tuple(math.cos(theta) * x for x in axis), e1, math.sin(theta) * math.cos(phi)),
                              e2, math.sin(theta) * math.sin(phi)))
    return points, theta_max


def curved_facets(rings, segments):
    """Vertex indices of the curved facets: triangles round the apex, then quads between rings."""
    ring = lambda k, j: 1 + (k - 1) * segments + j % segments  # noqa: E731
    facets = [[0, ring(1, j), ring(1, j + 1)] for j in range(segments)]
    for k in range(1, rings):
        facets += [[ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1)] for j in range(segments)]
    return facets


def joint(cohesion, friction, point_stiffness):
    return {"type": "mohr_coulomb", "normal_stiffness": point_stiffness, "friction_angle": friction,
            "cohesion": cohesion, "damping_ratio": 0.0, "shear_softening": "none"}



def slide_bodies(ellipsoid, face_point, face_normal, rings, segments, base_depth, density, base_density, cohesion,
                 friction, joint_stiffness):
    """The base blocks (fixed, listed first: a contact uses the model of the block listed first) and the sliding
    block, and the sliding block's volume."""
    n, d = ellipsoid.plane_to_sphere(face_point, face_normal)
    if not -1.0 < d < 1.0:
        sys.exit("error: the slope face does not cut the ellipsoid: there is no sliding mass")
    sphere, _ = cap_in_sphere(n, d, rings, segments)
    vertices = [ellipsoid.to_world(u) for u in sphere]
    facets = curved_facets(rings, segments)
    rim = [1 + (rings - 1) * segments + j for j in range(segments)]
    bodies, point_stiffness = [], []
    for k, f in enumerate(facets):
        inner = [sphere[i] for i in f]
        outer = [tuple((1.0 + base_depth) * x for x in u) for u in inner]
        m = len(f)
        faces = [list(range(m)), list(range(m, 2 * m))] + [[a, (a + 1) % m, m + (a + 1) % m, m + a] for a in range(m)]
        points = [ellipsoid.to_world(u) for u in inner + outer]
        point_stiffness.append(joint_stiffness * polygon_area(points[:m]) / m)
        bodies.append({"name": "base_%d" % k, "kind": "block", "density": base_density, "fixed": True,
                       "shape": {"polyhedron": {"vertices": rounded(points), "faces": oriented(points, faces)}},
                       "contact": joint(cohesion, friction, float("%.6g" % point_stiffness[-1]))})
    faces = oriented(vertices, facets + [rim])
    # The slide's own model meets no other block (its contacts take the bases' models); the stiffest facet's.
    bodies.append({"name": "slide", "kind": "block", "density": density,
                   "shape": {"polyhedron": {"vertices": rounded(vertices), "faces": faces}},
                   "contact": joint(cohesion, friction, float("%.6g" % max(point_stiffness)))})
    return bodies, volume(vertices, faces)


def exact_cap_volume(ellipsoid, face_point, face_normal):
    """Volume of the smooth ellipsoidal cap: abc times the unit ball's cap u.n <= d, of height 1 + d."""
    _, d = ellipsoid.plane_to_sphere(face_point, face_normal)
    h = 1.0 + d
    a, b, c = ellipsoid.axes
    return a * b * c * math.pi * h * h * (3.0 - h) / 3.0


def fit_face(dem_path, ellipsoid):
    """Least-squares plane z = p + q x + r y through the DEM cells over the ellipsoid's outline whose terrain lies
    inside it; returns (point, outward normal, cells, largest |departure|)."""
    import numpy as np

    from esri_grid import read_asc
    values, extent, nodata = read_asc(dem_path)
    nr, nc = values.shape
    cell = (extent[1] - extent[0]) / nc
    xs = extent[0] + (np.arange(nc) + 0.5) * cell
    ys = extent[3] - (np.arange(nr) + 0.5) * cell
    gx, gy = np.meshgrid(xs, ys)
    inside = np.zeros(values.shape, dtype=bool)
    for r in range(nr):
        for col in range(nc):
            if values[r, col] == nodata:
                continue
            u = ellipsoid.to_sphere((gx[r, col], gy[r, col], values[r, col]))
            inside[r, col] = dot(u, u) < 1.0
    if inside.sum() < 3:
        sys.exit("error: %s: fewer than three DEM cells lie inside the ellipsoid: no slope face to fit"
                 % dem_path)
    x, y, z = gx[inside], gy[inside], values[inside]
    design = np.column_stack([np.ones_like(x), x, y])
    (p, q, r), *_ = np.linalg.lstsq(design, z, rcond=None)
    departure = float(np.max(np.abs(design @ np.array([p, q, r]) - z)))
    x0, y0 = float(x.mean()), float(y.mean())
    point = (x0, y0, float(p + q * x0 + r * y0))
    normal = unit((-float(q), -float(r), 1.0))
    return point, normal, int(inside.sum()), departure


def scene(args):
    ellipsoid = Ellipsoid(args.ellipsoid[:3], args.ellipsoid[3:], args.azimuth)
    if args.dem:
        point, normal, cells, departure = fit_face(args.dem, ellipsoid)
        fit = (" The face is the plane fitted to %d cells of %s (largest departure %.3g m)."
               % (cells, os.path.basename(args.dem), departure))
        print("slope face: plane fitted to %d DEM cells over the slip surface; the terrain departs from it by up "
              "to %.3g m (the block's top is the plane)" % (cells, departure))
    else:
        point, normal = tuple(args.plane[:3]), unit(tuple(args.plane[3:]))
        fit = ""
    bodies, block_volume = slide_bodies(ellipsoid, point, normal, args.rings, args.segments, args.base_depth,
                                        args.density, args.base_density, args.cohesion, args.friction,
                                        args.joint_stiffness)
    exact = exact_cap_volume(ellipsoid, point, normal)
    slide = bodies[-1]["shape"]["polyhedron"]["vertices"]
    lo = [min(p[i] for b in bodies for p in b["shape"]["polyhedron"]["vertices"]) for i in range(3)]
    hi = [max(p[i] for b in bodies for p in b["shape"]["polyhedron"]["vertices"]) for i in range(3)]
    pad = 0.2 * max(hi[i] - lo[i] for i in range(3))
    centroid = [sum(p[i] for p in slide) / len(slide) for i in range(3)]
    stage = {"stage": "strength_reduction", "bracket": [0.5, 4.0], "tolerance": 0.005,
             "monitors": [[round(x, 6) for x in centroid]]}
    handoff = ""
    if args.runout_scene:
        handoff = (" After the search the failed block is handed to %s: run OUT/strength_reduction_runout.json next, "
                   "then tools/runout_map.py for the deposit map." % os.path.basename(args.runout_scene))
        out_dir = os.path.dirname(os.path.abspath(args.out))
        stage["handoff"] = {"runout_scene": os.path.relpath(os.path.abspath(args.runout_scene), out_dir)}
        if args.dem:
            stage["handoff"]["dem"] = os.path.relpath(os.path.abspath(args.dem), out_dir)
    description = (
        "A slope face cut by the ellipsoidal slip surface centred at (%g, %g, %g) m with semi-axes %g, %g, %g m "
        "(turned %g deg): the sliding mass is the ellipsoidal cap %.1f m^3 (the smooth cap: %.1f m^3), one rigid "
        "block of %g kg/m^3, its curved side in %d facets (%d rings x %d segments), each on a fixed base block. "
        "Joints c = %g Pa, phi = %g deg, perfectly plastic, %g Pa/m normal stiffness per unit area.%s%s Written by "
        "tools/make_ellipsoid_slide.py."
        % (*args.ellipsoid, args.azimuth, block_volume, exact, args.density, args.rings * args.segments, args.rings,
           args.segments, args.cohesion, args.friction, args.joint_stiffness, fit, handoff))
    return (strength_reduction_scene(description, [v - pad for v in lo], [v + pad for v in hi], bodies, stage),
            block_volume, exact)


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ellipsoid", type=float, nargs=6, required=True, metavar=("X0", "Y0", "Z0", "A", "B", "C"),
                    help="slip surface: centre and semi-axes (a, b along the turned x, y; c along z), m")
    ap.add_argument("--azimuth", type=float, default=0.0, help="turn of the a axis from +x about z, deg")
    face = ap.add_mutually_exclusive_group(required=True)
    face.add_argument("--plane", type=float, nargs=6, metavar=("PX", "PY", "PZ", "NX", "NY", "NZ"),
                      help="slope face: a point on it and its normal pointing out of the ground")
    face.add_argument("--dem", help="slope face: the plane fitted to this ESRI ASCII DEM over the slip surface "
                                    "(the hand-off then uses the DEM too)")
    ap.add_argument("--rings", type=int, default=4, help="rings of facets from the apex to the rim (default 4)")
    ap.add_argument("--segments", type=int, default=16, help="facets round each ring (default 16)")
    ap.add_argument("--base-depth", type=float, default=0.125,
                    help="depth of the base blocks as a fraction of the way from the centre (default 0.125)")
    ap.add_argument("--density", type=float, default=2000.0, help="sliding mass, kg/m^3 (default 2000)")
    ap.add_argument("--base-density", type=float, default=2300.0, help="base rock, kg/m^3 (default 2300)")
    ap.add_argument("--cohesion", type=float, default=30e3, help="joint cohesion, Pa (default 30e3)")
    ap.add_argument("--friction", type=float, default=30.0, help="joint friction angle, deg (default 30)")
    ap.add_argument("--joint-stiffness", type=float, default=1e9,
                    help="joint normal stiffness per unit area, Pa/m (default 1e9; shear 0.4 of it)")
    ap.add_argument("--runout-scene", help="run-out scene the strength reduction hands the failed mass to")
    ap.add_argument("--out", required=True, help="scene file to write")
    args = ap.parse_args(argv)
    if args.rings < 1 or args.segments < 3:
        ap.error("need at least 1 ring and 3 segments")
    if min(args.ellipsoid[3:]) <= 0:
        ap.error("--ellipsoid: the semi-axes must be > 0")
    for name in ("base_depth", "density", "base_density", "joint_stiffness"):
        if not getattr(args, name) > 0:
            ap.error("--%s must be > 0" % name.replace("_", "-"))
    if args.cohesion < 0 or not 0 <= args.friction < 90:
        ap.error("--cohesion must be >= 0 and --friction in [0, 90)")
    if args.plane and dot(args.plane[3:], args.plane[3:]) == 0:
        ap.error("--plane: the normal must not be zero")
    if args.runout_scene and not args.dem:
        ap.error("--runout-scene needs --dem: the failed mass runs out over the DEM")
    return args


def main():
    args = parse()
    s, block_volume, exact = scene(args)
    write_scene(args.out, s)
    print("wrote %s: %d base blocks and one sliding block of %.1f m^3 (smooth cap %.1f m^3, %+.2f %%)"
          % (args.out, len(s["bodies"]) - 1, block_volume, exact, 100.0 * (block_volume / exact - 1.0)))


if __name__ == "__main__":
    main()
