"""Shared pieces of the case modules: scene edits and HDF5 frames."""
import numpy as np


def read_csv(path):
    """dict column -> numpy array of a CSV with '#' comment lines and a header row (probes output, reference data)."""
    with open(path) as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")]
    names = lines[0].strip().split(",")
    data = np.array([[float(v) for v in line.strip().split(",")] for line in lines[1:]])
    return {n: data[:, k] for k, n in enumerate(names)}


def set_dp(scene, dp, kinds=("fluid", "wall")):
    """Sets every fluid/wall body's particle spacing."""
    for body in scene["bodies"]:
        if body["kind"] in kinds:
            body["dp"] = dp
    return scene


def periodic_strip(scene, dp, particles=8, axis=0):
    """Shortens a periodic channel scene along `axis` (0: x, 1: y) to `particles` spacings at every rung (the strip
    must span the kernel support): the domain and every body's box."""
    length = particles * dp
    scene["domain"]["max"][axis] = length
    for body in scene["bodies"]:
        next(iter(body["shape"].values()))["max"][axis] = length
    return scene


def whole_spacings(box, dp, axis):
    """Moves the box's max so that it spans a whole number of spacings dp along `axis` (the nearest): the host
    then fills it at dp itself, on the lattice write_row_raster's cells are centred on."""
    box["max"][axis] = box["min"][axis] + round((box["max"][axis] - box["min"][axis]) / dp) * dp
    return box


def write_row_raster(path, box, dp, value_of_y):
    """An ESRI ASCII raster (a release thickness) over a body's `box`, its cells centred on the lattice the box is
    filled with (spacing dp), every row the value at its y."""
    columns = int(round((box["max"][0] - box["min"][0]) / dp))
    rows = int(round((box["max"][1] - box["min"][1]) / dp))
    values = value_of_y(box["min"][1] + (np.arange(rows) + 0.5) * dp)
    with open(path, "w") as f:
        f.write(f"ncols {columns}\nnrows {rows}\nxllcorner {box['min'][0]!r}\nyllcorner {box['min'][1]!r}\n"
                f"cellsize {dp!r}\nNODATA_value -9999\n")
        for value in values[::-1]:  # north row first
            f.write(" ".join([f"{value:.10g}"] * columns) + "\n")


def row_averages(f, dp, *values):
    """Averages over each particle row (rows dp apart, y = (k + 1/2) dp) of a frame: (y, each of `values`)."""
    rows = np.round(f["y"] / dp - 0.5).astype(int)
    ids = np.unique(rows)
    return tuple(np.array([v[rows == r].mean() for r in ids]) for v in (f["y"], *values))


def last_frame(run):
    """(time, dict of numpy arrays) of the last frame of the run's HDF5 output."""
    with run.hdf5() as f:
        steps = sorted((k for k in f.keys() if k.startswith("Step#")), key=lambda k: int(k[5:]))
        g = f[steps[-1]]
        return float(g.attrs["TimeValue"][0]), {k: np.asarray(g[k]) for k in g.keys()}


def frames(run):
    """Every frame as (time, dict of arrays), in order."""
    with run.hdf5() as f:
        steps = sorted((k for k in f.keys() if k.startswith("Step#")), key=lambda k: int(k[5:]))
        for k in steps:
            g = f[k]
            yield float(g.attrs["TimeValue"][0]), {n: np.asarray(g[n]) for n in g.keys()}


def worst_density_deviation(run, stage="wcsph"):
    """The wcsph stage's running maximum of max |rho/rho0 - 1| over the whole run (a fraction), read from the
    summary's "stages" entry: "rho dev X% (worst Y% at t = T s)"."""
    import re
    text = run.summary.get("stages", {}).get(stage, "")
    m = re.search(r"worst ([0-9.eE+-]+|nan|inf)% at t = ([0-9.eE+-]+) s", text)
    if not m:
        raise RuntimeError(f"the {stage} stage's status '{text}' has no worst density deviation")
    return float(m.group(1)) / 100.0


def worst_density_time(run, stage="wcsph"):
    """When the worst density deviation occurred (s)."""
    import re
    m = re.search(r"worst .*% at t = ([0-9.eE+-]+) s", run.summary.get("stages", {}).get(stage, ""))
    return float(m.group(1)) if m else float("nan")


