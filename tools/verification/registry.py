"""Finds the case modules in tools/verification/cases/."""
import importlib
import os
import pkgutil

REQUIRED = ("NAME", "TITLE", "SCENE", "LADDER", "TOLERANCE", "ERROR_LABEL", "REFERENCE", "configure", "error")
# Stability-only cases (HARD_CASE = True): no reference, a worst-over-the-run measure and gates instead.
REQUIRED_HARD = ("NAME", "TITLE", "SCENE", "LADDER", "TOLERANCE", "STRESSES", "WORST_LABEL", "configure", "worst",
                 "gates")


def is_hard(case):
    return bool(getattr(case, "HARD_CASE", False))


def check_case(module, name):
    """Refuses a case module that misses part of its contract (SystemExit with the reason)."""
    hard = is_hard(module)
    missing = [k for k in (REQUIRED_HARD if hard else REQUIRED) if not hasattr(module, k)]
    if missing:
        raise SystemExit(f"error: case module {name} lacks {', '.join(missing)}")
    if hard:
        if not module.LADDER:
            raise SystemExit(f"error: hard case {module.NAME} needs at least one rung in LADDER")
        no_limit = [r for r in module.LADDER if r not in module.TOLERANCE]
        if no_limit:
            raise SystemExit(f"error: hard case {module.NAME} has no TOLERANCE (limit on worst()) for rung(s) "
                             f"{', '.join(f'{r:g}' for r in no_limit)}: every hard case needs a criterion that can fail")
    elif len(module.LADDER) < 3:
        raise SystemExit(f"error: case {module.NAME} needs a ladder of at least three resolutions")


def load_cases():
    here = os.path.join(os.path.dirname(__file__), "cases")
    cases = []
    for info in sorted(pkgutil.iter_modules([here]), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue  # shared helpers, not cases
        module = importlib.import_module(f"verification.cases.{info.name}")
        check_case(module, info.name)
        cases.append(module)
    return cases
