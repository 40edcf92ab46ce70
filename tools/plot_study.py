#!/usr/bin/python3
"""Plot a measure of a Talus study table (`talus study`, OUT/table.csv) against
one of its axes, one line per value of another axis.

Examples:
  tools/plot_study.py out/sweep/table.csv --x f --y xi -o xi.png
  tools/plot_study.py out/sweep/table.csv --x f --y H_G2 --by dp --logx --logy

Rows whose status is not "done", or whose x or y is empty, are left out (and
counted on stderr). Needs Debian's python3-matplotlib.
"""
import argparse
import csv
import sys
from collections import OrderedDict

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as e:  # pragma: no cover
    sys.exit(f"plot_study.py: {e}; install python3-matplotlib (Debian) and run with /usr/bin/python3")


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def series(rows, x, y, by):
    """{group value: [(x, y), ...]} over the finished rows, and how many were left out."""
    groups, skipped = OrderedDict(), 0
    for row in rows:
        xv, yv = number(row[x]), number(row[y])
        if row["status"] != "done" or xv is None or yv is None:
            skipped += 1
            continue
        groups.setdefault(row[by] if by else "", []).append((xv, yv))
    for points in groups.values():
        points.sort()
    return groups, skipped


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("table", help="OUT/table.csv of a study")
    p.add_argument("--x", required=True, help="the column on the horizontal axis (an axis of the study)")
    p.add_argument("--y", required=True, help="the column on the vertical axis (a measure)")
    p.add_argument("--by", help="one line per value of this column")
    p.add_argument("--logx", action="store_true")
    p.add_argument("--logy", action="store_true")
    p.add_argument("-o", "--output", default="study.png", help="image file (default study.png)")
    a = p.parse_args(argv)
    with open(a.table, newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        sys.exit(f"plot_study.py: {a.table}: no rows")
    for column in [a.x, a.y] + ([a.by] if a.by else []):
        if column not in rows[0]:
            sys.exit(f"plot_study.py: {a.table}: no column '{column}'; columns: {', '.join(rows[0].keys())}")
    groups, skipped = series(rows, a.x, a.y, a.by)
    if skipped:
        print(f"plot_study.py: {skipped} rows left out (not done, or no number in {a.x} or {a.y})", file=sys.stderr)
    if not groups:
        sys.exit(f"plot_study.py: {a.table}: no finished row with numbers in {a.x} and {a.y}")
    fig, ax = plt.subplots(figsize=(6, 4))
    for value, points in groups.items():
        ax.plot([q[0] for q in points], [q[1] for q in points], "o-", label=f"{a.by} = {value}" if a.by else None)
    ax.set_xlabel(a.x)
    ax.set_ylabel(a.y)
    if a.logx:
        ax.set_xscale("log")
    if a.logy:
        ax.set_yscale("log")
    if a.by:
        ax.legend()
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print(f"plot_study.py: wrote {a.output}")


if __name__ == "__main__":
    main()
