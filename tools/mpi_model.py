#!/usr/bin/env python3
"""Time per step of a run on several MPI ranks, from the measured compute rate,
the halo volume and the messages a step sends (docs/mpi.md, "Cost model").

  t_step = imbalance * (owned + halo_cost * halo
                        + rebuild_cost * (owned + halo) / rebuild_every) / rate     compute
         + refreshes * (neighbours * latency + halo * row_bytes / bandwidth)         halo refreshes
         + reductions * ceil(log2(ranks)) * latency                                  time step, checks

rate is one rank's particle-steps per second with every core of its node busy;
halo_cost what a halo row costs in a step relative to an owned one (binned,
sorted, integrated and refreshed, its neighbours walked); rebuild_cost what
one rebuild of owners and halos costs per row relative to one step of an
owned row, every rebuild_every steps; imbalance the busiest rank's work over
the mean. tools/bench_ranks.py measures rate, halo_cost and rebuild_cost on
this machine and checks the model against 2-rank runs; the defaults are its
figures (docs/mpi.md). The halo of an interior rank of a cubic grid of ranks
is the shell of width `reach` (search radius plus skin) around its cube of
particles; --halo-share replaces it with a measured share (the run summary's
ranks/halo_share). Weak-scaling efficiency = t_step(1 rank, same particles) / t_step.
"""
import argparse
import math
from types import SimpleNamespace

# The model's parameters and their defaults (help text, value).
PARAMETERS = {
    "rate": ("particle-steps/s of one rank with every core busy (measured)", 8.78e5),
    "halo_cost": ("cost of a halo row in a step relative to an owned one (measured)", 0.354),
    "rebuild_cost": ("cost of a rebuild per row relative to a step of an owned row (measured)", 0.742),
    "rebuild_every": ("steps between rebuilds (measured)", 25.0),
    "imbalance": ("the busiest rank's work over the mean", 1.0),
    "row_bytes": ("bytes of one particle's fields in a refresh", 192.0),
    "refreshes": ("halo refreshes per step (symplectic: 2)", 2.0),
    "reductions": ("all-reduces per step", 5.0),
    "latency": ("s per message (InfiniBand: about 1-2 us)", 1.5e-6),
    "bandwidth": ("B/s per rank (HDR100 InfiniBand: 12.5 GB/s)", 12.5e9),
}


def parameters(**given):
    """The defaults with `given` (same names) replacing them."""
    values = {name: default for name, (_, default) in PARAMETERS.items()}
    unknown = set(given) - set(values)
    if unknown:
        raise ValueError(f"unknown model parameters: {sorted(unknown)}")
    values.update(given)
    return SimpleNamespace(**values)


def shell_halo(owned, dim, reach_dp):
    """Halo rows of an interior rank whose owned particles fill a cube (square in 2D)."""
    side = owned ** (1.0 / dim)
    return (side + 2 * reach_dp) ** dim - side ** dim


def step_time(p, ranks, owned, halo, neighbours):
    """(seconds per step, of which messages) on `ranks` ranks of `owned` rows each."""
    if ranks == 1:
        return owned / p.rate, 0.0
    rows = owned + p.halo_cost * halo + p.rebuild_cost * (owned + halo) / p.rebuild_every
    messages = p.refreshes * (neighbours * p.latency + halo * p.row_bytes / p.bandwidth)
    messages += p.reductions * math.ceil(math.log2(ranks)) * p.latency
    return p.imbalance * rows / p.rate + messages, messages


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ranks", type=int, nargs="+", default=[8, 64, 512])
    ap.add_argument("--particles-per-rank", type=float, default=1e6)
    ap.add_argument("--dim", type=int, default=3)
    ap.add_argument("--reach-dp", type=float, default=4.46,
                    help="halo width in dp: 2h + skin (cubic spline, h = sqrt(3) dp: 3.46 dp + dp)")
    ap.add_argument("--halo-share", type=float, default=None, help="measured halo rows per owned row")
    ap.add_argument("--neighbours", type=int, default=1, help="ranks exchanged with, with --halo-share")
    for name, (text, default) in PARAMETERS.items():
        ap.add_argument("--" + name.replace("_", "-"), type=float, default=default, help=text)
    a = ap.parse_args()
    p = parameters(**{name: getattr(a, name) for name in PARAMETERS})
    owned = a.particles_per_rank
    base, _ = step_time(p, 1, owned, 0.0, 0)
    print(f"one rank: {base:.4g} s per step ({owned:.3g} particles at {p.rate:.3g} particle-steps/s)")
    for n in a.ranks:
        if a.halo_share is not None:
            halo, neighbours = a.halo_share * owned, a.neighbours
        else:
            halo, neighbours = shell_halo(owned, a.dim, a.reach_dp), 3 ** a.dim - 1
        t, messages = step_time(p, n, owned, halo, neighbours)
        print(f"{n:5d} ranks: {t:.4g} s per step, halo {100 * halo / owned:.1f} % of owned, messages {messages:.3g} s, "
              f"weak-scaling efficiency {100 * base / t:.1f} %")


if __name__ == "__main__":
    main()
