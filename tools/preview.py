#!/usr/bin/python3
"""Render a PNG preview of one frame of a Talus HDF5 (H5Part) output file.

Particles are drawn as dots coloured by a field; rigid blocks (the Blocks
group written beside the particles) are outlined. 2D runs are drawn in their
x-y plane; 3D runs are projected on a plane (x-z by default, the side view of
a tank), nearer particles drawn over farther ones.

Examples:
  tools/preview.py out/dam_break.h5part                       # last frame, pressure
  tools/preview.py out/dam_break.h5part --frame 10 --field velocity -o f10.png
  tools/preview.py out/dam_break.h5part --time 0.5 --plane xy --boundary out/dam_break_boundary.h5part

Needs Debian's python3-numpy, python3-matplotlib and python3-h5py.
File layout: docs/output-formats.md.
"""
import argparse
import os
import sys

try:
    import h5py
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
except ImportError as e:  # pragma: no cover
    sys.exit(f"preview.py: {e}; install python3-numpy python3-matplotlib python3-h5py (Debian) "
             "and run with /usr/bin/python3")

AXES = {"x": 0, "y": 1, "z": 2}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                epilog="\n".join(__doc__.split("\n\n")[2:]),
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("file", help="HDF5 output of the 'hdf5' writer (SCENE.h5part)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--frame", type=int, default=-1,
                   help="frame index (Step#N); negative counts from the end (default -1, the last)")
    g.add_argument("--time", type=float, help="the frame nearest to this simulated time, s")
    p.add_argument("--field", default=None,
                   help="colour by this field: a scalar (pressure), a vector (velocity: its magnitude) or "
                        "one component (velocity_0); default pressure if written, else the first field")
    p.add_argument("--plane", choices=["xy", "xz", "yz"], default=None,
                   help="projection plane for 3D runs (default xz); 2D runs are always drawn in xy")
    p.add_argument("--boundary", help="also draw the wall particles of this file (SCENE_boundary.h5part) in grey")
    p.add_argument("--no-blocks", action="store_true", help="do not outline rigid blocks")
    p.add_argument("--cmap", default="viridis", help="matplotlib colour map (default viridis)")
    p.add_argument("--vmin", type=float, help="lower end of the colour scale (default: the data's minimum)")
    p.add_argument("--vmax", type=float, help="upper end of the colour scale (default: the data's maximum)")
    p.add_argument("--width", type=float, default=8.0, help="figure width in inches (default 8)")
    p.add_argument("--dpi", type=int, default=150, help="resolution of the PNG (default 150)")
    p.add_argument("-o", "--output", help="PNG to write (default FILE_frameN.png beside the input)")
    return p.parse_args(argv)


def text_attr(obj, name, default=""):
    if name not in obj.attrs:
        return default
    v = obj.attrs[name]
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray):
        v = v.flat[0]
    return v.decode() if isinstance(v, bytes) else v


def number_attr(obj, name, default=None):
    if name not in obj.attrs:
        return default
    return np.asarray(obj.attrs[name]).flat[0]


def frames(f):
    steps = sorted((int(k.split("#")[1]) for k in f.keys() if k.startswith("Step#")))
    return steps


def pick_frame(f, args):
    steps = frames(f)
    if not steps:
        sys.exit(f"preview.py: {args.file} has no Step#N groups (not a Talus/H5Part file?)")
    if args.time is not None:
        times = [number_attr(f[f"Step#{s}"], "TimeValue", 0.0) for s in steps]
        return steps[int(np.argmin(np.abs(np.asarray(times) - args.time)))]
    try:
        return steps[args.frame]
    except IndexError:
        sys.exit(f"preview.py: frame {args.frame} out of range; {args.file} has {len(steps)} frames")


def field_values(group, name):
    """Values of a scalar, vector magnitude or component; and the unit."""
    if name in group:
        d = group[name]
        return np.asarray(d[...], dtype=float), text_attr(d, "unit"), name
    comps = [f"{name}_{k}" for k in range(3) if f"{name}_{k}" in group]
    if comps:
        v = np.stack([np.asarray(group[c][...], dtype=float) for c in comps])
        return np.sqrt((v ** 2).sum(axis=0)), text_attr(group[comps[0]], "unit"), f"|{name}|"
    known = sorted({k.rsplit("_", 1)[0] if k.rsplit("_", 1)[-1].isdigit() else k for k in group.keys()})
    sys.exit(f"preview.py: no field '{name}' in this frame; known: {', '.join(known)}")


def default_field(group):
    if "pressure" in group:
        return "pressure"
    for k in sorted(group.keys()):
        if k not in ("x", "y", "z", "id", "body", "material"):
            return k.rsplit("_", 1)[0] if k.rsplit("_", 1)[-1].isdigit() else k
    return "x"


