"""Periodic cells of the bonded lattice and the stresses of their bond sums.

A periodic cell is the standard way to measure a lattice's elastic constants and
strength without platens, free surfaces or boundary layers: every particle sees
the same neighbourhood, so under a homogeneous deformation of the box (LAMMPS'
``change_box ... remap``, ``fix deform ... remap x`` or a barostat) the particles
stay on the affinely deformed lattice and the stress is the bond sum below.

Geometry
--------
The lattice is the close-packed Bravais lattice of diameter-``d`` particles:
triangular in 2D (primitive vectors a1 = d (1, 0), a2 = d (1/2, sqrt3/2)) and
face-centred cubic in 3D (a1, a2 in the close-packed xy layer, a3 = d (1/2,
sqrt3/6, sqrt(2/3)) to the next layer: ABC stacking).  A cell is given by an
integer matrix ``cell`` whose rows are its edge vectors in lattice coordinates;
its volume holds ``|det cell|`` particles.  The cell is turned so that its first
edge lies along x and its second in the xy plane (LAMMPS' restricted triclinic
box), so a cell whose first edge is not along a1 holds the lattice at another
orientation.  Bond directions: see :func:`bond_vectors`.

Bond-sum stress
---------------
Under the displacement gradient H (x -> (I + H) x), the bond of separation r =
x_i - x_j gains the relative displacement u = H r; its normal spring carries Kn
n.u along n and its shear spring Ks (u - (n.u) n) across it (the papers' fixed
frame; ``shear_frame corotational`` removes the rotation (H - H^T)/2 first).  To
first order in H the pressure tensor LAMMPS reports (compute pressure, virial
part) is

    P_ab = (1 / v) sum over the bonds of one particle (each once) r_a f_b,
    f = -Kn (n.u) n - Ks (u - (n.u) n),

with v the volume per particle (an area in 2D) and f the force on i.  The
elastic stiffness follows from it (:func:`stiffness_matrix`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .lattice import Lattice, _sorted

__all__ = [
    "PeriodicCell",
    "bond_pressure",
    "paper_cell",
    "periodic_cell",
    "stiffness_matrix",
]

SQRT3 = math.sqrt(3.0)

# primitive vectors in units of d (rows); 2D carries a third vector for the
# one-diameter-thick periodic z extent of LAMMPS' 2D box
_PRIMITIVE = {
    2: np.array([[1.0, 0.0, 0.0], [0.5, 0.5 * SQRT3, 0.0], [0.0, 0.0, 1.0]]),
    3: np.array([[1.0, 0.0, 0.0], [0.5, 0.5 * SQRT3, 0.0],
                 [0.5, SQRT3 / 6.0, math.sqrt(2.0 / 3.0)]]),
}
# nearest neighbours in lattice coordinates, one of each +- pair (the bonds of
# one particle, each counted once): 3 in 2D, 6 in 3D
_NEIGHBOURS = {
    2: np.array([[1, 0, 0], [0, 1, 0], [-1, 1, 0]]),
    3: np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 1, 0], [-1, 0, 1], [0, -1, 1]]),
}


def paper_cell(dim: int, n: int) -> np.ndarray:
    """The papers' orientation in an orthogonal cell of about n particles across.

    2D: close-packed rows along x, loading axis y (2013 paper): edges n a1 and
    m (2 a2 - a1) = m d (0, sqrt3), m = round(n / sqrt3).  3D: close-packed
    layers in xy, loading axis z (2017 paper; fcc rather than its hcp stacking:
    the bonds' angles to z are the same): edges n a1, m (2 a2 - a1) and
    k (3 a3 - a1 - a2) = k d (0, 0, sqrt6), k = round(n / sqrt6).
    """
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim} is out of range: use 2 or 3")
    if n < 2:
        raise ValueError(f"n = {n} is out of range: need n >= 2 particles across")
    m = max(1, round(n / SQRT3))
    if dim == 2:
        return np.array([[n, 0], [-m, 2 * m]])
    k = max(1, round(n / math.sqrt(6.0)))
    return np.array([[n, 0, 0], [-m, 2 * m, 0], [-k, -k, 3 * k]])


def _full_cell(cell: np.ndarray, dim: int) -> np.ndarray:
    cell = np.asarray(cell)
    if cell.shape != (dim, dim) or not np.issubdtype(cell.dtype, np.integer):
        raise ValueError(f"cell must be a {dim} x {dim} integer matrix (edges in lattice "
                         f"coordinates), got {cell.tolist()!r}")
    full = np.eye(3, dtype=np.int64)
    full[:dim, :dim] = cell
    if round(np.linalg.det(full)) == 0:
        raise ValueError(f"cell {cell.tolist()!r} is singular: its edges must span the "
                         f"{'plane' if dim == 2 else 'space'}")
    return full


def _reduce(full: np.ndarray, primitive: np.ndarray) -> np.ndarray:
    """The same cell with edges b, c shifted by whole edges so that the tilts are at
    most half a period (LAMMPS' preferred triclinic box); the same particles."""
    full = full.copy()
    for _ in range(3):
        h = _lammps_box(full @ primitive)
        xprd, yprd, xy, xz, yz = h[0, 0], h[1, 1], h[0, 1], h[0, 2], h[1, 2]
        full[1] -= round(xy / xprd) * full[0]
        full[2] -= round(yz / yprd) * full[1]
        h = _lammps_box(full @ primitive)
        full[2] -= round(h[0, 2] / xprd) * full[0]
    return full


def _lammps_box(edges: np.ndarray) -> np.ndarray:
    """Upper-triangular box matrix (columns = edges a, b, c turned so that a lies along
    x and b in the xy plane) of the edges given as rows."""
    a, b, c = edges
    if np.dot(np.cross(a, b), c) < 0:
        raise ValueError("the cell's edges are left-handed: swap two of them")
    xprd = np.linalg.norm(a)
    ahat = a / xprd
    xy = float(np.dot(b, ahat))
    yprd = float(np.linalg.norm(np.cross(ahat, b)))
    xz = float(np.dot(c, ahat))
    yz = float((np.dot(b, c) - xy * xz) / yprd)
    zprd = math.sqrt(max(float(np.dot(c, c)) - xz * xz - yz * yz, 0.0))
    return np.array([[xprd, xy, xz], [0.0, yprd, yz], [0.0, 0.0, zprd]])


@dataclass
class PeriodicCell:
    """One periodic cell: its particles and the bonds of one particle.

    lattice: the particles in LAMMPS' frame, ``box`` from the origin to the cell's
        lengths (2D: z from -d/2 to d/2), ``tilt`` (xy, xz, yz) unless the cell is
        orthogonal, positions sorted row by row (neighbours have nearby IDs).  Write
        it with :func:`bonded_lattice.lattice.write_data`, read it with ``boundary p
        p p``.
    bonds: the bonds of one particle, each once (3 rows in 2D, 6 in 3D): the
        separations r = x_i - x_j in the cell's frame.
    """

    lattice: Lattice
    bonds: np.ndarray

    @property
    def volume_per_particle(self) -> float:
        """Volume of one particle's share of the lattice (an area in 2D)."""
        d = self.lattice.d
        return 0.5 * SQRT3 * d * d if self.lattice.dim == 2 else d ** 3 / math.sqrt(2.0)


def periodic_cell(dim: int, d: float, cell: np.ndarray) -> PeriodicCell:
    """The particles of one periodic cell (see the module's text), in LAMMPS' frame."""
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim} is out of range: use 2 or 3")
    d = float(d)
    if not (d > 0 and math.isfinite(d)):
        raise ValueError(f"d = {d} is out of range: need 0 < d < inf")
    primitive = _PRIMITIVE[dim]
    full = _reduce(_full_cell(cell, dim), primitive)
    if np.linalg.det(full) < 0:
        full[1] = -full[1]
    count = int(round(abs(np.linalg.det(full))))
    edges = full @ primitive
    h = _lammps_box(edges)
    # lattice points n (integer rows) with fractional cell coordinates s = n full^-1 in [0, 1)
    corners = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)]) @ full
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    grid = np.stack(np.meshgrid(*[np.arange(lo[k], hi[k] + 1) for k in range(3)],
                                indexing="ij"), axis=-1).reshape(-1, 3)
    if dim == 2:
        grid = grid[grid[:, 2] == 0]
    frac = grid @ np.linalg.inv(full)
    eps = 1e-9
    frac = frac[np.all((frac > -eps) & (frac < 1.0 - eps), axis=1)]
    if len(frac) != count:
        raise RuntimeError(f"internal error: {len(frac)} sites for a cell of {count}")
    # off the faces of the box, where rounding puts a particle on either side (and
    # LAMMPS' read_restart of a triclinic box then misses it): a shift of a
    # quarter of the mean site spacing along each edge
    shift = 0.25 / count ** (1.0 / dim)
    frac[:, :dim] = (frac[:, :dim] + shift) % 1.0
    positions = d * frac @ h.T
    if dim == 2:
        positions[:, 2] = 0.0
    positions = _sorted(positions, d, dim)
    box = np.array([[0.0, d * h[0, 0]], [0.0, d * h[1, 1]], [0.0, d * h[2, 2]]])
    if dim == 2:
        box[2] = (-0.5 * d, 0.5 * d)
    # tilts of rounding size (an orthogonal cell's edges are orthogonal to 1e-16) are 0
    tilt = tuple(0.0 if abs(t) < 1e-12 else d * t for t in (h[0, 1], h[0, 2], h[1, 2]))
    lattice = Lattice(positions, d, dim, box, tilt=None if not any(tilt) else tilt)
    # rows r (lattice frame) -> r @ rotation (the cell's frame)
    rotation = np.linalg.solve(edges, h.T)
    bonds = d * (_NEIGHBOURS[dim] @ primitive) @ rotation
    return PeriodicCell(lattice, bonds)


