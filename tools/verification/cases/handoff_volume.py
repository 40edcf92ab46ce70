"""Landslide hand-off: the volume of the planar slide's failed slab in the run-out's release raster."""
import os
import re

NAME = "handoff_volume"
TITLE = ("Hand-off of the failed planar slide to run-out: volume of the released slab (20 m x 4 m x 8.66 m) in the "
         "vertical thickness raster; ladder: the raster cell")
SCENE = "share/scenes/planar_slide_chain.json"
LADDER = [1.0, 0.5, 0.25]
# The thickness is averaged over 8 x 8 points per cell, so a slab edge inside a cell is placed to cell/16: the
# error is bounded by 2 (cell / 16) / 17.32 m along the slope but depends on where the edges fall, not only on
# the cell (the 0.5 and 0.25 m grids both put the lower end at the same sub-sample).
CONVERGES = False
TOLERANCE = {1.0: 0.01, 0.5: 0.01, 0.25: 0.01}  # the gate
ERROR_LABEL = "|V_raster / V_slab - 1|"
REFERENCE = "V_slab = 20 x 4 x 8.660 m = 692.82 m^3 (the released block's volume)"
SLAB = 20.0 * 4.0 * 8.660254037844386
TEMPLATE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", "share", "scenes",
                                        "planar_slide_runout.json"))


def configure(scene, cell, option):
    handoff = scene["pipeline"][0]["handoff"]
    handoff.pop("dem", None)
    handoff.update({"cell": cell, "margin": 1.0, "runout_scene": TEMPLATE})
    scene["outputs"] = []
    return scene


def volumes(run):
    for line in run.summary.get("finish", []):
        m = re.search(r"released volume ([0-9.e+]+) m\^3, in the thickness raster ([0-9.e+]+) m\^3", line)
        if m:
            return float(m.group(1)), float(m.group(2))
    raise RuntimeError("the run reported no hand-off: " + "; ".join(run.summary.get("finish", [])))


def error(run):
    return abs(volumes(run)[1] / SLAB - 1.0)


def gates(run):
    released, _ = volumes(run)
    return [("the released blocks are the slab", abs(released / SLAB - 1.0) < 1e-5,
             f"released {released:.6g} m^3 of {SLAB:.6g}")]
