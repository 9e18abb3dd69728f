"""What is left between a user's deck and the tuned one, one set-up choice at a time.

The user-written deck of bench_throughput.py (atom_style sphere, create_atoms with the
lattice's conventional cells, LAMMPS' default neighbour settings, platens by fix move,
fix nve and fix viscous) after the lines the pair style's warnings name ("advised": the
skin, fix lattice/nve, fix lattice/viscous), then the advised deck with one more change
towards the tuned deck at a time (bench_throughput.DECK_STEPS):

- rows: the particles numbered row by row (create_atoms with a one-atom cell);
- atomic: atom_style atomic with a mass per type (no per-atom radius, mass, torque);
- setforce: the platens given a velocity and held by fix setforce, fix lattice/nve on all;
- bins: bins of one neighbour cutoff for the lists and the sorting;
- rows+bins: both of the last two.

All models run in one process per repeat (bench/run.py's measure), on 1 and 2 ranks; the
printed numbers are medians over the repeats of the rate of each model divided by the
tuned deck's rate in the same process.  ``targets`` instead measures issue 21's target:
the deck as written and the advised deck against the tuned deck and against bpm/spring
(and the tuned deck against bpm/spring), with each run's advised/tuned ratio.

    python bench/deck_steps.py steps [--repeat 3] [--steps 1000] [--cells3 23] [--cells2 235]
    python bench/deck_steps.py targets [--repeat 5] [--steps 2000] [--interleave 200]

With ``--interleave CHUNK`` the four models of ``targets`` are set up side by side in one
process and run in turns of CHUNK steps (the order rotating from turn to turn); each turn's
ratios count as one run, so a burst of load from the rest of the machine, which lasts longer
than one turn, shifts both sides of a ratio instead of one.
"""

from __future__ import annotations

import argparse
import statistics

from bench_throughput import DECK_STEPS
from run import measure

TUNED = "lattice/bond"
WRITTEN = "lattice/bond:user-deck"
ADVISED = "lattice/bond:user-deck-advised"
BPM = "bpm/spring"
# the last: the package's own two set-up choices (numbering, bins) both as in the tuned
# deck, so that what is left is the user's choice of LAMMPS styles (sphere, fix move)
MODELS = ([TUNED, WRITTEN, ADVISED] + [f"{ADVISED}+{step}" for step in DECK_STEPS]
          + [f"{ADVISED}+rows+bins"])
TARGET_MODELS = [TUNED, ADVISED, BPM, WRITTEN]


def collect(cells: int, ranks: int, dim: int, models: list[str],
            args: argparse.Namespace) -> list[dict[str, dict]]:
    """The runs of the models, {model: JSON line} each: one per repeat, or with
    --interleave one per turn of every repeat."""
    if not args.interleave:
        return [{r["model"]: r for r in measure(cells, args.steps, ranks, dim, models)}
                for _ in range(args.repeat)]
    particles = measure(cells, 1, 1, dim, [TUNED])[0]["particles"]
    runs = []
    for _ in range(args.repeat):
        lines = measure(cells, args.steps, ranks, dim, models, args.interleave)
        for k in sorted({line["round"] for line in lines}):
            runs.append({line["model"]: dict(line, particles=particles)
                         for line in lines if line["round"] == k})
    return runs


def targets(args: argparse.Namespace) -> None:
    """The written and the advised deck against the tuned deck and bpm/spring."""
    print("| dim | particles | ranks | as written / tuned | as written / bpm/spring "
          "| advised / tuned | advised / bpm/spring | tuned / bpm/spring | advised / tuned, each run |")
    print("|---|---|---|---|---|---|---|---|---|")
    for dim, cells in ((d, args.cells3 if d == 3 else args.cells2) for d in args.dims):
        for ranks in args.ranks:
            runs = collect(cells, ranks, dim, TARGET_MODELS, args)
            particles = runs[0][TUNED]["particles"]

            def ratio(a: str, b: str) -> float:
                return statistics.median(run[a]["rate"] / run[b]["rate"] for run in runs)

            each = [run[ADVISED]["rate"] / run[TUNED]["rate"] for run in runs]
            if args.interleave:     # many turns: their spread, not each one
                q = statistics.quantiles(each, n=4)
                each = (f"{len(each)} turns: quartiles {q[0]:.2f}, {q[2]:.2f}; "
                        f"range {min(each):.2f}-{max(each):.2f}")
            else:
                each = ", ".join(f"{r:.2f}" for r in each)
            print(f"| {dim}D | {particles} | {ranks} | "
                  f"{ratio(WRITTEN, TUNED):.2f} | {ratio(WRITTEN, BPM):.2f} | "
                  f"{ratio(ADVISED, TUNED):.2f} | {ratio(ADVISED, BPM):.2f} | "
                  f"{ratio(TUNED, BPM):.2f} | {each} |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("table", choices=("steps", "targets"))
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--cells3", type=int, default=23, help="3D: fcc cells per side")
    parser.add_argument("--cells2", type=int, default=235, help="2D: particles along x")
    parser.add_argument("--interleave", type=int, metavar="CHUNK", default=0,
                        help="set the models up side by side and run them in turns "
                             "of CHUNK steps (--steps in all per model); each turn's ratio "
                             "counts as one run")
    parser.add_argument("--dims", type=int, nargs="+", choices=(2, 3), default=[3, 2])
    parser.add_argument("--ranks", type=int, nargs="+", choices=(1, 2), default=[1, 2])
    args = parser.parse_args()
    if args.table == "targets":
        targets(args)
        return
    print("| dim | particles | ranks | " + " | ".join(m.split(":")[-1] for m in MODELS[1:]) + " |")
    print("|---|---|---|" + "---|" * (len(MODELS) - 1))
    for dim, cells in ((d, args.cells3 if d == 3 else args.cells2) for d in args.dims):
        for ranks in args.ranks:
            runs = collect(cells, ranks, dim, MODELS, args)
            particles = runs[0][TUNED]["particles"]
            ratios = [statistics.median(run[m]["rate"] / run[TUNED]["rate"] for run in runs)
                      for m in MODELS[1:]]
            print(f"| {dim}D | {particles} | {ranks} | " + " | ".join(f"{r:.2f}" for r in ratios)
                  + " |", flush=True)


if __name__ == "__main__":
    main()
