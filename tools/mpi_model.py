#!/usr/bin/env python3
"""Time per step of a run on several MPI ranks, from the measured compute rate,
the halo volume and the messages a step sends (docs/mpi.md).

  t_step = (owned + halo_cost * halo) / rate                      compute
         + refreshes * (neighbours * latency + halo * row_bytes / bandwidth)
         + reductions * log2(ranks) * latency                     time step, density check

halo_cost is what a halo row costs relative to an owned one. The pair loops
run their outer loop over owned rows only and skip the pairs of two halo
rows, but halo rows are still binned, integrated and refreshed, and the
walls' own passes still visit them: the default is the value measured on a
3D dam break on 2 ranks (docs/mpi.md, "Cost model").
The halo of an interior rank of a cubic grid of ranks is the shell of width
`reach` (search radius plus skin) around its cube of particles; --halo-share
replaces it with a measured share (the run summary's ranks/halo_share).
Weak-scaling efficiency = t_step(1 rank, same particles, no halo, no messages) / t_step.
"""
import argparse
import math


def step_time(a, ranks):
    owned = a.particles_per_rank
    if ranks == 1:
        return owned / a.rate, 0.0, 0.0
    if a.halo_share is not None:
        halo = a.halo_share * owned
    else:
        side = owned ** (1.0 / a.dim)  # particles along an edge of the rank's cube
        halo = (side + 2 * a.reach_dp) ** a.dim - side ** a.dim
    neighbours = 3 ** a.dim - 1 if a.halo_share is None else a.neighbours
    compute = (owned + a.halo_cost * halo) / a.rate
    messages = a.refreshes * (neighbours * a.latency + halo * a.row_bytes / a.bandwidth)
    messages += a.reductions * math.ceil(math.log2(ranks)) * a.latency
    return compute + messages, halo / owned, messages


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ranks", type=int, nargs="+", default=[8, 64, 512])
    ap.add_argument("--particles-per-rank", type=float, default=1e6)
    ap.add_argument("--rate", type=float, default=3.04e5, help="particle-steps/s of one rank (measured)")
    ap.add_argument("--dim", type=int, default=3)
    ap.add_argument("--reach-dp", type=float, default=4.0, help="halo width in dp: 2h + skin = 3 dp + dp")
    ap.add_argument("--halo-share", type=float, default=None, help="measured halo rows per owned row")
    ap.add_argument("--neighbours", type=int, default=1, help="ranks exchanged with, with --halo-share")
    ap.add_argument("--halo-cost", type=float, default=0.2, help="cost of a halo row relative to an owned one")
    ap.add_argument("--row-bytes", type=float, default=192, help="bytes of one particle's fields")
    ap.add_argument("--refreshes", type=float, default=2, help="halo refreshes per step (symplectic: 2)")
    ap.add_argument("--reductions", type=float, default=5, help="all-reduces per step")
    ap.add_argument("--latency", type=float, default=1.5e-6, help="s per message (InfiniBand: about 1-2 us)")
    ap.add_argument("--bandwidth", type=float, default=12.5e9, help="B/s per rank (HDR100 InfiniBand: 12.5 GB/s)")
    a = ap.parse_args()
    base, _, _ = step_time(a, 1)
    print(f"one rank: {base:.4g} s per step ({a.particles_per_rank:.3g} particles at {a.rate:.3g} particle-steps/s)")
    for n in a.ranks:
        t, share, messages = step_time(a, n)
        print(f"{n:5d} ranks: {t:.4g} s per step, halo {100 * share:.1f} % of owned, messages {messages:.3g} s, "
              f"weak-scaling efficiency {100 * base / t:.1f} %")


if __name__ == "__main__":
    main()
