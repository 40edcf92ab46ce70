"""Strength reduction with no slip surface given: the Griffiths & Lane slope cut into triangular blocks."""
import os
import sys

from .planar_slide import safety_factor, trials

sys.path.insert(0, os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
import tessellate_slope  # noqa: E402  (tools/, beside the harness)

NAME = "tessellated_slope"
TITLE = ("Safety factor of a homogeneous slope with no slip surface given (Griffiths & Lane 1999, example 1: H = 10 m "
         "at 2:1, c = 10 kPa, phi = 20 deg, gamma = 20 kN/m^3, base at the toe), the section cut into triangular "
         "blocks with fixed joints (rigid-block-spring method); ladder: block size (m)")
SCENE = "share/scenes/tessellated_slope.json"
LADDER = [2.5, 1.25, 0.625]
# The reference factors differ by 1.4 % (finite elements 1.40, Bishop 1.38); agreement is within 2 % of 1.40.
TOLERANCE = {cell: 0.02 for cell in LADDER}
ERROR_LABEL = "|F_s / 1.40 - 1|"
REFERENCE = ("Griffiths & Lane (1999), Geotechnique 49(3), example 1: F = 1.40 by elasto-plastic finite elements with "
             "strength reduction, 1.38 from Bishop & Morgenstern's charts; tools/bishop_circle.py gives 1.3776 on the "
             "scene's own geometry")
KNOWN_DEVIATION = (
    "Rigid blocks overestimate the factor: a block's strength is only tested on its faces, so a slip surface must "
    "follow them, and joints without dilatancy lock where it kinks. F_s falls with the block size, slowly and without "
    "a readable order (1.4885, 1.4866, 1.4805, 1.4769, 1.4726 at 5 to 0.3125 m, each to 0.001), and stays about 5 % "
    "above the finite-element factor; other patterns do not help (both diagonals in the wedge 1.484, nodes moved at "
    "random 1.538, at 1.25 m). Deformable blocks on the same cut would not help either: at a steady collapse the "
    "stresses stop changing, so elastic blocks move rigidly and the mechanism is still one of the cut's joints.")


def configure(scene, cell, option):
    # A bisection to 0.001 (not the tool's 0.005), so that the rungs' factors differ by more than their brackets.
    scene, _, _ = tessellate_slope.scene(tessellate_slope.parse(["--cell", str(cell), "--tolerance", "0.001",
                                                                 "--out", "unused"]))
    scene["outputs"] = []
    return scene


def error(run):
    return abs(safety_factor(run)[0] / 1.40 - 1.0)


def gates(run):
    fs, holds, fails = safety_factor(run)
    rows = [r for r in trials(run) if r["factor"] != "elastic"]
    failed = [r for r in rows if r["outcome"] == "failed"]
    collapse = all(r["no_equilibrium"] == "1" or r["displacement_limit"] == "1" or r["displacement_growing"] == "1"
                   for r in failed)
    holding = max((r for r in rows if r["outcome"] == "stable"), key=lambda r: float(r["factor"]), default=None)
    failing = min(failed, key=lambda r: float(r["factor"]), default=None)
    # The crest belongs to the slide: at the final bracket it moves much farther in the failing trial.
    crest = (float(failing["monitor0_d_m"]) / float(holding["monitor0_d_m"])
             if holding and failing and float(holding["monitor0_d_m"]) > 0 else 0.0)
    return [(f"F_s = {fs:.4f} inside its final bracket", holds <= fs <= fails, f"[{holds:.4f}, {fails:.4f}]"),
            ("every failing trial collapses (no equilibrium or displacement)", collapse and bool(failed),
             f"{len(failed)} failing trials"),
            ("at the final bracket the crest moves at least twice as far in the failing trial", crest >= 2.0,
             f"{crest:.1f} times as far")]
