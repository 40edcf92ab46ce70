"""Validation cases, one module each (see ../case.py)."""
