"""A prototype of the direct quasi-static solver, outside LAMMPS: what one break costs, and
whether it breaks the bonds LAMMPS breaks.

The scenes' network of central springs is linear between breaks for small strains: after a
strain step (the walls' affine displacement, as ``change_box ... remap`` moves them) the
equilibrium is one linear solve, and a broken spring is a rank-one change of the stiffness
matrix. This script factorises the matrix of the intact network once (SciPy's SuperLU) and
follows the breaks with the Woodbury identity (one solve with that factor per break, a dense
system the size of the breaks since the last factorisation, refactorising every
``--refactor`` breaks), breaking the intact spring with the largest ratio to its threshold
(ties: the lowest IDs) until none exceeds 1, at every strain step: the seed's loop with an
exact linear relaxation. Per-bond stiffness and breaking stretch come from LAMMPS itself
(``compute lattice/bond/local id1 id2 kn fb`` after a ``run 0`` of the scene's deck), so the
heterogeneity is the pair style's. It prints the breaks, the time per break, and, given a
LAMMPS run's ``breaks.txt`` (``--reference``), how many first breaks are the same bonds in
the same order. Broken springs here never push back (the layer-extension scene opens its
cracks; the count of broken springs left in compression is printed).

    python bench/quasistatic_direct_prototype.py --n 60 --steps 4 --reference RUN/breaks.txt

SciPy is not a dependency of the package: ``pip install scipy`` first.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from bonded_lattice import runner
from bonded_lattice.io import read_local_dump
from bonded_lattice.scenes import Scene, build_model, wall_masks, write_scene

SETUP_END = "# ---- quasi-static loading"


def bond_table(scene: Scene, out: Path) -> np.ndarray:
    """(id1, id2, kn, fb) of every bond of the scene, from LAMMPS (a run 0 of its deck)."""
    deck = Path(write_scene(scene, out)["deck"])
    text = deck.read_text()
    head = text[:text.index(SETUP_END)]
    probe = out / "in.bond_table"
    probe.write_text(head + "compute         kb all lattice/bond/local id1 id2 kn fb\n"
                     "dump            kbd all local 1 bond_table.txt c_kb[*]\n"
                     "run             0 post no\n")
    result = runner.run_deck(probe, out, progress=False)
    if result.returncode != 0:
        raise SystemExit(f"LAMMPS failed in {out}: {result.error}")
    return read_local_dump(out / "bond_table.txt")[1]


class Network:
    """The linear spring network with held wall components, its factor and its breaks."""

    def __init__(self, positions: np.ndarray, bonds: np.ndarray, held: np.ndarray,
                 refactor: int) -> None:
        from scipy import sparse

        self.sparse = sparse
        self.p = positions
        self.i = bonds[:, 0].astype(np.int64) - 1
        self.j = bonds[:, 1].astype(np.int64) - 1
        self.kn = bonds[:, 2]
        self.xb = bonds[:, 3] / bonds[:, 2]
        sep = self.p[self.j] - self.p[self.i]
        self.n = sep / np.linalg.norm(sep, axis=1)[:, None]
        self.intact = np.ones(len(bonds), dtype=bool)
        self.free = ~held.reshape(-1)
        self.index = np.full(self.free.size, -1, dtype=np.int64)
        self.index[self.free] = np.arange(self.free.sum())
        self.refactor_every = refactor
        self.solves = 0
        self.factorisations = 0
        self.factorise()

    def dipole(self, b: int) -> np.ndarray:
        """(4,) dof indices and (4,) values of spring b's unit stretch vector g: stretch = g.u."""
        dofs = np.array([2 * self.i[b], 2 * self.i[b] + 1, 2 * self.j[b], 2 * self.j[b] + 1])
        vals = np.array([-self.n[b, 0], -self.n[b, 1], self.n[b, 0], self.n[b, 1]])
        return dofs, vals

    def factorise(self) -> None:
        from scipy.sparse.linalg import splu

        rows, cols, vals = [], [], []
        for b in np.flatnonzero(self.intact):
            dofs, g = self.dipole(b)
            rows.append(np.repeat(dofs, 4))
            cols.append(np.tile(dofs, 4))
            vals.append(self.kn[b] * np.outer(g, g).reshape(-1))
        size = self.free.size
        K = self.sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows),
                                                          np.concatenate(cols))), shape=(size, size))
        self.K_ff = K[self.free][:, self.free].tocsc()
        self.K_fp = K[self.free][:, ~self.free].tocsc()
        self.lu = splu(self.K_ff, permc_spec="COLAMD")
        self.factorisations += 1
        self.broken_since: list[int] = []
        self.W = np.zeros((self.K_ff.shape[0], 0))
        self.S = np.zeros((0, 0))

    def solve(self, u_p: np.ndarray) -> np.ndarray:
        """All displacements (2 per particle) with the held components at u_p."""
        rhs = -(self.K_fp @ u_p)
        u = np.zeros(self.free.size)
        u[~self.free] = u_p
        # springs broken since the factorisation: the factor still holds their stiffness
        # towards held components, which the right-hand side takes back
        for b in self.broken_since:
            dofs, g = self.dipole(b)
            held_part = ~self.free[dofs]
            stretch_p = float(g[held_part] @ u[dofs[held_part]])
            if stretch_p != 0.0:
                f = self.index[dofs[~held_part]]
                np.add.at(rhs, f, self.kn[b] * g[~held_part] * stretch_p)
        u0 = self.lu.solve(rhs)
        self.solves += 1
        if self.broken_since:
            c = np.linalg.solve(self.S, self.W.T @ rhs)
            u0 = u0 + self.W @ c
        u[self.free] = u0
        return u

    def break_spring(self, b: int) -> None:
        self.intact[b] = False
        if len(self.broken_since) >= self.refactor_every:
            self.factorise()
            return
        dofs, g = self.dipole(b)
        mask = self.free[dofs]
        gf = np.zeros(self.K_ff.shape[0])
        gf[self.index[dofs[mask]]] = g[mask]
        w = self.lu.solve(gf)
        self.solves += 1
        # K = K0 - G diag(k) G^T:  K^-1 = K0^-1 + W (diag(1/k) - G^T W)^-1 W^T
        gtw_new = np.array([self._g_dot(c, w) for c in self.broken_since] + [gf @ w])
        m = len(self.broken_since)
        S = np.zeros((m + 1, m + 1))
        S[:m, :m] = self.S
        S[m, :m] = -gtw_new[:m]
        S[:m, m] = -gtw_new[:m]
        S[m, m] = 1.0 / self.kn[b] - gtw_new[m]
        self.S = S
        self.W = np.column_stack([self.W, w])
        self.broken_since.append(b)

    def _g_dot(self, b: int, w: np.ndarray) -> float:
        dofs, g = self.dipole(b)
        mask = self.free[dofs]
        return float(g[mask] @ w[self.index[dofs[mask]]])

    def ratios(self, u: np.ndarray) -> np.ndarray:
        du = u.reshape(-1, 2)[self.j] - u.reshape(-1, 2)[self.i]
        stretch = np.einsum("bk,bk->b", self.n, du)
        return np.where(self.intact, stretch / self.xb, -np.inf), stretch


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=60, help="particles per row (default 60)")
    ap.add_argument("--steps", type=int, default=4, help="strain steps of 2e-5 (default 4)")
    ap.add_argument("--refactor", type=int, default=200,
                    help="breaks between factorisations (default 200)")
    ap.add_argument("--reference", default="", help="a LAMMPS run's breaks.txt to compare")
    ap.add_argument("--out", default="bench-qs-direct")
    args = ap.parse_args()
    try:
        import scipy  # noqa: F401
    except ImportError as err:
        raise SystemExit("this prototype needs SciPy: pip install scipy") from err

    scene = Scene("layer-extension", n_x=args.n, n_steps=args.steps)
    out = Path(args.out) / f"n{args.n}"
    model = build_model(scene)
    lat = model.lattice
    p = lat.positions[:, :2]
    table = bond_table(scene, out)
    walls = wall_masks(lat.positions, scene.d)
    held = np.zeros((len(p), 2), dtype=bool)
    held[walls["left"] | walls["right"], 0] = True
    held[walls["bottom"] | walls["top"], 1] = True
    centre = lat.box[:2].mean(axis=1)
    t0 = time.perf_counter()
    net = Network(p, table, held, args.refactor)
    t_set_up = time.perf_counter() - t0
    a = 1.0 + scene.strain_step
    breaks = []
    t0 = time.perf_counter()
    for k in range(1, args.steps + 1):
        scale = np.array([a ** k, a ** -k])     # change_box x scale a, y scale 1/a, k times
        u_all = (p - centre) * (scale - 1.0)     # the walls' affine displacement
        u_p = u_all.reshape(-1)[~net.free]
        while True:
            u = net.solve(u_p)
            ratio, _ = net.ratios(u)
            top = ratio.max()
            if not top > 1.0:
                break
            candidates = np.flatnonzero(ratio == top)
            b = candidates[np.lexsort((net.j[candidates], net.i[candidates]))[0]]
            breaks.append((k, int(net.i[b]) + 1, int(net.j[b]) + 1, float(top)))
            net.break_spring(b)
    t_run = time.perf_counter() - t0
    _, stretch = net.ratios(u)
    squeezed = int(((~net.intact) & (stretch < 0)).sum())
    print(f"{len(p):,} particles, {len(table):,} bonds, {args.steps} strain steps: "
          f"{len(breaks)} breaks, {net.solves} solves, {net.factorisations} factorisations; "
          f"set-up {t_set_up:.2f} s, loading {t_run:.2f} s, "
          f"{t_run / max(1, len(breaks)):.4f} s per break; broken springs in compression at "
          f"the end: {squeezed}")
    if args.reference:
        ref = [tuple(map(int, line.split()[1:3]))
               for line in Path(args.reference).read_text().splitlines() if line.strip()]
        mine = [(i, j) for _, i, j, _ in breaks]
        same = next((k for k, (x, y) in enumerate(zip(mine, ref)) if x != y),
                    min(len(mine), len(ref)))
        print(f"reference {args.reference}: {len(ref)} breaks; the first {same} are the same "
              f"bonds in the same order; {len(set(mine) & set(ref))} bonds in common")


if __name__ == "__main__":
    main()
