#!/usr/bin/python3
"""Plot probe time series written by the Talus 'probes' writer (CSV), optionally
against a reference data file.

The probe file has '#' comment lines (units, probe positions), a header row
and one row per output; a last line without its newline (a run killed while
writing) is ignored. A reference file is any CSV with '#' comment lines and a
header row, like the validation data in share/validation-data/*.csv; its first two columns are used
unless --ref-columns names others.

Examples:
  tools/plot_probes.py out/dam_probes.csv                         # every column
  tools/plot_probes.py out/dam_probes.csv --columns 'P1_*' G1_elevation -o probes.png
  # Buchner (2002) pressure at P1, non-dimensional (H = 0.6 m, rho = 1000):
  tools/plot_probes.py out/dam_probes.csv --columns P1_pressure \\
      --time-scale 4.0435 --value-scale 1.699e-4 \\
      --reference share/validation-data/dambreak2d_buchner2002_P1_pysph.csv \\
      --xlabel 't sqrt(g/H)' --ylabel 'p/(rho g H)'

Needs Debian's python3-numpy and python3-matplotlib.
"""
import argparse
import fnmatch
import math
import os
import sys

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as e:  # pragma: no cover
    sys.exit(f"plot_probes.py: {e}; install python3-numpy python3-matplotlib (Debian) and run with /usr/bin/python3")


def read_csv(path):
    """(header, rows as a 2-D float array, units by column name or {})."""
    with open(path, "r", encoding="utf-8") as fh:
        text = fh.read()
    lines = text.split("\n")
    if not text.endswith("\n"):
        lines = lines[:-1]  # incomplete last line
    header, rows, units_line = None, [], None
    for line in lines:
        if not line.strip():
            continue
        if line.startswith("#"):
            if line.startswith("# units:"):
                units_line = line[len("# units:"):].strip()
            continue
        cells = [c.strip() for c in line.split(",")]
        if header is None:
            header = cells
            continue
        try:
            rows.append([float(c) if c else math.nan for c in cells])
        except ValueError:
            sys.exit(f"plot_probes.py: {path}: not a number in row {len(rows) + 1}: {line[:80]}")
    if header is None:
        sys.exit(f"plot_probes.py: {path}: no header row")
    data = np.array(rows, dtype=float).reshape(-1, len(header))
    units = {}
    if units_line is not None:
        parts = units_line.split(",")
        if len(parts) == len(header):
            units = dict(zip(header, parts))
    return header, data, units


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                epilog="\n\n".join(__doc__.split("\n\n")[1:]),
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("file", help="probe CSV of the 'probes' writer")
    p.add_argument("--columns", nargs="+", help="columns to plot (names or shell patterns like 'P1_*'); default all")
    p.add_argument("--x-column", default="time", help="column on the horizontal axis (default time)")
    p.add_argument("--time-scale", type=float, default=1.0, help="multiply the probe's x values by this")
    p.add_argument("--value-scale", type=float, default=1.0, help="multiply the probe's values by this")
    p.add_argument("--reference", action="append", default=[],
                   help="reference CSV to overlay (may be repeated)")
    p.add_argument("--ref-columns", nargs=2, metavar=("X", "Y"),
                   help="reference columns to plot (default its first two)")
    p.add_argument("--ref-label", action="append", default=[], help="legend label of each reference file")
    p.add_argument("--separate", action="store_true", help="one panel per column instead of one shared panel")
    p.add_argument("--xlabel", help="horizontal axis label")
    p.add_argument("--ylabel", help="vertical axis label")
    p.add_argument("--title", help="figure title (default the file name)")
    p.add_argument("-o", "--output", help="PNG to write (default FILE.png beside the input)")
    p.add_argument("--dpi", type=int, default=150)
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    header, data, units = read_csv(args.file)
    if args.x_column not in header:
        sys.exit(f"plot_probes.py: no column '{args.x_column}'; columns: {', '.join(header)}")
    skip = {args.x_column, "time", "step"}
    if args.columns:
        chosen = []
        for pattern in args.columns:
            hits = [h for h in header if fnmatch.fnmatchcase(h, pattern)]
            if not hits:
                sys.exit(f"plot_probes.py: no column matches '{pattern}'; columns: {', '.join(header)}")
            chosen += [h for h in hits if h not in chosen]
    else:
        chosen = [h for h in header if h not in skip]
    if not chosen:
        sys.exit("plot_probes.py: nothing to plot")

    x = data[:, header.index(args.x_column)] * args.time_scale
    panels = len(chosen) if args.separate else 1
    fig, axes = plt.subplots(panels, 1, figsize=(8, 2.6 * panels + 1.0), sharex=True, squeeze=False)
    for k, name in enumerate(chosen):
        ax = axes[k if args.separate else 0][0]
        unit = units.get(name, "")
        label = f"{name} [{unit}]" if unit and args.value_scale == 1.0 else name
        ax.plot(x, data[:, header.index(name)] * args.value_scale, label=label, lw=1.2)
    for r, ref in enumerate(args.reference):
        rh, rd, _ = read_csv(ref)
        cx, cy = args.ref_columns if args.ref_columns else (rh[0], rh[1])
        if cx not in rh or cy not in rh:
            sys.exit(f"plot_probes.py: {ref}: no columns {cx}, {cy}; columns: {', '.join(rh)}")
        order = np.argsort(rd[:, rh.index(cx)], kind="stable")
        label = args.ref_label[r] if r < len(args.ref_label) else os.path.basename(ref)
        for row in axes:
            row[0].plot(rd[order, rh.index(cx)], rd[order, rh.index(cy)], "o", ms=3, mfc="none", label=label)
    for row in axes:
        ax = row[0]
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        if args.ylabel:
            ax.set_ylabel(args.ylabel)
    axes[-1][0].set_xlabel(args.xlabel or (f"{args.x_column} [s]" if args.x_column == "time" and args.time_scale == 1.0
                                            else args.x_column))
    fig.suptitle(args.title or os.path.basename(args.file))
    fig.tight_layout()
    out = args.output or os.path.splitext(args.file)[0] + ".png"
    fig.savefig(out, dpi=args.dpi)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
