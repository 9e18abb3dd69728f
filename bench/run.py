"""Benchmark suite: lattice/bond against LAMMPS' BPM bonds, 1 and 2 ranks, memory, features.

The tuned deck (as bonded-lattice writes it) and a deck written as a user would
(bench_throughput.USER_DECK: atom_style sphere, fix nve, LAMMPS' default neighbour
settings, platens by fix move) run side by side, and the user's deck once more with the
lines the pair style's warnings name (the skin, fix lattice/nve, fix lattice/viscous).

The canonical problem of bench/bench_throughput.py (uniaxial tension of a bonded 3D
fcc block, quartzite parameters, d = 1 mm, dt = 1e-8 s, viscous damping; in 2D the
hexagonal equivalent) at several sizes, each model on the same lattice in the same
process, on 1 and on 2 MPI ranks (``mpirun -np 2``).  Prints particle-steps per
second, the ratios of lattice/bond to each peer, the two-rank efficiency, the peak
resident memory per particle of each model (one process per model, one rank), and
with ``--features`` the cost of each feature of the force loop (friction, shear
springs, several parameter sets, the energy budget).  Ratios are what to compare on
a shared machine; the closing Markdown table (with date, commit and machine) is
what docs/performance.md records.

    python bench/run.py --quick     # about 11k particles in 3D and 2D, a few minutes
    python bench/run.py             # about 11k, 50k and 200k particles
    python bench/run.py --quick --features
    python bench/run.py --repeat 3   # medians of three runs (a shared, noisy machine)
"""

from __future__ import annotations

import argparse
import datetime
import json
import statistics
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
# 3D: fcc cells per side (4 atoms each); 2D: particles along x of a square block;
# with the time steps per size (fewer for the large blocks: the BPM peers are slow)
SIZES = {3: {"quick": [(14, 1000)], "full": [(14, 1000), (23, 400), (37, 100)]},
         2: {"quick": [(105, 1000)], "full": [(105, 1000), (235, 400), (470, 100)]}}
MODELS = ["lattice/bond", "bpm/spring", "bpm/rotational", "lattice/bond:user-deck",
          "lattice/bond:user-deck-advised"]
# the deck as a user writes it (bench_throughput.USER_DECK), and the same deck with the
# lines the pair style's warnings name: measured next to the tuned one
USERS = {"written": "lattice/bond:user-deck", "advised": "lattice/bond:user-deck-advised"}
# lattice/bond variants whose memory differs: the particles numbered by create_atoms'
# conventional cells instead of row by row (one more record slot per particle), and
# atom_style sphere (per-atom radius, mass, angular velocity, torque)
MEMORY_VARIANTS = ["lattice/bond:cell-numbering", "lattice/bond:sphere"]


