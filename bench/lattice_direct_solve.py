"""What a sparse direct solve of the scenes' spring lattice costs, against its size.

The quasi-static loop needs the equilibrium of a linear network of central springs after
every break (with small strains the lattice is linear between breaks). A relaxation
(FIRE, ``relax local``) pays for it with work that grows with the box
(``bench/quasistatic_scaling.py``); a direct method factorises the stiffness matrix once and,
after a break (a rank-one change of the matrix), needs about two solves with that factor
(Sherman-Morrison / Woodbury), refactorising now and then. This script measures those costs
with SciPy's SuperLU (``scipy.sparse.linalg.splu``, COLAMD ordering) on the scenes' lattice
(``scenes.box_lattice``: n_x particles per row, a square box), central springs with per-particle
stiffness factors from a Gaussian (mean 1, sd 0.15, a bond the mean of its two), the wall
rows held: per size, the factorisation's time and fill (nonzeros of L + U), and the time of
one solve. SciPy is not a dependency of the package: ``pip install scipy`` first.

    python bench/lattice_direct_solve.py                  # n 60 120 240 400; ~2 minutes, ~2 GB
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from bonded_lattice.lattice import pairs_within
from bonded_lattice.scenes import box_lattice


def stiffness(n_x: int, seed: int = 1) -> tuple["object", np.ndarray]:
    """The stiffness matrix (2 dof per particle, Kn = 1 times the bonds' factors) of the
    square scene lattice, and the mask of the free dof (wall rows held)."""
    from scipy import sparse

    n_y = int(round(n_x * 2.0 / np.sqrt(3.0) / 2.0)) * 2
    lat = box_lattice(n_x, n_y, 1.0)
    p = lat.positions[:, :2]
    i, j, r = pairs_within(lat.positions, 1.01)
    factor = np.random.default_rng(seed).normal(1.0, 0.15, len(p))
    k = 0.5 * (factor[i] + factor[j])
    n = (p[j] - p[i]) / r[:, None]
    rows, cols, vals = [], [], []
    for a in range(2):
        for b in range(2):
            kab = k * n[:, a] * n[:, b]
            for (u, v, sign) in ((i, i, 1), (j, j, 1), (i, j, -1), (j, i, -1)):
                rows.append(2 * u + a)
                cols.append(2 * v + b)
                vals.append(sign * kab)
    size = 2 * len(p)
    K = sparse.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(size, size))
    lo, hi = p.min(axis=0), p.max(axis=0)
    wall = (np.isclose(p[:, 0], lo[0]) | np.isclose(p[:, 0], hi[0]) |
            np.isclose(p[:, 1], lo[1]) | np.isclose(p[:, 1], hi[1]))
    return K, np.repeat(~wall, 2)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, nargs="+", default=[60, 120, 240, 400],
                    help="particles per row, square boxes (400: the seed's 184,800)")
    ap.add_argument("--solves", type=int, default=5, help="solves timed per size (default 5)")
    args = ap.parse_args()
    try:
        from scipy.sparse.linalg import splu
    except ImportError as err:
        raise SystemExit("this benchmark needs SciPy: pip install scipy") from err

    print("| particles | free dof | factorisation (s) | nonzeros of L + U | one solve (s) | "
          "two solves per break (s) |")
    print("|---|---|---|---|---|---|")
    for n_x in args.n:
        K, free = stiffness(n_x)
        Kff = K[free][:, free].tocsc()
        t0 = time.perf_counter()
        lu = splu(Kff, permc_spec="COLAMD")
        t_factor = time.perf_counter() - t0
        rhs = np.random.default_rng(2).normal(size=Kff.shape[0])
        t0 = time.perf_counter()
        for _ in range(args.solves):
            x = lu.solve(rhs)
        t_solve = (time.perf_counter() - t0) / args.solves
        residual = np.linalg.norm(Kff @ x - rhs) / np.linalg.norm(rhs)
        assert residual < 1e-8, f"the solve is inaccurate: relative residual {residual:.2e}"
        print(f"| {K.shape[0] // 2:,} | {Kff.shape[0]:,} | {t_factor:.2f} | "
              f"{lu.L.nnz + lu.U.nnz:.3g} | {t_solve:.3f} | {2 * t_solve:.3f} |", flush=True)


if __name__ == "__main__":
    main()
