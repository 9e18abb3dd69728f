"""Benchmark suite (first part): lattice/bond against LAMMPS' BPM bonds, 1 and 2 ranks.

The canonical problem of bench/bench_throughput.py (uniaxial tension of a bonded 3D
fcc block, quartzite parameters, d = 1 mm, dt = 1e-8 s, viscous damping) at several
sizes, each model on the same lattice in the same process, on 1 and on 2 MPI ranks
(``mpirun -np 2``).  Prints particle-steps per second and the ratios of lattice/bond
to each peer; ratios are what to compare on a shared machine.

    python bench/run.py --quick     # about 11k particles in 3D and 2D, about a minute
    python bench/run.py             # about 11k, 50k and 200k particles

3D: the fcc block; 2D: the hexagonal equivalent (rows along x, loading along y).
Not yet here (issue 5): memory, per-feature costs, speed against error.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
# 3D: fcc cells per side (4 atoms each); 2D: particles along x of a square block
SIZES = {3: {"quick": [14], "full": [14, 23, 37]},
         2: {"quick": [105], "full": [105, 235, 470]}}
MODELS = ["lattice/bond", "bpm/spring", "bpm/rotational"]


def measure(cells: int, steps: int, ranks: int, dim: int) -> list[dict]:
    """One bench_throughput run under mpirun; its JSON lines."""
    from bonded_lattice.runner import lmp_command

    mpirun = lmp_command(2)[0]    # the mpirun of this environment (MPICH wheel)
    cmd = [mpirun, "-np", str(ranks), sys.executable, str(HERE / "bench_throughput.py"),
           "--cells", str(cells), "--steps", str(steps), "--dim", str(dim), "--json",
           "--models", *MODELS]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="one size per dimension (about 11k particles)")
    parser.add_argument("--steps", type=int, default=1000)
    args = parser.parse_args()
    rows = []
    for dim in (3, 2):
        for cells in SIZES[dim]["quick" if args.quick else "full"]:
            for ranks in (1, 2):
                results = {r["model"]: r for r in measure(cells, args.steps, ranks, dim)}
                ref = results["lattice/bond"]["rate"]
                particles = results["lattice/bond"]["particles"]
                rows.append((dim, particles, ranks, ref))
                print(f"{dim}D {particles:8d} particles, {ranks} rank(s): "
                      + ", ".join(f"{m} {results[m]['rate']:.3g}" for m in MODELS)
                      + " particle-steps/s; lattice/bond is "
                      + ", ".join(f"{ref / results[m]['rate']:.2f}x {m}" for m in MODELS[1:]),
                      flush=True)
    # two-rank parallel efficiency of lattice/bond at each size
    for dim, particles, ranks, ref in rows:
        if ranks == 2:
            one = next(r[3] for r in rows if r[:3] == (dim, particles, 1))
            print(f"{dim}D {particles:8d} particles: lattice/bond two-rank efficiency "
                  f"{ref / (2 * one):.2f}")


if __name__ == "__main__":
    main()
