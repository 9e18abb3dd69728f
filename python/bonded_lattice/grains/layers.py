"""Layered grains: layer indices between planes, and a competent layer in a weak matrix."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from .checks import check_axis, check_points


def layered_grains(positions: np.ndarray, axis: int | str,
                   boundaries: Sequence[float]) -> np.ndarray:
    """Layer index of every particle: how many of the (increasing) boundaries lie
    at or below its coordinate along ``axis``.

    With boundaries b0 < b1 < ..., layer 0 is below b0, layer 1 between b0
    and b1, and so on; a particle exactly on a boundary belongs to the layer
    above it.
    """
    k = check_axis(axis)
    b = np.asarray(boundaries, dtype=float).reshape(-1)
    if not np.all(np.isfinite(b)) or np.any(np.diff(b) <= 0):
        raise ValueError(f"boundaries = {b.tolist()} are out of range: need finite, "
                         "strictly increasing values")
    p = check_points(positions, k + 1)
    return np.searchsorted(b, p[:, k], side="right").astype(np.int64)


def competent_layer(positions: np.ndarray, axis: int | str, centre: float, thickness: float,
                    contrast: float) -> tuple[np.ndarray, np.ndarray]:
    """A competent layer in a weak matrix: grain ids and stiffness factors.

    The layer is the slab ``centre - thickness/2 <= coordinate < centre +
    thickness/2`` along ``axis`` (normal to the layer); its particles get grain
    1 and stiffness factor ``contrast``, the matrix on both sides grain 0 and
    factor 1.  The layer's interfaces count as grain boundaries
    (``boundary_strength`` of :class:`GrainPairOptions`; 1 makes them as
    strong as the inside).  Multiply the factors by :func:`particle_stiffness`
    for Gaussian disorder on top.
    """
    if not (thickness > 0 and math.isfinite(thickness)):
        raise ValueError(f"thickness = {thickness} is out of range: need 0 < thickness < inf")
    if not (contrast > 0 and math.isfinite(contrast)):
        raise ValueError(f"contrast = {contrast} is out of range: need 0 < contrast < inf "
                         "(layer stiffness / matrix stiffness)")
    if not math.isfinite(centre):
        raise ValueError(f"centre = {centre} is out of range: need a finite coordinate")
    layer = layered_grains(positions, axis, [centre - 0.5 * thickness, centre + 0.5 * thickness])
    grain = (layer == 1).astype(np.int64)
    return grain, np.where(grain == 1, float(contrast), 1.0)
