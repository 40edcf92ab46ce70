"""Finds the case modules in tools/verification/cases/."""
import importlib
import os
import pkgutil

REQUIRED = ("NAME", "TITLE", "SCENE", "LADDER", "TOLERANCE", "ERROR_LABEL", "REFERENCE", "configure", "error")


def load_cases():
    here = os.path.join(os.path.dirname(__file__), "cases")
    cases = []
    for info in sorted(pkgutil.iter_modules([here]), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue  # shared helpers, not cases
        module = importlib.import_module(f"verification.cases.{info.name}")
        missing = [k for k in REQUIRED if not hasattr(module, k)]
        if missing:
            raise SystemExit(f"error: case module {info.name} lacks {', '.join(missing)}")
        if len(module.LADDER) < 3:
            raise SystemExit(f"error: case {module.NAME} needs a ladder of at least three resolutions")
        cases.append(module)
    return cases
