"""Stiffness factors: one per grain from a Gaussian, deterministic per grain."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from .checks import check_grain_ids, check_n_grains, check_seed, check_stiffness_distribution

MAX_REDRAWS = 1000            # per grain: non-positive stiffness draws are redrawn


def grain_stiffness(grains: int | Sequence[int] | np.ndarray, mean: float, sd: float,
                    seed: int) -> np.ndarray:
    """Stiffness factor of each grain, from a Gaussian (mean, sd), deterministic per grain.

    grains: a count n (grains 0..n-1) or an array of grain ids; the result
        has one factor per entry, in the same order.
    Grain g's factor is drawn by ``numpy.random.default_rng(SeedSequence([seed, g]))``,
    so it depends only on seed and g: not on the number of grains, their
    order, or which other grains exist.  A non-positive draw is redrawn from
    the same generator (a Gaussian truncated at zero, normalised); the
    truncation removes the fraction Phi(-mean/sd) of the distribution (3e-7
    at mean/sd = 5), and mean/sd < 0.5 is refused.
    """
    check_seed(seed)
    check_stiffness_distribution(mean, sd)
    if isinstance(grains, (int, np.integer)) and not isinstance(grains, bool):
        ids = np.arange(check_n_grains(grains))
    else:
        ids = check_grain_ids(np.asarray(grains))
    unique, inverse = np.unique(ids, return_inverse=True)
    factors = np.empty(len(unique))
    for k, g in enumerate(unique.tolist()):
        rng = np.random.default_rng(np.random.SeedSequence([seed, g]))
        for _ in range(MAX_REDRAWS):
            value = rng.normal(mean, sd)
            if value > 0:
                break
        else:   # cannot happen for mean/sd >= 0.5 (probability 0.31^1000)
            raise ValueError(f"grain {g}: {MAX_REDRAWS} non-positive stiffness draws "
                             f"(mean = {mean}, sd = {sd})")
        factors[k] = value
    return factors[inverse.reshape(-1)]


def particle_stiffness(grain: np.ndarray, mean: float, sd: float, seed: int) -> np.ndarray:
    """Per-particle stiffness factor: its grain's :func:`grain_stiffness`."""
    return grain_stiffness(check_grain_ids(grain), mean, sd, seed)
