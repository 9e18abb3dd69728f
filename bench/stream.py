"""How close is the force loop to the machine's memory limit?

A streaming kernel (STREAM "triad", a = b + s*c, with numpy) over arrays as large
as the force loop's data for a given particle count measures the memory
bandwidth this machine sustains.  The bytes that lattice/bond's loop must move
per particle-step (its records read and written, the partner indices, the
partners' positions and displacements, the forces) divided into that bandwidth
give the particle-steps per second a purely memory-bound loop would reach; the
measured rate (bench_throughput.py, same size) over that bound is the fraction
of the memory limit the loop uses.

    python bench/stream.py [--particles 200000] [--dim 3] [--rate R]

With --rate (particle-steps/s of lattice/bond at that size) it prints the fraction.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

# bytes per record that the force loop reads every step: the shear spring (3
# doubles in 3D, a signed length in 2D; read and written), the state (1 byte,
# read) and the pair style's partner index (4 bytes); the partner tags are read
# only after reneighbouring
SPRING = {3: 24, 2: 8}
RECORDS_PER_PARTICLE = {3: 6, 2: 3}


def loop_bytes(dim: int) -> int:
    """Bytes the force loop moves per particle-step, counting every array once:
    records read and written, the particle's position and displacement read
    (triples in 2D too), its force read and written (the partners' values are
    the same arrays, reached through the cache)."""
    n = RECORDS_PER_PARTICLE[dim]
    return n * (2 * SPRING[dim] + 1 + 4) + 24 + 24 + 2 * 24


def triad_bandwidth(nbytes: int, repeats: int = 5) -> float:
    """Best bandwidth (bytes/s) of a = b + s*c over three arrays of nbytes/3 each."""
    n = max(1, nbytes // 24)
    b = np.random.default_rng(1).random(n)
    c = np.random.default_rng(2).random(n)
    a = np.empty_like(b)
    best = 0.0
    for _ in range(repeats):
        t0 = time.perf_counter()
        np.multiply(c, 3.0, out=a)
        np.add(a, b, out=a)
        elapsed = time.perf_counter() - t0
        # multiply: read c, write a; add: read a and b, write a
        best = max(best, 5 * 8 * n / elapsed)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--particles", type=int, default=200000)
    parser.add_argument("--dim", type=int, choices=(2, 3), default=3)
    parser.add_argument("--rate", type=float, default=None,
                        help="measured lattice/bond particle-steps/s at this size")
    args = parser.parse_args()
    per_step = loop_bytes(args.dim)
    bandwidth = triad_bandwidth(per_step * args.particles)
    bound = bandwidth / per_step
    print(f"{args.dim}D, {args.particles} particles: the force loop moves {per_step} bytes per "
          f"particle-step; streaming bandwidth {bandwidth / 1e9:.2f} GB/s; a memory-bound loop "
          f"would reach {bound:.3g} particle-steps/s")
    if args.rate:
        print(f"measured {args.rate:.3g} particle-steps/s = {args.rate / bound:.2f} of that bound")


if __name__ == "__main__":
    main()
