"""The verification report in double against the same cases run with "precision": "mixed": which rungs move, which
pass, and what that says about the default precision (verify.py --compare-precision)."""
import csv
import math
import os

from verification.report import cell, fmt, number

MIXED_LABEL = "precision=mixed"


def read_rows(path):
    """results.csv as a list of dicts; a missing file is an error naming it."""
    if not os.path.exists(path):
        raise SystemExit(f"error: {path}: no results.csv there (run verify.py with --out into that folder first)")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def option_without_precision(label):
    """The option label of a mixed run without its precision part, as the double report labels the same run."""
    parts = [p for p in label.split(", ") if p != MIXED_LABEL]
    return ", ".join(parts) or "default"


def outcome(row):
    """'pass', 'known' (a documented open deviation, accuracy only) or 'fail'."""
    if row["passed"] == "True":
        return "pass"
    return "known" if row.get("known_deviation") == "True" else "fail"


def shown(row):
    if row is None:
        return "not run"
    hard = row.get("hard_case") == "True"
    return {"pass": "stable" if hard else "pass", "known": "known deviation",
            "fail": "**UNSTABLE**" if hard else "**FAIL**"}[outcome(row)]


def passed(rows):
    """'N passed', with the known deviations among the others counted."""
    known = sum(outcome(r) == "known" for r in rows)
    return f"{sum(outcome(r) == 'pass' for r in rows)}" + (f" ({known} known deviation{'s' if known > 1 else ''})" if known else "")


def pair_rows(double_rows, mixed_rows):
    """{case: [(key, double row or None, mixed row or None)]}, the cases in name order and each case's rungs in the
    double report's order, mixed rows keyed by (option without precision, resolution); mixed rows the double report
    lacks come last."""
    mixed = {(r["case"], option_without_precision(r["option"]), float(r["resolution"])): r for r in mixed_rows}
    cases = {name: [] for name in sorted({r["case"] for r in double_rows + mixed_rows})}  # as the report orders them
    seen = set()
    for r in double_rows:
        key = (r["case"], r["option"], float(r["resolution"]))
        cases[r["case"]].append((key, r, mixed.get(key)))
        seen.add(key)
    for key, r in mixed.items():
        if key not in seen:
            cases[key[0]].append((key, None, r))
    return cases


def relative_change(double, mixed):
    a, b = number(double, "error"), number(mixed, "error")
    return (b - a) / abs(a) if math.isfinite(a) and math.isfinite(b) and a != 0 else float("nan")


def change_in_tolerances(double, mixed):
    """(mixed error - double error) / tolerance: how much of the tolerance the precision moves (nan without one).
    Unlike the relative change it stays small where both errors are at round-off."""
    a, b, tolerance = number(double, "error"), number(mixed, "error"), number(double, "tolerance")
    return (b - a) / tolerance if math.isfinite(a) and math.isfinite(b) and tolerance > 0 else float("nan")


def verdict(cases):
    """(mixed may be the default, the reasons as Markdown bullet lines)."""
    not_run = [c for c, pairs in cases.items() if not any(m for _, _, m in pairs)]
    partly = [c for c, pairs in cases.items() if c not in not_run and any(m is None for _, _, m in pairs)]
    both, only_mixed, only_double = [], [], []
    for c, pairs in cases.items():
        for (_, option, resolution), d, m in pairs:
            if m is None:
                continue
            where = f"`{c}` {option} {resolution:g}"
            in_double = "pass" if d is None else outcome(d)
            if outcome(m) == "fail" and in_double != "pass":
                both.append(where)
            elif outcome(m) != "pass" and in_double == "pass":
                only_mixed.append(where)  # a known deviation too: it is one only where double has it
            elif outcome(m) == "pass" and in_double == "fail":
                only_double.append(where)
    reasons = []
    if only_mixed:
        reasons.append(f"- fails in mixed precision only: {', '.join(only_mixed)}")
    if both:
        reasons.append(f"- fails in both precisions: {', '.join(both)}")
    if not_run:
        reasons.append(f"- not run in mixed precision: {', '.join(f'`{c}`' for c in sorted(not_run))}")
    if partly:
        reasons.append(f"- run in mixed precision on part of its ladder: {', '.join(f'`{c}`' for c in sorted(partly))}")
    if only_double:
        reasons.append(f"- fails in double only (passes in mixed): {', '.join(only_double)}")
    allowed = not (only_mixed or both or not_run or partly)
    return allowed, reasons