def measure(cells: int, steps: int, ranks: int, dim: int, models: list[str],
            interleave: int = 0) -> list[dict]:
    """One bench_throughput run under mpirun; its JSON lines (with ``interleave``, the
    models run in turns of that many steps: one line per model and turn)."""
    from bonded_lattice.runner import lmp_command

    mpirun = lmp_command(2)[0]    # the mpirun of this environment (MPICH wheel)
    cmd = [mpirun, "-np", str(ranks), sys.executable, str(HERE / "bench_throughput.py"),
           "--cells", str(cells), "--steps", str(steps), "--dim", str(dim), "--json",
           "--models", *models]
    if interleave:
        cmd += ["--interleave", str(interleave)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="one size per dimension (about 11k particles)")
    parser.add_argument("--steps-scale", type=float, default=1.0,
                        help="multiply every size's time steps by this")
    parser.add_argument("--features", action="store_true",
                        help="also the cost of each force-loop feature (1 rank, smallest size)")
    parser.add_argument("--no-memory", action="store_true", help="skip the memory pass")
    parser.add_argument("--repeat", type=int, default=1,
                        help="run every size and rank count this many times; report medians")
    args = parser.parse_args()
    from bench_throughput import FEATURE_MODELS

    from bonded_lattice.provenance import git_commit, machine

    rows = []
    for dim in (3, 2):
        for cells, steps in SIZES[dim]["quick" if args.quick else "full"]:
            steps = max(10, int(steps * args.steps_scale))
            for ranks in (1, 2):
                # repeated runs: the median of each rate, and of each ratio taken
                # within one run (the models of one run share the machine's load)
                runs = [{r["model"]: r for r in measure(cells, steps, ranks, dim, MODELS)}
                        for _ in range(args.repeat)]
                rates = {m: statistics.median(run[m]["rate"] for run in runs) for m in MODELS}
                ratios = {m: statistics.median(run["lattice/bond"]["rate"] / run[m]["rate"]
                                               for run in runs) for m in MODELS}
                # the user-written deck (as written, and advised) against the tuned one
                # and against bpm/spring
                user = {(deck, peer): statistics.median(run[model]["rate"] / run[peer]["rate"]
                                                        for run in runs)
                        for deck, model in USERS.items() for peer in ("lattice/bond", "bpm/spring")}
                particles = runs[0]["lattice/bond"]["particles"]
                rows.append(dict(dim=dim, particles=particles, ranks=ranks, cells=cells,
                                 rates=rates, ratios=ratios, user=user))
                print(f"{dim}D {particles:8d} particles, {ranks} rank(s): "
                      + ", ".join(f"{m} {rates[m]:.3g}" for m in MODELS)
                      + " particle-steps/s; lattice/bond is "
                      + ", ".join(f"{ratios[m]:.2f}x {m}" for m in MODELS[1:3])
                      + "".join(f"; the user-written deck {deck} is "
                                f"{user[deck, 'lattice/bond']:.2f}x the tuned deck, "
                                f"{user[deck, 'bpm/spring']:.2f}x bpm/spring" for deck in USERS)
                      + (f" (median of {args.repeat})" if args.repeat > 1 else ""),
                      flush=True)

    # peak resident memory: one process per model (the peak never goes down), 1 rank
    memory = {}
    if not args.no_memory:
        for dim in (3, 2):
            cells, _ = SIZES[dim]["quick" if args.quick else "full"][-1]
            for model in MODELS + MEMORY_VARIANTS:
                r = measure(cells, 10, 1, dim, [model])[0]
                memory[(dim, model)] = (r["particles"], r["peak_bytes_per_particle"])
                print(f"{dim}D {r['particles']:8d} particles: {model} peak memory "
                      f"{r['peak_bytes_per_particle']:.0f} bytes/particle", flush=True)

    features = {}
    if args.features:
        for dim in (3, 2):
            cells, steps = SIZES[dim]["quick"][0]
            results = {r["model"]: r["rate"] for r in measure(cells, steps, 1, dim,
                                                               FEATURE_MODELS)}
            features[dim] = results
            for m in FEATURE_MODELS:
                print(f"{dim}D features, 1 rank: {m} {results[m]:.3g} particle-steps/s, "
                      f"time per step {results['lattice/bond'] / results[m]:.2f}x lattice/bond",
                      flush=True)

    # the record for docs/performance.md
    print(f"\n{datetime.date.today()}, commit {git_commit(HERE, mark_changes=True)}, "
          f"{machine()}, "
          f"`python bench/run.py{' --quick' if args.quick else ''}"
          f"{' --features' if args.features else ''}"
          f"{f' --repeat {args.repeat}' if args.repeat > 1 else ''}`\n")
    print("| dim | particles | ranks | lattice/bond (particle-steps/s) | vs bpm/spring "
          "| vs bpm/rotational | two-rank efficiency | user-written deck vs tuned "
          "| user-written deck vs bpm/spring | advised user deck vs tuned "
          "| advised user deck vs bpm/spring |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        rates = row["rates"]
        ref = rates["lattice/bond"]
        eff = ""
        if row["ranks"] == 2:
            one = next(r for r in rows if r["dim"] == row["dim"] and r["cells"] == row["cells"]
                       and r["ranks"] == 1)
            eff = f"{ref / (2 * one['rates']['lattice/bond']):.2f}"
        print(f"| {row['dim']}D | {row['particles']} | {row['ranks']} | {ref:.3g} | "
              f"{row['ratios']['bpm/spring']:.2f} | {row['ratios']['bpm/rotational']:.1f} | {eff} | "
              + " | ".join(f"{row['user'][deck, peer]:.2f}" for deck in USERS
                           for peer in ("lattice/bond", "bpm/spring")) + " |")
    if memory:
        print("\n| dim | particles | model | peak memory (bytes/particle, 1 rank) |")
        print("|---|---|---|---|")
        for (dim, model), (particles, peak) in memory.items():
            print(f"| {dim}D | {particles} | {model} | {peak:.0f} |")
    if features:
        print("\n| dim | variant | particle-steps/s | time per step vs lattice/bond |")
        print("|---|---|---|---|")
        for dim, results in features.items():
            for m in FEATURE_MODELS:
                print(f"| {dim}D | {m} | {results[m]:.3g} | "
                      f"{results['lattice/bond'] / results[m]:.2f} |")
    # 2D against 3D throughput per particle (target: at least 2)
    one_rank = {r["dim"]: r for r in reversed(rows) if r["ranks"] == 1}
    if 2 in one_rank and 3 in one_rank:
        print(f"\n2D / 3D lattice/bond throughput per particle (1 rank, smallest size): "
              f"{one_rank[2]['rates']['lattice/bond'] / one_rank[3]['rates']['lattice/bond']:.2f}")


if __name__ == "__main__":
    sys.path.insert(0, str(HERE))
    main()
