#!/usr/bin/env python3
"""Speed against error: runs every registered validation case over its
resolution ladder (and option sweeps) with the `talus` binary, measures
error, cost and stability, and writes a Markdown report, PNG plots of
error against wall time, and the raw CSV.

Each case runs as one `talus study` (a variant per rung and option) in
OUT/runs/CASE/variants/, so a stopped verification resumes with --reuse and
--jobs runs the rungs side by side.

  python3 tools/verify.py                 # full ladder, report in docs/verification/
  python3 tools/verify.py --quick         # smallest rung of every case (the test suite runs this)
  python3 tools/verify.py --case hydrostatic_2d --out /tmp/v
  python3 tools/verify.py --precision mixed --no-plots --out docs/verification/mixed   # fields in float
  python3 tools/verify.py --compare-precision docs/verification/mixed       # docs/verification/precision.md

Hard cases (cases/hard_*.py, HARD_CASE = True) are stability runs without a reference: the report's
"Hard cases (stability)" table gives whether each stayed stable, its worst measure over the whole run
(for SPH, the worst density deviation) and its gates.

Cases live in tools/verification/cases/, one module each; see
tools/verification/case.py for what a case defines.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from verification import precision, registry, report, runner  # noqa: E402


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="only the smallest rung of each case, no sweeps")
    parser.add_argument("--case", action="append", help="run only this case (repeatable)")
    parser.add_argument("--talus", default=os.path.join(root, "build", "bin", "talus"), help="the talus binary")
    parser.add_argument("--out", default=None, help="report folder (default docs/verification, or a scratch folder with --quick)")
    parser.add_argument("--threads", type=int, default=2, help="OpenMP threads per run")
    parser.add_argument("--list", action="store_true", help="list the registered cases and exit")
    parser.add_argument("--jobs", type=int, default=1, help="runs of a case side by side (each with --threads)")
    parser.add_argument("--reuse", action="store_true",
                        help="resume a case's study stored under --out when its runs are the same: finished runs are "
                             "judged again without running talus (new tolerances, gates or report layout), stopped "
                             "ones resume from their checkpoints; without it every case starts afresh")
    parser.add_argument("--walls", choices=["dbc", "mdbc"], default=None,
                        help="run every case that has particle walls (dynamic_particles, block_particles) with this "
                             "wall method; the option label says so, cases without such walls are skipped")
    parser.add_argument("--precision", choices=["double", "mixed"], default=None,
                        help="run every case with this scene \"precision\" (mixed: the fields that allow it in float); "
                             "the option label says so")
    parser.add_argument("--no-plots", action="store_true",
                        help="no PNG plot per case (a report beside another, such as the mixed-precision one)")
    parser.add_argument("--compare-precision", metavar="MIXED_OUT", default=None,
                        help="run nothing: compare the report in --out (double) with the one in MIXED_OUT (made with "
                             "--precision mixed) and write OUT/precision.md: every rung side by side, and whether "
                             "mixed precision may be the default")
    args = parser.parse_args()

    cases = registry.load_cases()
    if args.list:
        for c in cases:
            print(f"{c.NAME:28s} {c.TITLE}")
        return 0
    if args.case:
        unknown = set(args.case) - {c.NAME for c in cases}
        if unknown:
            print(f"error: unknown case(s) {', '.join(sorted(unknown))}; --list shows them", file=sys.stderr)
            return 2
        cases = [c for c in cases if c.NAME in args.case]
    if args.compare_precision:
        out = args.out or os.path.join(root, "docs", "verification")
        precision.write(os.path.join(out, "results.csv"), os.path.join(args.compare_precision, "results.csv"),
                        os.path.join(out, "precision.md"))
        return 0
    if not os.access(args.talus, os.X_OK):
        print(f"error: {args.talus} is not an executable talus; build first or pass --talus", file=sys.stderr)
        return 2
    out = args.out or (os.path.join(root, "build", "verify-quick") if args.quick else os.path.join(root, "docs", "verification"))
    os.makedirs(out, exist_ok=True)

    results = []
    for case in cases:
        results.extend(runner.run_case(case, args.talus, root, out, quick=args.quick, threads=args.threads,
                                      reuse=args.reuse, walls=args.walls, precision=args.precision,
                                      jobs=max(1, args.jobs)))
    # Re-running some cases updates an existing report: the other cases keep their stored results.
    all_cases = registry.load_cases()
    if args.case and not args.quick:
        results = report.read_previous(out, exclude={c.NAME for c in cases}, known={c.NAME for c in all_cases}) + results
    # An update in place keeps the machine line of the report's own run; the rerun cases say where they ran.
    header = report.stored_machine(out) if args.case and not args.quick else None
    report.write(results, all_cases if args.case and not args.quick else cases, out, quick=args.quick, header=header,
                 with_plots=not args.no_plots)
    ran = {c.NAME for c in cases}
    known = [r for r in results if r.case in ran and not r.passed and r.known]
    failed = [r for r in results if r.case in ran and not r.passed and not r.known]
    results = [r for r in results if r.case in ran]
    for r in known:
        print(f"  KNOWN DEVIATION {r.case} {r.option_label} resolution {r.resolution:g}: {r.failure}")
    for r in failed:
        print(f"  {'UNSTABLE' if r.hard else 'FAILED'} {r.case} {r.option_label} resolution {r.resolution:g}: {r.failure}")
    hard = [r for r in results if r.hard]
    if hard:
        print(f"hard cases: {sum(r.stable for r in hard)} of {len(hard)} runs stable")
    print(f"\n{len(results) - len(failed) - len(known)} passed, {len(failed)} failed, {len(known)} known deviations")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