def write(double_csv, mixed_csv, path):
    """Writes the comparison page to `path`; returns whether mixed precision may be the default."""
    double_rows, mixed_rows = read_rows(double_csv), read_rows(mixed_csv)
    if any(MIXED_LABEL in r["option"] for r in double_rows):
        raise SystemExit(f"error: {double_csv}: holds runs in mixed precision; pass the double report's folder as --out")
    stray = sorted({r["case"] for r in mixed_rows if MIXED_LABEL not in r["option"]})
    if stray:
        raise SystemExit(f"error: {mixed_csv}: rows of {', '.join(stray)} were not run with --precision mixed")
    cases = pair_rows(double_rows, mixed_rows)
    allowed, reasons = verdict(cases)
    lines = ["# Precision: double and mixed", "",
             "A scene runs in double unless it says `\"precision\": \"mixed\"`. Mixed precision keeps in float the fields "
             "whose every reader allows it (DESIGN.md, principle 6); positions stay double, and the terms compute in "
             "double. "
             "Which fields a run kept in float is in its summary; the column *in float* gives them. Where a case's "
             "fluid keeps only `velocity_n, density_n` (the integrator's saved state) in float, its scene has a term "
             "that reads the fluid in double (a non-Newtonian rheology, a block's walls), and the run is close to "
             "its double run by construction.", "",
             f"Double: `{os.path.relpath(double_csv, os.path.dirname(path))}`; mixed: "
             f"`{os.path.relpath(mixed_csv, os.path.dirname(path))}` (`python3 tools/verify.py --precision mixed "
             "--no-plots --out docs/verification/mixed`). Each mixed row names the commit it ran at. Regenerate this "
             "page with `python3 tools/verify.py --compare-precision docs/verification/mixed`.", "",
             "## Default", ""]
    if allowed:
        lines += ["Every rung of every case runs in mixed precision and passes: mixed precision may be the default.", ""]
    else:
        lines += ["**The default stays double.** Mixed precision becomes the default only when every rung of every case "
                  "passes in it. Not yet:", ""] + reasons + [""]
    lines += ["## Cases", "",
              "| case | rungs | run in mixed | in float (mixed) | passed, double | passed, mixed | largest change of the error, in tolerances | mixed at commit |",
              "|---|---|---|---|---|---|---|---|"]
    for c, pairs in cases.items():
        mixed = [m for _, _, m in pairs if m is not None]
        changes = [change_in_tolerances(d, m) for _, d, m in pairs if d is not None and m is not None]
        changes = [x for x in changes if math.isfinite(x)]
        largest = max(changes, key=abs) if changes else float("nan")
        floats = sorted({m.get("in_float") or "?" for m in mixed})
        commits = sorted({m.get("commit") or "?" for m in mixed})
        lines.append(f"| `{c}` | {sum(d is not None for _, d, _ in pairs)} | {len(mixed)} | {cell(' / '.join(floats)) or '—'} | "
                     f"{passed([d for _, d, _ in pairs if d is not None])} | {passed(mixed)} | "
                     f"{fmt(largest, '+.2g')} | {', '.join(commits) or '—'} |")
    lines.append("")
    for c, pairs in cases.items():
        if not any(m for _, _, m in pairs):
            continue
        hard = any((d or m).get("hard_case") == "True" for _, d, m in pairs)
        measure = "worst measure" if hard else "error"
        lines += [f"### {c}", "",
                  f"| option | resolution | {measure}, double | {measure}, mixed | change | in tolerances | "
                  f"{'limit' if hard else 'tolerance'} | double | mixed |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for (_, option, resolution), d, m in pairs:
            both = d is not None and m is not None
            change = relative_change(d, m) if both else float("nan")
            share = change_in_tolerances(d, m) if both else float("nan")
            lines.append(f"| {cell(option)} | {resolution:g} | {fmt(number(d, 'error') if d else None, '.4g')} | "
                         f"{fmt(number(m, 'error') if m else None, '.4g')} | "
                         f"{fmt(change * 100, '+.3g') + ' %' if math.isfinite(change) else '—'} | {fmt(share, '+.2g')} | "
                         f"{fmt(number(d or m, 'tolerance'), '.3g')} | {shown(d)} | {shown(m)} |")
        failures = [(option, resolution, m["failure"]) for (_, option, resolution), _, m in pairs
                    if m is not None and outcome(m) != "pass"]
        if failures:
            lines += [""] + [f"- mixed, {cell(option)} {resolution:g}: {cell(text)}" for option, resolution, text in failures]
        lines.append("")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    print(f"verify: precision comparison in {path}")
    return allowed