def _rotation(q):
    """Rotation matrix of the unit quaternion (w, x, y, z)."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def block_frames(run):
    """Every frame of the DDA blocks (HDF5 group Blocks) as (time, list of block dicts): name, fixed, mass, inertia
    (3x3, body frame), position, orientation (w, x, y, z), velocity, angular_velocity, vertices (world frame),
    faces (lists of vertex indices)."""
    with run.hdf5() as f:
        group = f["Blocks"]
        for key in sorted(group.keys(), key=lambda k: int(k[5:])):
            g = group[key]
            names = [n.decode() if isinstance(n, bytes) else n for n in g["name"][...]]
            verts, voff = np.asarray(g["vertices"]), np.asarray(g["vertex_offset"])
            fverts, foff, bfoff = np.asarray(g["face_vertices"]), np.asarray(g["face_offset"]), np.asarray(g["block_face_offset"])
            blocks = []
            for b, name in enumerate(names):
                q = np.asarray(g["orientation"][b])
                x = np.asarray(g["position"][b])
                local = verts[voff[b]:voff[b + 1]]
                faces = [list(fverts[foff[k]:foff[k + 1]]) for k in range(bfoff[b], bfoff[b + 1])]
                blocks.append({"name": name, "fixed": bool(g["fixed"][b]), "mass": float(g["mass"][b]),
                               "inertia": np.asarray(g["inertia"][b]).reshape(3, 3), "position": x, "orientation": q,
                               "velocity": np.asarray(g["velocity"][b]),
                               "angular_velocity": np.asarray(g["angular_velocity"][b]),
                               "vertices": x + local @ _rotation(q).T, "faces": faces})
            yield float(g.attrs["TimeValue"][0]), blocks


def _unique_directions(vectors):
    """Unit vectors up to sign, duplicates removed (a box has 3 face-normal and 3 edge directions)."""
    v = np.asarray(vectors, dtype=float)
    v = v[np.linalg.norm(v, axis=1) > 1e-12]
    v /= np.linalg.norm(v, axis=1)[:, None]
    pivot = np.argmax(np.abs(v) > 1e-9, axis=1)
    v *= np.sign(v[np.arange(len(v)), pivot])[:, None]
    return np.unique(np.round(v, 9), axis=0)


def _axes(vertices, faces):
    """Face normal and edge directions of a convex polyhedron."""
    normals, edges = [], []
    for face in faces:
        p = vertices[face]
        normals.append(np.cross(p[1] - p[0], p[2] - p[0]))
        edges.extend(p[np.r_[1:len(face), 0]] - p)
    return _unique_directions(normals), _unique_directions(edges)


def penetration_depth(a, b):
    """Depth of overlap of two convex polyhedra (block dicts of block_frames) by the separating-axis test over face
    normals and edge-edge cross products: 0 when they are apart or touch, else the smallest overlap along an axis."""
    va, vb = a["vertices"], b["vertices"]
    if np.any(va.max(0) < vb.min(0)) or np.any(vb.max(0) < va.min(0)):
        return 0.0
    na, ea = _axes(va, a["faces"])
    nb, eb = _axes(vb, b["faces"])
    cross = np.cross(ea[:, None, :], eb[None, :, :]).reshape(-1, 3)
    axes = np.vstack([na, nb] + ([_unique_directions(cross)] if np.any(np.linalg.norm(cross, axis=1) > 1e-9) else []))
    pa, pb = va @ axes.T, vb @ axes.T
    overlap = np.minimum(pa.max(0) - pb.min(0), pb.max(0) - pa.min(0))
    return 0.0 if np.any(overlap <= 0) else float(overlap.min())


def cached(function):
    """Memoises a per-run scan on the run's folder: worst() and gates() read the frames once."""
    store = {}

    def wrapper(run):
        if run.directory not in store:
            store[run.directory] = function(run)
        return store[run.directory]
    return wrapper


def block_energy(blocks, gravity):
    """Kinetic (translation + rotation) and gravitational potential energy of the free blocks, J."""
    g = np.asarray(gravity, dtype=float)
    kinetic = potential = 0.0
    for b in blocks:
        if b["fixed"]:
            continue
        r = _rotation(b["orientation"])
        inertia_world = r @ b["inertia"] @ r.T
        w = b["angular_velocity"]
        kinetic += 0.5 * b["mass"] * float(b["velocity"] @ b["velocity"]) + 0.5 * float(w @ inertia_world @ w)
        potential -= b["mass"] * float(g @ b["position"])
    return kinetic, potential