def quaternion_matrix(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def block_polygons(f, step, a, b):
    """Projected faces of every block at this frame, as a list of (k, 2) arrays."""
    name = f"Blocks/Step#{step}"
    if name not in f:
        return []
    g = f[name]
    pos, quat = g["position"][...], g["orientation"][...]
    verts, voff = g["vertices"][...], g["vertex_offset"][...]
    fverts, foff, bfoff = g["face_vertices"][...], g["face_offset"][...], g["block_face_offset"][...]
    polys = []
    for k in range(len(pos)):
        local = verts[voff[k]:voff[k + 1]]
        world = local @ quaternion_matrix(quat[k]).T + pos[k]
        for face in range(bfoff[k], bfoff[k + 1]):
            idx = fverts[foff[face]:foff[face + 1]]
            polys.append(world[idx][:, [a, b]])
    return polys


def main(argv=None):
    args = parse_args(argv)
    with h5py.File(args.file, "r") as f:
        dim = int(number_attr(f, "dim", 3))
        plane = "xy" if dim == 2 else (args.plane or "xz")
        a, b = AXES[plane[0]], AXES[plane[1]]
        depth = 3 - a - b
        step = pick_frame(f, args)
        group = f[f"Step#{step}"]
        xyz = np.stack([np.asarray(group[c][...], dtype=float) for c in ("x", "y", "z")], axis=1)
        field = args.field or default_field(group)
        values, unit, label = field_values(group, field)
        time = number_attr(group, "TimeValue", 0.0)
        sim_step = number_attr(group, "step", 0)
        dp = number_attr(f, "dp", 0.0)
        lo = np.asarray(f.attrs["domain_min"], dtype=float) if "domain_min" in f.attrs else xyz.min(axis=0)
        hi = np.asarray(f.attrs["domain_max"], dtype=float) if "domain_max" in f.attrs else xyz.max(axis=0)
        polys = [] if args.no_blocks else block_polygons(f, step, a, b)
        scene = text_attr(f, "scene_name", os.path.basename(args.file))

    wall = None
    if args.boundary:
        with h5py.File(args.boundary, "r") as fb:
            wsteps = frames(fb)
            ws = step if step in wsteps else (wsteps[-1] if wsteps else None)
            if ws is not None:
                gb = fb[f"Step#{ws}"]
                wall = np.stack([np.asarray(gb[c][...], dtype=float) for c in ("x", "y", "z")], axis=1)

    # Extent: the domain, grown to whatever particles lie outside it (walls).
    everything = np.concatenate([p for p in (xyz, wall) if p is not None and len(p)] or [np.zeros((1, 3))])
    data_lo, data_hi = everything.min(axis=0), everything.max(axis=0)
    ext_lo = np.where(np.isfinite(lo), np.minimum(lo, data_lo), data_lo)
    ext_hi = np.where(np.isfinite(hi), np.maximum(hi, data_hi), data_hi)
    span_a, span_b = max(ext_hi[a] - ext_lo[a], 1e-12), max(ext_hi[b] - ext_lo[b], 1e-12)
    height = max(2.0, min(args.width * span_b / span_a + 0.8, 3 * args.width))
    fig, ax = plt.subplots(figsize=(args.width, height))
    ax.set_xlim(ext_lo[a], ext_hi[a])
    ax.set_ylim(ext_lo[b], ext_hi[b])
    ax.set_aspect("equal")
    # Dots about one particle spacing wide: measure the laid-out axes in points.
    fig.canvas.draw()
    axes_points = ax.get_window_extent().width * 72.0 / fig.dpi
    points_per_metre = axes_points / span_a
    size = max(0.3, (dp * points_per_metre) ** 2) if dp > 0 else 4.0

    if wall is not None and len(wall):
        ax.scatter(wall[:, a], wall[:, b], s=size, c="0.6", marker="s", linewidths=0)
    order = np.argsort(-xyz[:, depth]) if dim == 3 else np.arange(len(xyz))
    sc = ax.scatter(xyz[order, a], xyz[order, b], s=size, c=values[order], cmap=args.cmap,
                    vmin=args.vmin, vmax=args.vmax, linewidths=0)
    if polys:
        ax.add_collection(PolyCollection(polys, facecolors="none", edgecolors="k", linewidths=1.0))
    ax.set_xlabel(f"{plane[0]} [m]")
    ax.set_ylabel(f"{plane[1]} [m]")
    ax.set_title(f"{scene}: t = {time:.6g} s (step {int(sim_step)}, frame {step}), {len(xyz)} particles")
    cb = fig.colorbar(sc, ax=ax, shrink=0.8)
    cb.set_label(f"{label} [{unit}]" if unit else label)
    out = args.output or os.path.splitext(args.file)[0] + f"_frame{step}.png"
    fig.savefig(out, dpi=args.dpi, bbox_inches="tight")
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
