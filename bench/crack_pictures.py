"""Scene pictures of many broken bonds: vector segments against the raster, time and size.

Builds the seed's high resolution lattice (default 800 x 922, 737,600 particles, 2.2
million bonds) in Python only, breaks a synthetic set of its bonds (random straight
cracks, each with up to two branches, one in three a bundle of three parallel strands
3 d apart, plus isolated breaks: 80 % / 20 % of the count)
and draws each set with ``plotting.scene_bonds_png`` both ways (``method="segments"``:
one line per broken bond; ``method="raster"``: crack_raster at the figure's resolution).
Prints a table: broken bonds, method, wall and CPU seconds of the call (the machine is
shared: CPU seconds are the steadier number), PNG size.

    python bench/crack_pictures.py --out bench-crack-pictures      # ~2 minutes

The pictures stay in --out (crack_<count>_<method>.png) for a look at their legibility.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from bonded_lattice.lattice import contact_pairs
from bonded_lattice.plotting import scene_bonds_png
from bonded_lattice.scenes import box_lattice


BUNDLE = 3.0   # spacing of the parallel strands of a crack bundle, diameters


def crossing(p: np.ndarray, q: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Which of the segments p[k]-q[k] cross the segment a-b (proper crossings)."""
    def side(u, v, w):
        return np.sign((v[..., 0] - u[..., 0]) * (w[..., 1] - u[..., 1])
                       - (v[..., 1] - u[..., 1]) * (w[..., 0] - u[..., 0]))
    return (side(a, b, p) * side(a, b, q) < 0) & (side(p, q, a) * side(p, q, b) < 0)


def crack_bonds(p: np.ndarray, bonds: np.ndarray, mid: np.ndarray, a: np.ndarray,
                b: np.ndarray, d: float) -> np.ndarray:
    """Indices of the bonds that the straight crack a-b cuts."""
    lo, hi = np.minimum(a, b) - d, np.maximum(a, b) + d
    near = np.nonzero(np.all((mid >= lo) & (mid <= hi), axis=1))[0]
    cut = crossing(p[bonds[near, 0]], p[bonds[near, 1]], a, b)
    return near[cut]


def synthetic_breaks(p: np.ndarray, bonds: np.ndarray, d: float, count: int,
                     rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """``count`` distinct broken bonds: 80 % along random straight cracks (each with up to
    two branches, one in three a bundle of three parallel strands :data:`BUNDLE` d apart,
    like the en-echelon cracks of the dynamic runs), the rest isolated; returns their indices and a "step" for each (its crack's number; isolated
    breaks get random steps)."""
    mid = 0.5 * (p[bonds[:, 0]] + p[bonds[:, 1]])
    lo, hi = p.min(axis=0), p.max(axis=0)
    width = float((hi - lo).max())
    chosen: dict[int, int] = {}
    target = int(0.8 * count)
    crack = 0
    while len(chosen) < target:
        a = lo + rng.random(2) * (hi - lo)
        angle = rng.uniform(0, math.pi)
        length = rng.uniform(0.05, 0.5) * width
        segs = [(a, a + length * np.array([math.cos(angle), math.sin(angle)]))]
        for _ in range(rng.integers(0, 3)):
            start = segs[0][0] + rng.random() * (segs[0][1] - segs[0][0])
            turn = angle + rng.choice([-1, 1]) * rng.uniform(math.radians(25), math.radians(60))
            segs.append((start, start + rng.uniform(0.3, 0.7) * length
                         * np.array([math.cos(turn), math.sin(turn)])))
        if rng.random() < 1.0 / 3.0:
            # a bundle: two more strands beside the main crack, BUNDLE d to either side
            off = BUNDLE * d * np.array([-math.sin(angle), math.cos(angle)])
            segs += [(segs[0][0] + off, segs[0][1] + off), (segs[0][0] - off, segs[0][1] - off)]
        for s, e in segs:
            for k in crack_bonds(p, bonds, mid, s, e, d).tolist():
                if len(chosen) < target:
                    chosen.setdefault(k, crack)
        crack += 1
    rest = np.setdiff1d(np.arange(len(bonds)), np.fromiter(chosen, dtype=np.int64))
    for k in rng.choice(rest, count - len(chosen), replace=False).tolist():
        chosen[k] = int(rng.integers(0, crack))
    idx = np.fromiter(chosen, dtype=np.int64)
    return idx, np.array([chosen[k] for k in idx.tolist()])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--nx", type=int, default=800)
    ap.add_argument("--ny", type=int, default=922)
    ap.add_argument("--counts", type=int, nargs="+", default=[1000, 10000, 20000, 50000, 200000])
    ap.add_argument("--methods", nargs="+", default=["segments", "raster"])
    ap.add_argument("--steps", action="store_true",
                    help="colour by the synthetic step (each crack one step) instead of by mode")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="bench-crack-pictures")
    args = ap.parse_args()

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    d = 1e-3
    lattice = box_lattice(args.nx, args.ny, d)
    p = lattice.positions[:, :2]
    bonds = contact_pairs(lattice)
    # every interior particle has six bonds: the lattice is what the deck bonds
    assert len(bonds) == 3 * args.nx * args.ny - 2 * args.nx - 2 * args.ny + 1, len(bonds)
    grain = (np.abs(p[:, 1] - 0.5 * (p[:, 1].min() + p[:, 1].max()))
             < 0.1 * np.ptp(p[:, 1])).astype(np.int64)     # a layer of 20 % of the height
    rng = np.random.default_rng(args.seed)
    # warm-up: matplotlib's imports and font cache, not part of a picture's cost
    small = box_lattice(10, 10, d)
    small_bonds = contact_pairs(small)
    for method in args.methods:
        scene_bonds_png(out / "warm-up.png", small.positions, np.zeros(100, dtype=np.int64),
                        np.column_stack([small_bonds + 1, np.ones(len(small_bonds))]), d,
                        method=method)
    print(f"{len(p)} particles, {len(bonds)} bonds")
    print("| broken bonds | method | wall time (s) | CPU time (s) | PNG size (kB) |")
    print("|---|---|---|---|---|")
    for count in args.counts:
        idx, steps = synthetic_breaks(p, bonds, d, count, rng)
        records = np.zeros((len(bonds), 3))
        records[:, :2] = bonds + 1
        records[idx, 2] = 1
        broken_at = ({(int(bonds[k, 0]) + 1, int(bonds[k, 1]) + 1): int(s)
                      for k, s in zip(idx.tolist(), steps.tolist())} if args.steps else None)
        for method in args.methods:
            png = out / f"crack_{count}_{method}{'_steps' if args.steps else ''}.png"
            wall, cpu = time.perf_counter(), time.process_time()
            n = scene_bonds_png(png, lattice.positions, grain, records, d, broken_at=broken_at,
                                title=f"{count} synthetic breaks, {method}", method=method)
            wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
            assert n == count
            print(f"| {count} | {method} | {wall:.2f} | {cpu:.2f} | "
                  f"{png.stat().st_size / 1e3:.0f} |", flush=True)


if __name__ == "__main__":
    main()
