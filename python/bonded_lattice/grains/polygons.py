"""Grains from polygons: each particle in the grain whose outline contains it.

The outlines come from an Elle file (:func:`bonded_lattice.io.read_elle`, mapped onto the
block by :func:`map_polygons`) or a plain polygon file
(:func:`bonded_lattice.io.read_polygons`).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from ..io.polygons import Polygon
from .checks import check_box, check_grain_ids, check_points


def map_polygons(polygons: Sequence[Polygon], from_lo: Sequence[float],
                 from_hi: Sequence[float], to_lo: Sequence[float],
                 to_hi: Sequence[float]) -> list[Polygon]:
    """The polygons mapped linearly from one rectangle onto another (e.g. the
    Elle unit cell onto the particle block)."""
    f_lo, f_hi, _ = check_box(from_lo, from_hi, (False, False))
    t_lo, t_hi, _ = check_box(to_lo, to_hi, (False, False))
    scale = (t_hi - t_lo) / (f_hi - f_lo)
    return [Polygon(p.grain, t_lo + (np.asarray(p.vertices) - f_lo) * scale, p.line)
            for p in polygons]


def points_in_polygon(points: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Whether each point lies inside the polygon (even-odd rule), vectorised over points.

    Half-open rule: an edge counts where it crosses the horizontal ray from the
    point towards +x with one end strictly above the point's y and the other at
    or below it; the crossing is computed from the edge's lower end whichever
    polygon it belongs to, so it is bitwise the same in two polygons that share
    the edge.  A point on a shared edge is therefore inside exactly one of the
    two (on a horizontal edge: the one above).
    """
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    v = np.asarray(vertices, dtype=float).reshape(-1, 2)
    x, y = p[:, 0], p[:, 1]
    inside = np.zeros(len(p), dtype=bool)
    for (x0, y0), (x1, y1) in zip(v, np.roll(v, -1, axis=0)):
        if y0 == y1:
            continue
        if y0 > y1:
            x0, y0, x1, y1 = x1, y1, x0, y0
        crosses = (y0 > y) != (y1 > y)
        x_cross = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (x < x_cross)
    return inside


def _segment_distance2(points: np.ndarray, vertices: np.ndarray) -> np.ndarray:
    """Squared distance from each point to the polygon's outline."""
    best = np.full(len(points), np.inf)
    for a, b in zip(vertices, np.roll(vertices, -1, axis=0)):
        ab = b - a
        t = np.clip(((points - a) @ ab) / max(float(ab @ ab), 1e-300), 0.0, 1.0)
        d = points - (a + t[:, None] * ab)
        best = np.minimum(best, np.einsum("ij,ij->i", d, d))
    return best


def polygon_grains(positions: np.ndarray, polygons: Sequence[Polygon],
                   box_lo: Sequence[float] | None = None,
                   box_hi: Sequence[float] | None = None,
                   periodic: Sequence[bool] = (False, False),
                   outside: str = "error") -> np.ndarray:
    """Grain id of every particle: the polygon that contains its (x, y).

    polygons: in the particles' coordinates (:func:`map_polygons` maps an Elle
        cell onto the block).  A particle inside several (overlapping input, or
        a corner shared by several polygons) takes the first in the list.
    box_lo, box_hi, periodic: the periodic cell (x, y), needed only when an axis
        is periodic: particles are wrapped into it and each polygon is also
        tested shifted by one cell length either way (so a polygon may stick out
        of the cell by less than one cell, as Elle flynns do).
    outside: what to do with particles inside no polygon: ``"error"`` raises
        ``ValueError`` with their number and an example position; ``"nearest"``
        gives them the grain of the nearest polygon outline (images included).

    Each polygon is tested only on the particles inside its bounding box.
    """
    if outside not in ("error", "nearest"):
        raise ValueError(f"outside = {outside!r} is not known: use 'error' or 'nearest'")
    if not polygons:
        raise ValueError("no polygons")
    p = check_points(positions, 2).copy()
    per = np.asarray(periodic, dtype=bool).reshape(-1)
    if len(per) != 2:
        raise ValueError(f"periodic = {list(periodic)}: need two flags (x, y)")
    shifts = np.zeros((1, 2))
    if per.any():
        if box_lo is None or box_hi is None:
            raise ValueError("a periodic axis needs box_lo and box_hi (the periodic cell)")
        lo, hi, _ = check_box(box_lo, box_hi, per)
        length = hi - lo
        p[:, per] = lo[per] + np.mod(p[:, per] - lo[per], length[per])
        shifts = np.array([(i, j) for i in ((-1, 0, 1) if per[0] else (0,))
                           for j in ((-1, 0, 1) if per[1] else (0,))]) * length
    grain = np.full(len(p), -1, dtype=np.int64)
    by_x = np.argsort(p[:, 0], kind="stable")     # bounding-box prefilter: an x range, then y
    xs = p[by_x, 0]
    for poly in polygons:
        v0 = np.asarray(poly.vertices, dtype=float).reshape(-1, 2)
        if len(v0) < 3:
            raise ValueError(f"polygon of grain {poly.grain} has {len(v0)} corners: need 3")
        check_grain_ids(np.array([poly.grain]))
        for shift in shifts:
            v = v0 + shift
            lo_v, hi_v = v.min(axis=0), v.max(axis=0)
            todo = by_x[np.searchsorted(xs, lo_v[0], "left"):np.searchsorted(xs, hi_v[0], "right")]
            y = p[todo, 1]
            todo = todo[(grain[todo] < 0) & (y >= lo_v[1]) & (y <= hi_v[1])]
            if len(todo):
                hit = points_in_polygon(p[todo], v)
                grain[todo[hit]] = poly.grain
    lost = np.nonzero(grain < 0)[0]
    if len(lost) and outside == "error":
        x, y = p[lost[0]]
        raise ValueError(f"{len(lost)} particles lie in no polygon, e.g. particle index "
                         f"{lost[0]} at ({x:.6g}, {y:.6g}): cover the block with polygons "
                         "or use outside='nearest'")
    if len(lost):
        best = np.full(len(lost), np.inf)
        for poly in polygons:
            for shift in shifts:
                d2 = _segment_distance2(p[lost], np.asarray(poly.vertices, float) + shift)
                closer = d2 < best
                best[closer] = d2[closer]
                grain[lost[closer]] = poly.grain
    return grain
