"""Helpers for the tools that write block scenes: convex polyhedra, joints and the strength-reduction scene as JSON,
and the options the tessellation tools share."""
import json
import math

GRAVITY = 9.81


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


def polygon_area(points):
    """Area of a planar polygon given by its corners in order."""
    total = (0.0, 0.0, 0.0)
    for k in range(1, len(points) - 1):
        total = add(total, cross(sub(points[k], points[0]), sub(points[k + 1], points[0])))
    return 0.5 * math.sqrt(dot(total, total))


def volume(vertices, faces):
    """Volume of a closed polyhedron whose faces are oriented outwards (divergence theorem over fanned faces)."""
    total = 0.0
    for f in faces:
        a = vertices[f[0]]
        for k in range(1, len(f) - 1):
            total += dot(a, cross(vertices[f[k]], vertices[f[k + 1]]))
    return total / 6.0


def box(lo, hi):
    """The axis-aligned box from corner lo to corner hi (vertices, outward faces)."""
    vertices = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    faces = [[0, 1, 3, 2], [4, 5, 7, 6], [0, 1, 5, 4], [2, 3, 7, 6], [0, 2, 6, 4], [1, 3, 7, 5]]
    return vertices, oriented(vertices, faces)


def joint(cohesion, friction, tensile, point_stiffness):
    """A perfectly plastic Mohr-Coulomb joint model; the stiffness is per contact point (N/m)."""
    return {"type": "mohr_coulomb", "normal_stiffness": float("%.6g" % point_stiffness), "friction_angle": friction,
            "cohesion": cohesion, "tensile_strength": tensile, "damping_ratio": 0.0, "shear_softening": "none"}


def block(name, shape, density, contact, fixed=False):
    """A block body of the scene from its shape (vertices, faces)."""
    vertices, faces = shape
    body = {"name": name, "kind": "block", "density": density,
            "shape": {"polyhedron": {"vertices": rounded(vertices), "faces": faces}}, "contact": contact}
    if fixed:
        body["fixed"] = True
    return body


def strength_reduction_scene(description, lo, hi, bodies, stage):
    """A scene of blocks under gravity in the domain [lo, hi] whose pipeline is one strength_reduction stage."""
    return {
        "talus": 1,
        "description": description,
        "domain": {"dim": 3, "min": [round(v, 3) for v in lo], "max": [round(v, 3) for v in hi]},
        "gravity": [0, 0, -GRAVITY],
        "bodies": bodies,
        "pipeline": [stage],
        "time": {"end": 1.0},
        "outputs": [{"type": "hdf5", "every": 1.0}],
    }


def add_joint_options(ap, cohesion, friction):
    """The options a tessellation tool shares: the ground's weight, its joints, and the factor search."""
    ap.add_argument("--unit-weight", type=float, default=20e3, help="unit weight of the ground, N/m^3 (default 20e3)")
    ap.add_argument("--cohesion", type=float, default=cohesion, help="joint cohesion, Pa (default %g)" % cohesion)
    ap.add_argument("--friction", type=float, default=friction, help="joint friction angle, deg (default %g)" % friction)
    ap.add_argument("--tensile-strength", type=float, help="joint tensile strength, Pa (default c / tan(phi))")
    ap.add_argument("--joint-stiffness", type=float, default=1e8,
                    help="joint normal stiffness per unit area, Pa/m (default 1e8)")
    ap.add_argument("--bracket", type=float, nargs=2, default=[0.5, 3.0], help="factor bracket (default 0.5 3)")
    ap.add_argument("--tolerance", type=float, default=0.005, help="factor tolerance (default 0.005)")


def check_joint_options(ap, args):
    """Refuses (exit 2) what add_joint_options reads and no tessellation can use."""
    if not (args.unit_weight > 0 and args.joint_stiffness > 0):
        ap.error("--unit-weight and --joint-stiffness must be > 0")
    if args.cohesion < 0 or not 0 <= args.friction < 90:
        ap.error("--cohesion must be >= 0 and --friction in [0, 90)")


def tensile_strength(args):
    """The joints' tensile strength: as given, else the apex of the Mohr-Coulomb envelope c / tan(phi) (c without
    friction)."""
    if args.tensile_strength is not None:
        return args.tensile_strength
    return args.cohesion / math.tan(math.radians(args.friction)) if args.friction > 0 else args.cohesion


def write_scene(path, scene):
    """A scene file as the shipped block scenes are written (one-space indent, final newline)."""
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
