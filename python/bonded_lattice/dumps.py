"""Strains from particle displacements in the decks' LAMMPS text dumps.

The decks write ``dump ... custom N dump.lammpstrj id type x y z c_nbonds``
(and single-frame ``dump.initial`` / ``dump.final``) with ``%.17g`` floats, in
SI units.  A least-squares affine fit of the displacements over the middle of
the block measures the strain like a strain gauge, away from the platens' end
zones.  The loading axis is y in 2D and z in 3D.

The trajectory is read by :func:`bonded_lattice.io.read_frames` (MDAnalysis, float64
columns; see :mod:`bonded_lattice.io.dump`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .io.dump import read_frames

__all__ = ["central_selection", "displacement_gradient", "loading_axis",
           "poisson_ratio_from_dump", "read_frames", "strains_from_dump"]


def displacement_gradient(x0: np.ndarray, x: np.ndarray,
                          select: np.ndarray | None = None) -> np.ndarray:
    """Least-squares ``G`` (3x3) of ``u = u0 + G x0`` with ``u = x - x0``, over ``select``.

    ``G[i, j] = du_i/dx_j``.  When all selected ``x0`` share one z (2D), only
    the in-plane 2x2 block is fitted and the z row and column are zero.
    """
    x0 = np.asarray(x0, dtype=float)
    x = np.asarray(x, dtype=float)
    if x0.shape != x.shape or x0.ndim != 2 or x0.shape[1] != 3:
        raise ValueError(f"x0 {x0.shape} and x {x.shape} must both be (n, 3)")
    if select is not None:
        x0, x = x0[select], x[select]
    axes = [0, 1] if np.ptp(x0[:, 2]) == 0 else [0, 1, 2]
    # centred coordinates keep the fit well conditioned far from the origin
    a = np.column_stack([np.ones(len(x0)), x0[:, axes] - x0[:, axes].mean(axis=0)])
    if np.linalg.matrix_rank(a) < len(axes) + 1:
        raise ValueError(f"{len(x0)} selected particles do not span {len(axes)} dimensions")
    coef = np.linalg.lstsq(a, (x - x0)[:, axes], rcond=None)[0]
    g = np.zeros((3, 3))
    g[np.ix_(axes, axes)] = coef[1:].T
    return g


def loading_axis(dim: int) -> int:
    """Index of the loading axis: y (1) in 2D, z (2) in 3D."""
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim} is not 2 or 3")
    return 1 if dim == 2 else 2


def central_selection(x0: np.ndarray, axis: int, height_fraction: float = 0.5) -> np.ndarray:
    """Mask of particles whose ``x0[:, axis]`` lies in the middle ``height_fraction`` of the block."""
    if not 0 < height_fraction <= 1:
        raise ValueError(f"height_fraction = {height_fraction} is out of range: need 0 < f <= 1")
    h = np.asarray(x0, dtype=float)[:, axis]
    lo, hi = h.min(), h.max()
    return np.abs(h - 0.5 * (lo + hi)) <= 0.5 * height_fraction * (hi - lo)


def strains_from_dump(path: str | Path, dim: int,
                      height_fraction: float = 0.5) -> dict[str, np.ndarray]:
    """Per-frame strains relative to the first frame, fitted over the central selection.

    Returns arrays ``step``, ``axial`` (G along the loading axis), ``lateral``
    (2D: G_xx; 3D: mean of G_xx and G_yy), ``lateral_x`` and ``lateral_y``
    (3D only, NaN in 2D).  Compression is negative.
    """
    axis = loading_axis(dim)
    steps, x = read_frames(path)
    if (np.ptp(x[0][:, 2]) == 0) != (dim == 2):
        raise ValueError(f"{path}: dim = {dim} does not match the dump "
                         f"({'all' if dim == 3 else 'not all'} particles share one z)")
    sel = central_selection(x[0], axis, height_fraction)
    g = np.array([displacement_gradient(x[0], xk, sel) for xk in x])
    axial = g[:, axis, axis]
    if dim == 2:
        nan = np.full(len(steps), np.nan)
        return {"step": steps, "axial": axial, "lateral": g[:, 0, 0],
                "lateral_x": nan, "lateral_y": nan.copy()}
    gx, gy = g[:, 0, 0], g[:, 1, 1]
    return {"step": steps, "axial": axial, "lateral": 0.5 * (gx + gy),
            "lateral_x": gx, "lateral_y": gy}


def poisson_ratio_from_dump(path: str | Path, dim: int, height_fraction: float = 0.5) -> float:
    """Poisson's ratio: minus the least-squares slope of lateral vs axial strain.

    The line (with intercept, so a start-up offset does not bias it) is fitted
    through all frames after the first, which is the reference.
    """
    s = strains_from_dump(path, dim, height_fraction)
    axial, lateral = s["axial"][1:], s["lateral"][1:]
    if len(axial) < 2 or np.ptp(axial) == 0:
        raise ValueError(f"{path}: need at least two loaded frames with different axial strains")
    return float(-np.polyfit(axial, lateral, 1)[0])
