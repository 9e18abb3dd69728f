"""What one break costs in the quasi-static loop, against the size of the box.

Runs the layer-extension scene (the seed's first scene) at several sizes, quasi-statically,
for the first strain steps that break bonds, with FIRE over the whole box (``--relax
fire``), ``lattice/quasistatic relax local`` and ``relax direct``, each at its default
tolerance, in one run, and prints per run: particles, breaks, relaxations, minimiser
iterations, sweeps or solves, particle updates (relax local: its moves; FIRE: iterations x
particles; relax direct: solves x particles), those per break, the wall time, the wall time
per break and the speed-up over FIRE; then the growth of the cost per break with the box
(the exponent of particles between successive sizes) and whether the relaxations broke the
same bonds in the same order as FIRE and as relax direct (their breaks.txt).

    python bench/quasistatic_scaling.py                       # n 60, 120; ~5 minutes on 1 core
    python bench/quasistatic_scaling.py --n 60 100 --steps 30 # the whole default loading
    python bench/quasistatic_scaling.py --n 60 120 240 --fire-up-to 120 --relax local direct

The runs go into --out (default bench-qs-scaling/); --reuse keeps finished runs.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from bonded_lattice.scene_analysis import break_sequence, relaxation_costs
from bonded_lattice.scene_study import SceneStudy
from bonded_lattice.scenes import Scene

def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, nargs="+", default=[60, 120],
                    help="particles per row (square boxes; default 60 120)")
    ap.add_argument("--steps", type=int, default=3,
                    help="strain steps of 2e-5 (default 3: the layer's first avalanche)")
    ap.add_argument("--fire-up-to", type=int, default=120,
                    help="also run FIRE for n up to this (default 120)")
    ap.add_argument("--relax", nargs="+", choices=("fire", "local", "direct"),
                    default=["fire", "local", "direct"], help="the relaxations (default all)")
    ap.add_argument("--out", default="bench-qs-scaling")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()

    rows = []
    for n in args.n:
        for relax in args.relax:
            if relax == "fire" and n > args.fire_up_to:
                continue
            scene = Scene("layer-extension", n_x=n, n_steps=args.steps, relax=relax)
            out = Path(args.out) / f"n{n}_{relax}"
            summary = SceneStudy(scene, out, np_=args.np, pictures=False).run(reuse=args.reuse)
            c = relaxation_costs(out / "log.lammps", scene.n)
            rows.append({"n": n, "particles": scene.n, "relax": relax, **c,
                         "wall": summary["wall_time_s"], "order": [tuple(b) for b in break_sequence(out, source="log").tolist()]})

    print(f"layer-extension, {args.steps} strain steps of 2e-5, {args.np} rank(s)\n")
    print("| particles | relax | breaks | relaxations | iterations, sweeps or solves | particle "
          "updates | updates per break | wall time (s) | wall time per break (s) | "
          "faster than FIRE |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        per = r["updates"] / max(1, r["breaks"])
        fire = next((f["wall"] for f in rows if f["n"] == r["n"] and f["relax"] == "fire"), None)
        speed = f"{fire / r['wall']:.1f}x" if fire else "-"
        print(f"| {r['particles']:,} | {r['relax']} | {r['breaks']} | {r['relaxations']} | "
              f"{r['iterations']:,} | {r['updates']:.3g} | {per:.3g} | {r['wall']:.1f} | "
              f"{r['wall'] / max(1, r['breaks']):.3g} | {speed} |")
    print()
    for relax in args.relax:
        mine = [r for r in rows if r["relax"] == relax and r["breaks"]]
        for a, b in zip(mine, mine[1:]):
            pa, pb = (r["updates"] / r["breaks"] for r in (a, b))
            k = math.log(pb / pa) / math.log(b["particles"] / a["particles"])
            print(f"{relax}: updates per break grow as particles^{k:.2f} from {a['particles']:,} "
                  f"to {b['particles']:,}")
    for n in args.n:
        order = {r["relax"]: r["order"] for r in rows if r["n"] == n}
        for ref, other in (("fire", "local"), ("fire", "direct"), ("direct", "local")):
            if ref not in order or other not in order:
                continue
            a, b = order[ref], order[other]
            same = next((k for k, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
            print(f"n {n}: {ref} broke {len(a)}, {other} {len(b)}; the first {same} breaks "
                  "are the same bonds in the same order")


if __name__ == "__main__":
    main()
