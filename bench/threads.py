"""Threads against ranks: pair_style lattice/bond/omp and fix lattice/nve/omp (``-sf omp``)
against the serial styles on MPI ranks, on the canonical problem of bench_throughput.py
(uniaxial tension of a bonded 3D fcc block or 2D hexagonal block, quartzite, d = 1 mm).

Each configuration runs the same deck with the LAMMPS executable of the test suite
(``BONDED_LATTICE_LMP`` and ``BONDED_LATTICE_MPIRUN``, bonded_lattice.runner): it needs a
LAMMPS with the package compiled in and the OPENMP package (tools/build-lammps-builtin.sh).
The configurations, in one run so that their ratios share the machine's load:

    serial 1 rank        pair lattice/bond, fix lattice/nve        (the reference)
    omp 1 rank x 1       -sf omp -pk omp 1: the /omp styles' overhead on one thread
    omp 1 rank x 2       -sf omp -pk omp 2: two threads
    serial 2 ranks       mpirun -np 2: two ranks, the serial styles
    omp 2 ranks x 2      four threads of work on a 2-core machine (oversubscribed)

Prints particle-steps per second (median of --repeat runs) and each configuration's
ratio to the serial 1-rank run of the same repetition, then a Markdown table with date,
commit and machine for docs/performance.md.

    BONDED_LATTICE_LMP=<lmp> BONDED_LATTICE_MPIRUN='mpirun --oversubscribe' \\
        python bench/threads.py [--repeat 3] [--quick]
"""

from __future__ import annotations

import argparse
import datetime
import re
import statistics
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

# 3D: fcc cells per side; 2D: particles along x (bench_throughput's sizes), with steps
SIZES = {"quick": [(3, 14, 1000), (2, 105, 1000)],
         "full": [(3, 14, 1000), (3, 23, 400), (2, 105, 1000), (2, 235, 400)]}
CONFIGS = [("serial 1 rank", 1, 0), ("omp 1 rank x 1 thread", 1, 1),
           ("omp 1 rank x 2 threads", 1, 2), ("serial 2 ranks", 2, 0),
           ("omp 2 ranks x 2 threads", 2, 2)]


def rate(dim: int, cells: int, steps: int, ranks: int, threads: int, work: Path) -> tuple[int, float]:
    """Particles and particle-steps per second of the timed run (after a 100-step warm-up)."""
    from bench_throughput import build_input

    from bonded_lattice.runner import run_deck

    deck = work / "in.threads"
    deck.write_text(build_input("lattice/bond", cells, dim) + f"run 100\nrun {steps}\n")
    args = ["-pk", "omp", str(threads), "-sf", "omp"] if threads else []
    res = run_deck(deck, work, np_=ranks, progress=False, extra_args=args)
    if res.returncode != 0:
        raise RuntimeError(f"{ranks} ranks x {threads} threads failed: {res.error}")
    if threads and "lattice/bond/omp" not in res.output:
        raise RuntimeError("-sf omp did not pick pair_style lattice/bond/omp: this LAMMPS lacks "
                           "the package's /omp styles (tools/build-lammps-builtin.sh)")
    loops = re.findall(r"^Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms",
                       res.output, re.M)
    seconds, nsteps, natoms = loops[-1]
    return int(natoms), int(natoms) * int(nsteps) / float(seconds)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the smallest 3D and 2D sizes only")
    parser.add_argument("--repeat", type=int, default=3, help="repetitions; medians are reported")
    args = parser.parse_args()
    from bonded_lattice.provenance import git_commit, machine

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for dim, cells, steps in SIZES["quick" if args.quick else "full"]:
            runs = []
            for _ in range(args.repeat):
                run = {}
                for name, ranks, threads in CONFIGS:
                    natoms, r = rate(dim, cells, steps, ranks, threads, Path(tmp))
                    run[name] = r
                runs.append(run)
            for name, ranks, threads in CONFIGS:
                med = statistics.median(run[name] for run in runs)
                ratio = statistics.median(run[name] / run["serial 1 rank"] for run in runs)
                rows.append((dim, natoms, name, med, ratio))
                print(f"{dim}D {natoms:7d} particles  {name:26s} {med:12.4g} particle-steps/s"
                      f"  x{ratio:.2f} of serial 1 rank", flush=True)
    print()
    print(f"{datetime.date.today()}, commit {git_commit(HERE.parent)}, {machine()}, "
          f"median of {args.repeat}")
    print()
    print("| dim | particles | configuration | particle-steps/s | vs serial 1 rank |")
    print("| --- | --- | --- | --- | --- |")
    for dim, natoms, name, med, ratio in rows:
        print(f"| {dim}D | {natoms} | {name} | {med:.3g} | {ratio:.2f} |")


if __name__ == "__main__":
    main()
