"""Shared pieces of the case modules: scene edits and HDF5 frames."""
import numpy as np


def set_dp(scene, dp, kinds=("fluid", "wall")):
    """Sets every fluid/wall body's particle spacing."""
    for body in scene["bodies"]:
        if body["kind"] in kinds:
            body["dp"] = dp
    return scene


def last_frame(run):
    """(time, dict of numpy arrays) of the last frame of the run's HDF5 output."""
    with run.hdf5() as f:
        steps = sorted((k for k in f.keys() if k.startswith("Step#")), key=lambda k: int(k[5:]))
        g = f[steps[-1]]
        return float(g.attrs["TimeValue"][0]), {k: np.asarray(g[k]) for k in g.keys()}


def frames(run):
    """Every frame as (time, dict of arrays), in order."""
    with run.hdf5() as f:
        steps = sorted((k for k in f.keys() if k.startswith("Step#")), key=lambda k: int(k[5:]))
        for k in steps:
            g = f[k]
            yield float(g.attrs["TimeValue"][0]), {n: np.asarray(g[n]) for n in g.keys()}
