"""Voronoi grains: each particle in the cell of its nearest seeded random point."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from .checks import check_box, check_n_grains, check_points, check_seed

# distances in one chunk of the nearest-seed search (~32 MB of float64)
CHUNK_ELEMENTS = 4_000_000


def voronoi_seeds(box_lo: Sequence[float], box_hi: Sequence[float], n_grains: int,
                  seed: int) -> np.ndarray:
    """The (n_grains, dim) seed points of :func:`voronoi_grains`, uniform in the box.

    Drawn with ``numpy.random.default_rng(seed)``: the same seed gives the same
    points on any machine and with any numpy that keeps PCG64 (numpy >= 1.17).
    """
    check_seed(seed)
    check_n_grains(n_grains)
    lo, hi, _ = check_box(box_lo, box_hi, [False] * len(np.atleast_1d(box_lo)))
    return np.random.default_rng(seed).uniform(lo, hi, size=(n_grains, len(lo)))


def nearest_seed(positions: np.ndarray, seeds: np.ndarray, box_lo: Sequence[float],
                 box_hi: Sequence[float], periodic: Sequence[bool] = (False, False)) -> np.ndarray:
    """Index of the nearest seed point of every particle (its Voronoi cell).

    Along periodic axes the particles are wrapped into the box and the seeds'
    images one box length either way count too.  Exact, with a tile search:
    the particles are binned into tiles of about one seed each; for a tile whose
    particles lie within ``h`` of its centre ``c``, and whose nearest seed (or
    image) to ``c`` is at ``r``, every particle's nearest seed lies within
    ``r + 2h`` of ``c`` (triangle inequality), so only those seeds are
    compared, by explicit differences.  Cost ~ n_particles x (seeds near a
    tile) + n_tiles x n_seeds x 3^(periodic axes): 1e6 particles and 1e3 seeds
    in a few seconds; beyond ~1e4 seeds the second term dominates.
    """
    lo, hi, per = check_box(box_lo, box_hi, periodic)
    dim = len(lo)
    p = check_points(positions, dim).copy()
    s = np.asarray(seeds, dtype=float).reshape(-1, dim)
    if len(s) == 0:
        raise ValueError("no seed points: need at least one")
    length = hi - lo
    p[:, per] = lo[per] + np.mod(p[:, per] - lo[per], length[per])
    # the seeds and their images along the periodic axes
    shifts = np.array(np.meshgrid(*[(-1, 0, 1) if f else (0,) for f in per],
                                  indexing="ij")).reshape(dim, -1).T
    candidates = (s[None, :, :] + shifts[:, None, :] * length).reshape(-1, dim)
    owner = np.tile(np.arange(len(s)), len(shifts))
    # tiles of about one seed each (particles outside the box go to the edge tiles)
    side = (float(np.prod(length)) / len(s)) ** (1.0 / dim)
    n_tiles = np.maximum(1, np.ceil(length / side)).astype(np.int64)
    cell = np.clip(np.floor((p - lo) / length * n_tiles), 0, n_tiles - 1).astype(np.int64)
    key = np.ravel_multi_index(tuple(cell.T), tuple(n_tiles)) if len(p) else cell[:, 0]
    order = np.argsort(key, kind="stable")
    starts = np.flatnonzero(np.diff(key[order], prepend=-1))
    ends = np.append(starts[1:], len(order))
    slack = 1e-9 * float(length.max())            # rounding of the distances below
    index = np.empty(len(p), dtype=np.int64)
    for a, b in zip(starts.tolist(), ends.tolist()):
        members = order[a:b]
        q = p[members]
        q_lo, q_hi = q.min(axis=0), q.max(axis=0)
        centre, h = 0.5 * (q_lo + q_hi), 0.5 * float(np.linalg.norm(q_hi - q_lo))
        dc = np.sqrt(((candidates - centre) ** 2).sum(axis=1))
        near = np.flatnonzero(dc <= dc.min() + 2.0 * h + slack)
        c = candidates[near]
        step = max(1, CHUNK_ELEMENTS // len(near))
        for k in range(0, len(q), step):
            d2 = ((q[k:k + step, None, :] - c[None, :, :]) ** 2).sum(axis=2)
            index[members[k:k + step]] = owner[near[np.argmin(d2, axis=1)]]
    return index


def voronoi_grains(positions: np.ndarray, box_lo: Sequence[float], box_hi: Sequence[float],
                   n_grains: int, seed: int,
                   periodic: Sequence[bool] = (False, False)) -> np.ndarray:
    """Grain id (0..n_grains-1) of every particle: the Voronoi cell of seeded random points.

    The seed points are :func:`voronoi_seeds` (uniform in the box); each particle
    gets the grain of its nearest seed point, counting the points' periodic
    images along periodic axes.  box_lo, box_hi and periodic have one entry per
    axis used (2 for the 2D models: x and y; positions may carry a z column).
    Grains that catch no particle stay empty (likely only when n_grains nears
    the number of particles).
    """
    seeds = voronoi_seeds(box_lo, box_hi, n_grains, seed)
    return nearest_seed(positions, seeds, box_lo, box_hi, periodic)
