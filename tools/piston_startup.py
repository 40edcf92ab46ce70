#!/usr/bin/python3
"""Linear theory of a piston wavemaker started from rest in a closed tank: what a wave gauge
records, and its first-harmonic H/S over a window, against Biesel's steady H/S.

A measured H/S is compared with Biesel's steady value only where the window sees the steady
wave: after the start-up front and before the end wall's reflection. This tool checks that
for a given tank, gauge and window, with the whole linear solution (no steady-state or
semi-infinite assumption).

The piston x(t) = (S/2) sin(2 pi t / T) for t > 0 moves the whole depth h at x = 0 of a tank
[0, L] with a wall at L. The potential is a particular part that carries the paddle's flux,
-U(t) ((x - L)^2 - (z + h)^2) / 2L, plus the tank's standing modes cos(k_n x) cosh k_n(z + h),
k_n = n pi / L, omega_n^2 = g k_n tanh k_n h. Each mode is a forced oscillator, started at rest,
solved in closed form; the free surface is the mean rise S/2 sin(omega t) h / L plus
-(1/g) sum_n de_n/dt cos(k_n x). The modes are summed to wavelengths of 1 mm.

Examples:
  tools/piston_startup.py --depth 0.2 --period 1 --stroke 0.02 --tank 4 --gauge 0.6 --window 3 5
  tools/piston_startup.py --depth 0.11 --period 2 --stroke 0.02 --tank 5 --gauge 0.6 --window 4.6 8.6 --within 0.01

With --within TOL it exits 1 when the window's H/S is not within TOL (relative) of Biesel's.
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verification.cases.wavemaker_piston_2d import G, first_harmonic, piston_ratio, wavenumber  # noqa: E402


def elevation(x, times, stroke, period, depth, tank, shortest=1e-3):
    """Free-surface elevation (m) at x over `times` (s) for the piston started at t = 0."""
    a, w = 0.5 * stroke, 2.0 * math.pi / period
    n = np.arange(1, int(2.0 * tank / shortest) + 1)
    k = n * math.pi / tank
    wn = np.sqrt(G * k * np.tanh(k * depth))
    # de_n/dt of e_n'' + wn^2 e_n = -wn^2 (2 / L k_n^2) U(t), U = a w cos(w t), e_n(0) = e_n'(0) = 0
    gain = -(2.0 * wn**2 * a * w / (tank * k**2)) / (wn**2 - w**2)
    shape = np.cos(k * x)
    out = np.empty(len(times))
    for start in range(0, len(times), 256):  # bounded memory: modes x 256 times at a time
        t = np.asarray(times[start:start + 256])[:, None]
        e_dot = gain * (-w * np.sin(w * t) + wn * np.sin(wn * t))
        out[start:start + 256] = a * np.sin(w * t[:, 0]) * depth / tank - (e_dot * shape).sum(axis=1) / G
    return out


def window_ratio(stroke, period, depth, tank, gauge, window, dt=0.005):
    """H/S = 2 x the first-harmonic amplitude at the gauge over the window, divided by the stroke."""
    times = np.arange(0.0, window[1] + 0.5 * dt, dt)
    eta = elevation(gauge, times, stroke, period, depth, tank)
    return 2.0 * first_harmonic(times, eta, 2.0 * math.pi / period, window) / stroke


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--depth", type=float, required=True, help="still-water depth h (m)")
    p.add_argument("--period", type=float, required=True, help="paddle period T (s)")
    p.add_argument("--stroke", type=float, required=True, help="stroke S, peak to peak (m)")
    p.add_argument("--tank", type=float, required=True, help="paddle to end wall L (m)")
    p.add_argument("--gauge", type=float, required=True, help="gauge distance from the paddle's mean position (m)")
    p.add_argument("--window", type=float, nargs=2, required=True, metavar=("FROM", "TO"), help="s")
    p.add_argument("--within", type=float, help="exit 1 unless |H/S / Biesel - 1| <= this")
    args = p.parse_args(argv)
    if not (args.depth > 0 and args.period > 0 and args.stroke > 0 and args.tank > args.gauge >= 0
            and 0 <= args.window[0] < args.window[1]):
        p.error("need depth, period, stroke > 0, 0 <= gauge < tank and 0 <= FROM < TO")
    kh = wavenumber(args.period, args.depth) * args.depth
    steady = piston_ratio(kh)
    ratio = window_ratio(args.stroke, args.period, args.depth, args.tank, args.gauge, tuple(args.window))
    off = ratio / steady - 1.0
    print(f"kh = {kh:.4f}, Biesel H/S = {steady:.4f}; linear start-up at x = {args.gauge} m over "
          f"{args.window[0]}-{args.window[1]} s: H/S = {ratio:.4f} ({100 * off:+.2f} % from Biesel)", flush=True)
    if args.within is not None and abs(off) > args.within:
        print(f"not within {100 * args.within:g} % of Biesel: the window is not clean", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
