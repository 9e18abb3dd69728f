"""What the package's own sparse Cholesky (``LatticeSparseCholesky``) costs on the scenes' lattice.

Compiles ``bench/sparse_cholesky_bench.cpp`` with ``src/BONDED_LATTICE/lattice_sparse_cholesky.cpp``
(g++, the plugin's release flags: ``-O3 -DNDEBUG -fno-math-errno -ffp-contract=off``, no
``-march``) and runs it per size: the scenes' triangular lattice (``scenes.box_lattice``'s
geometry, ``n_x`` particles in each of ``n_y`` rows), 2 free dof per node, the bottom and top rows
held, one central spring per nearest-neighbour pair with ``k`` Gaussian (mean 1, sd 0.15, redrawn
until positive), ``shift`` 1e-10 times the mean ``k``. Per size: the analyse (ordering and
symbolic) time, the factorisation, one solve, the mean rank-one downdate and update over
``--mods`` random springs, the stored entries of L, the factor's bytes, the factorisation's
peak scratch, the separator tree's nodes and depth, the factorisation's rate (its leading flop
terms over its time) and the solve's relative residual ``||K x - b|| / ||b||``: of the first
factor, of the factor after the ``--mods`` downdates and of a fresh factorisation of that
reduced spring set (b random on every free dof).

``--threads 1 2``: per size also a second table, the factorisation and the best of 5 solves of
the same factor on each thread count (``LatticeSparseCholesky::set_threads``; wall time, and the
process's CPU time over all its threads), the speed-up of the wall time over
the first count, the plans' task counts, whether the factor and the solution are bit-identical to
the first count's (a hash of their bits), and the cores the machine offered just before (count x
the time of a fixed loop on one thread over its time on each of count threads at once: the count
on an idle machine; less when other jobs run).

    python bench/sparse_cholesky.py        # 60x70 100x116 400x462 800x922: 4200 ... 737,600 nodes
    python bench/sparse_cholesky.py --sizes 400x462 800x922 --threads 1 2
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SOURCES = [ROOT / "bench" / "sparse_cholesky_bench.cpp",
           ROOT / "src" / "BONDED_LATTICE" / "lattice_sparse_cholesky.cpp"]
FLAGS = ["-std=c++17", "-O3", "-DNDEBUG", "-fno-math-errno", "-ffp-contract=off", "-pthread"]


def parse_size(text: str) -> tuple[int, int]:
    """"NXxNY" (particles per row x rows) as two ints, each at least 3."""
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.isdigit() for p in parts) or min(map(int, parts)) < 3:
        raise ValueError(f"size {text!r} is out of range: need NXxNY with NX, NY >= 3")
    return int(parts[0]), int(parts[1])


def compile_driver(build: Path) -> Path:
    """The bench driver, compiled into the folder build."""
    gxx = shutil.which("g++")
    if gxx is None:
        raise SystemExit("this benchmark needs g++ (C++17) on PATH")
    exe = build / "sparse_cholesky_bench"
    subprocess.run([gxx, *FLAGS, f"-I{ROOT / 'src' / 'BONDED_LATTICE'}", *map(str, SOURCES),
                    "-o", str(exe)], check=True)
    return exe


def run_size(exe: Path, n_x: int, n_y: int, leaf: int, mods: int, threads: list[int]) -> dict:
    """The driver's "name value" lines for one lattice, as a dict (threads: the counts timed)."""
    cmd = [str(exe), str(n_x), str(n_y), str(leaf), str(mods)]
    if threads:
        cmd.append(",".join(map(str, threads)))
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    values = {}
    for line in out.splitlines():
        name, value = line.split()
        values[name] = float(value)
    return values


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", nargs="+", default=["60x70", "100x116", "400x462", "800x922"],
                    help="NXxNY lattices (the scenes' square boxes; 400x462: 184,800 nodes)")
    ap.add_argument("--leaf", type=int, default=0,
                    help="largest leaf of the dissection in nodes (0: the class's default)")
    ap.add_argument("--mods", type=int, default=50,
                    help="random springs whose downdate and update are timed (default 50)")
    ap.add_argument("--threads", type=int, nargs="+", default=[],
                    help="thread counts whose factorisation and solve are timed (e.g. 1 2)")
    args = ap.parse_args()
    if any(t < 1 for t in args.threads):
        raise SystemExit(f"--threads {args.threads} is out of range (each >= 1)")
    if args.leaf < 0:
        raise SystemExit(f"--leaf {args.leaf} is out of range (>= 0)")
    if args.mods < 1:
        raise SystemExit(f"--mods {args.mods} is out of range (>= 1)")
    try:
        sizes = [parse_size(t) for t in args.sizes]
    except ValueError as err:
        raise SystemExit(str(err)) from err

    with tempfile.TemporaryDirectory() as build:
        exe = compile_driver(Path(build))
        print("| nodes | free dof | analyse (s) | factorise (s) | one solve (s) | downdate (ms) | "
              "update (ms) | entries of L | factor (MB) | factorise scratch (MB) | tree nodes | "
              "depth | factorise GFlop/s | residual | after the downdates | fresh factor |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        results = []
        for n_x, n_y in sizes:
            v = run_size(exe, n_x, n_y, args.leaf, args.mods, args.threads)
            results.append(v)
            print(f"| {int(v['nodes']):,} | {int(v['free_dof']):,} | {v['analyse_s']:.3f} | "
                  f"{v['factorise_s']:.3f} | {v['solve_s']:.4f} | {1e3 * v['downdate_s']:.2f} | "
                  f"{1e3 * v['update_s']:.2f} | {v['factor_entries']:.3g} | "
                  f"{v['factor_bytes'] / 1e6:.0f} | {v['work_bytes'] / 1e6:.0f} | "
                  f"{int(v['tree_nodes']):,} | {int(v['depth'])} | {v['factorise_gflops']:.2f} | "
                  f"{v['residual']:.1e} | {v['residual_after_downdates']:.1e} | "
                  f"{v['residual_fresh_factor']:.1e} |",
                  flush=True)
        if args.threads:
            print_threads(results, args.threads)


def print_threads(results: list[dict], threads: list[int]) -> None:
    """The thread counts' table: times, speed-ups over the first count, tasks, identity."""
    first = threads[0]
    print()
    print("| nodes | threads | factorise (s) | CPU (s) | speed-up | one solve, best of 5 (s) | "
          "CPU (s) | speed-up | solve tasks | factorise tasks | bit-identical | free cores |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for v in results:
        for t in threads:
            tf, ts = v[f"factorise_s_t{t}"], v[f"solve_best5_s_t{t}"]
            print(f"| {int(v['nodes']):,} | {t} | {tf:.3f} | {v[f'factorise_cpu_s_t{t}']:.3f} | "
                  f"{v[f'factorise_s_t{first}'] / tf:.2f} | {ts:.4f} | "
                  f"{v[f'solve_cpu_best5_s_t{t}']:.4f} | {v[f'solve_best5_s_t{first}'] / ts:.2f} | "
                  f"{int(v[f'solve_tasks_t{t}'])} | {int(v[f'factorise_tasks_t{t}'])} | "
                  f"{'yes' if v[f'identical_t{t}'] == 1.0 else 'NO'} | {v[f'free_cores_t{t}']:.2f} |",
                  flush=True)


if __name__ == "__main__":
    main()
