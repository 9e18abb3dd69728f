"""Checks of the grains' parameters: each raises ``ValueError`` naming the value and its
valid range (seeds, grain counts and ids, stiffness and strength factors, boxes, positions,
axes)."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

MAX_SEED = 2**63 - 1          # LAMMPS reads the pair_style seed as a bigint
MAX_GRAIN = 2**31 - 1         # i_ properties of fix property/atom are 32-bit ints
AXES = {"x": 0, "y": 1, "z": 2}


def check_seed(seed: int, name: str = "seed") -> int:
    """A seed: an integer 1 <= seed <= 2^63 - 1 (LAMMPS reads it as a bigint)."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"{name} = {seed!r} is out of range: need an integer "
                         f"1 <= {name} <= {MAX_SEED}")
    if not 1 <= int(seed) <= MAX_SEED:
        raise ValueError(f"{name} = {seed} is out of range: need 1 <= {name} <= {MAX_SEED}")
    return int(seed)


def check_n_grains(n_grains: int) -> int:
    """A number of grains: an integer >= 1."""
    if isinstance(n_grains, bool) or not isinstance(n_grains, (int, np.integer)) \
            or n_grains < 1:
        raise ValueError(f"n_grains = {n_grains!r} is out of range: need an integer "
                         "n_grains >= 1")
    return int(n_grains)


def check_stiffness_distribution(mean: float, sd: float) -> None:
    """Gaussian of the grains' stiffness factors: 0 < mean < inf, 0 <= sd < inf."""
    if not (mean > 0 and math.isfinite(mean)):
        raise ValueError(f"stiffness mean = {mean} is out of range: need 0 < mean < inf "
                         "(a factor on the pair_coeff's Kn and Ks)")
    if not (sd >= 0 and math.isfinite(sd)):
        raise ValueError(f"stiffness sd = {sd} is out of range: need 0 <= sd < inf")
    # redrawing non-positive values needs a reasonable chance of a positive one
    if sd > 0 and mean / sd < 0.5:
        raise ValueError(f"stiffness mean / sd = {mean / sd:.3g} is out of range: need "
                         "mean / sd >= 0.5 (non-positive draws are redrawn; with more than "
                         "31% of them the distribution is no longer the requested Gaussian)")


def check_strength(strength_min: float, strength_max: float,
                   boundary_strength: float) -> None:
    """Bond strength factors: 0 < min <= max < inf; 0 < boundary_strength < inf.

    The factors multiply the pair_coeff's breaking thresholds; a bond gets a
    factor drawn uniformly between min and max, times boundary_strength if its
    two particles belong to different grains (typically 0 < boundary_strength
    <= 1: weaker grain boundaries; the seed's models use 0.5).
    """
    if not (strength_min > 0 and math.isfinite(strength_min)):
        raise ValueError(f"strength min = {strength_min} is out of range: need "
                         "0 < min <= max < inf")
    if not (strength_max >= strength_min and math.isfinite(strength_max)):
        raise ValueError(f"strength max = {strength_max} is out of range: need "
                         f"min = {strength_min} <= max < inf")
    if not (boundary_strength > 0 and math.isfinite(boundary_strength)):
        raise ValueError(f"boundary_strength = {boundary_strength} is out of range: need "
                         "0 < boundary_strength < inf (typically <= 1)")


def check_grain_ids(grain: np.ndarray) -> np.ndarray:
    """Grain ids: integers 0 <= id <= 2^31 - 1 (LAMMPS' i_ properties are 32-bit)."""
    g = np.asarray(grain)
    if g.size and not np.issubdtype(g.dtype, np.integer):
        raise ValueError(f"grain ids have type {g.dtype}: need integers")
    g = g.astype(np.int64).reshape(-1)
    if g.size and (g.min() < 0 or g.max() > MAX_GRAIN):
        bad = g[(g < 0) | (g > MAX_GRAIN)][0]
        raise ValueError(f"grain id {bad} is out of range: need 0 <= id <= {MAX_GRAIN}")
    return g


def check_stiffness_factors(stiffness: np.ndarray, what: str = "stiffness") -> np.ndarray:
    """Per-particle stiffness (or, with what="strength", strength) factors: 0 < factor < inf."""
    s = np.asarray(stiffness, dtype=float).reshape(-1)
    bad = ~(np.isfinite(s) & (s > 0))
    if bad.any():
        k = int(np.argmax(bad))
        raise ValueError(f"{what} factor {s[k]} (particle index {k}) is out of range: "
                         "need 0 < factor < inf")
    return s


def check_box(box_lo: Sequence[float], box_hi: Sequence[float],
         periodic: Sequence[bool]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A box (lower and upper corners) and its periodic flags, one entry per axis (1 to 3)."""
    lo = np.asarray(box_lo, dtype=float).reshape(-1)
    hi = np.asarray(box_hi, dtype=float).reshape(-1)
    per = np.asarray(periodic, dtype=bool).reshape(-1)
    if not 1 <= len(lo) <= 3 or len(hi) != len(lo) or len(per) != len(lo):
        raise ValueError(f"box_lo, box_hi and periodic have {len(lo)}, {len(hi)} and "
                         f"{len(per)} entries: need the same number, 1 to 3 (one per axis)")
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) and np.all(hi > lo)):
        raise ValueError(f"box_lo = {lo.tolist()}, box_hi = {hi.tolist()} is not a box: "
                         "need finite box_lo < box_hi on every axis")
    return lo, hi, per


def check_points(positions: np.ndarray, dim: int) -> np.ndarray:
    """The first ``dim`` columns of (n, >= dim) finite positions."""
    p = np.asarray(positions, dtype=float)
    if p.ndim != 2 or p.shape[1] < dim:
        raise ValueError(f"positions have shape {p.shape}: need (n, {dim}) or more columns")
    p = p[:, :dim]
    if not np.all(np.isfinite(p)):
        raise ValueError("positions contain a non-finite value")
    return p


def check_axis(axis: int | str) -> int:
    """An axis as an index 0, 1, 2, from 0, 1, 2 or 'x', 'y', 'z'."""
    if isinstance(axis, str):
        if axis not in AXES:
            raise ValueError(f"axis = {axis!r} is not known: use 'x', 'y', 'z' or 0, 1, 2")
        return AXES[axis]
    if axis not in (0, 1, 2):
        raise ValueError(f"axis = {axis!r} is out of range: use 0, 1, 2 or 'x', 'y', 'z'")
    return int(axis)
