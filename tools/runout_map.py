#!/usr/bin/env python3
"""Map of a run-out: the deposit (or any) raster written by the
depth_integrated_sph stage, over a hillshade of the terrain, as a PNG.

    tools/runout_map.py PREFIX [--raster deposit_thickness] [--out map.png]

PREFIX is the stage's "rasters" prefix: the script reads PREFIX_elevation.asc
and PREFIX_<raster>.asc (ESRI ASCII grids)."""
import argparse
import sys

import numpy as np

from esri_grid import read_asc

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "deposit_thickness": ("deposit thickness", "m"),
    "peak_thickness": ("peak thickness", "m"),
    "peak_velocity": ("peak velocity", "m/s"),
    "arrival_time": ("arrival time", "s"),
}


def hillshade(z, cell, azimuth=315.0, altitude=45.0):
    gy, gx = np.gradient(z, cell)  # rows run north to south
    slope = np.arctan(np.hypot(gx, gy))
    aspect = np.arctan2(-gx, gy)
    az, alt = np.radians(azimuth), np.radians(altitude)
    return np.clip(np.sin(alt) * np.cos(slope) + np.cos(alt) * np.sin(slope) * np.cos(az - aspect), 0, 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("prefix", help="raster prefix given to the stage (PREFIX_*.asc)")
    ap.add_argument("--raster", default="deposit_thickness", choices=sorted(LABELS), help="raster to map")
    ap.add_argument("--out", help="PNG file (default PREFIX_RASTER.png)")
    ap.add_argument("--min", type=float, default=0.01, help="values at or below this are left transparent")
    args = ap.parse_args()

    z, extent, _ = read_asc(f"{args.prefix}_elevation.asc")
    v, vextent, nodata = read_asc(f"{args.prefix}_{args.raster}.asc")
    if v.shape != z.shape or not np.allclose(extent, vextent):
        sys.exit(f"error: {args.prefix}_{args.raster}.asc is not on the grid of {args.prefix}_elevation.asc")
    cell = (extent[1] - extent[0]) / z.shape[1]
    shown = np.ma.masked_where((v == nodata) | (v <= args.min), v)

    fig, ax = plt.subplots(figsize=(8, 8 * z.shape[0] / z.shape[1] + 0.6), constrained_layout=True)
    ax.imshow(hillshade(z, cell), extent=extent, cmap="gray", vmin=0, vmax=1)
    ax.contour(np.flipud(z), levels=15, extent=extent, colors="k", linewidths=0.3, alpha=0.5)
    im = ax.imshow(shown, extent=extent, cmap="inferno_r" if args.raster != "arrival_time" else "viridis", alpha=0.85)
    name, unit = LABELS[args.raster]
    fig.colorbar(im, ax=ax, shrink=0.8, label=f"{name} ({unit})")
    if shown.count():
        total = float(shown.sum() * cell * cell)
        extra = f", integral {total:.4g} m3 (plan)" if "thickness" in args.raster else ""
        ax.set_title(f"{name}: max {float(shown.max()):.3g} {unit}{extra}")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    out = args.out or f"{args.prefix}_{args.raster}.png"
    fig.savefig(out, dpi=120)
    print("wrote", out)


if __name__ == "__main__":
    main()