def bond_pressure(cell: PeriodicCell, H: np.ndarray, Kn: float, Ks: float,
                  corotational: bool = False) -> np.ndarray:
    """The pressure tensor P_ab = (1/v) sum r_a f_b (first order in H) of a periodic
    cell under the displacement gradient H (3 x 3), in LAMMPS' sign (tension
    negative); with ``corotational`` the shear springs see the symmetric part of H
    only.  Kn, Ks as in ``pair_coeff`` (2D: per unit thickness)."""
    H = np.asarray(H, dtype=float).reshape(3, 3)
    if not np.all(np.isfinite(H)):
        raise ValueError(f"H = {H.tolist()} is not finite")
    kn, ks = float(Kn), float(Ks)
    if not (kn > 0 and ks >= 0 and math.isfinite(kn) and math.isfinite(ks)):
        raise ValueError(f"Kn = {Kn}, Ks = {Ks} are out of range: need Kn > 0, Ks >= 0")
    Hs = 0.5 * (H + H.T) if corotational else H
    P = np.zeros((3, 3))
    for r in cell.bonds:
        n = r / np.linalg.norm(r)
        un = float(n @ (H @ r))
        us = Hs @ r
        f = -kn * un * n - ks * (us - float(n @ us) * n)
        P += np.outer(r, f)
    return P / cell.volume_per_particle


def stiffness_matrix(cell: PeriodicCell, Kn: float, Ks: float) -> np.ndarray:
    """The Voigt stiffness matrix (xx, yy, zz, yz, xz, xy; 3 x 3 of xx, yy, xy in 2D)
    of the bond sums for symmetric strains: sigma = C eps, eps with engineering shears."""
    voigt = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
    if cell.lattice.dim == 2:
        voigt = [(0, 0), (1, 1), (0, 1)]
    C = np.zeros((len(voigt), len(voigt)))
    for col, (a, b) in enumerate(voigt):
        eps = np.zeros((3, 3))
        eps[a, b] = eps[b, a] = 1.0 if a == b else 0.5
        sigma = -bond_pressure(cell, eps, Kn, Ks)
        C[:, col] = [sigma[i, j] for i, j in voigt]
    return C

