"""Fractures of a broken-bond set on the triangular lattice, and what they show.

A broken bond opens a crack face across the bond: in the dual lattice (the honeycomb of the
triangles' centroids) it is the dual edge of the bond, and a crack is a line of such edges.
:func:`fracture_labels` groups broken bonds into fractures: two broken bonds belong to the
same fracture when their midpoints (in the initial lattice) are at most one bond length d
apart (:data:`LINK`).  In the triangular lattice the bond midpoints lie at d/2 (two sides of
one triangle: their crack faces meet at its centroid), sqrt3/2 d (two bonds of one particle
at 120 degrees), d (opposite sides of a rhombus, or two collinear bonds of one particle),
and next at sqrt7/2 d = 1.32 d.  The rule therefore joins crack faces that meet, and faces
that only one intact bond separates (or that cut off a single particle).  The latter are
needed: a crack opening normal to a row direction breaks mostly the bonds of that direction,
stepping by d/2 from row to row (the en-echelon steps seen in the scene pictures), and its
faces in consecutive rows are opposite sides of a rhombus, d apart; joining only faces that
meet would cut such a crack into single bonds.  Two cracks are told apart when no bond of
one lies within d of a bond of the other (two straight cracks across the rows 2 d apart are
two).

The measures of the scenes (issue 20, point 4), each on the broken bonds (id1, id2) of a
run, 1-based ids into the initial positions:

- :func:`layer_fractures`: the fractures crossing a competent layer, their share of the
  broken bonds and their spacing over the layer thickness; and the field geologist's count,
  the fractures met by a scanline along the layer's middle row;
- :func:`intergranular_fraction`: the share of broken bonds joining two grains;
- :func:`radial_fractures`: the fractures that start at growing grains and run outwards.
"""

from __future__ import annotations

import math

import numpy as np

from .lattice import pairs_within

__all__ = ["BAND", "LINK", "REACH", "bond_midpoints", "fracture_labels", "intergranular_fraction",
           "layer_fractures", "radial_fractures"]

#: Largest midpoint distance, in bond lengths d, of two broken bonds of one fracture: d, with
#: room for rounding (the next midpoint distance of the lattice is sqrt7/2 d = 1.32 d).
LINK = 1.1
#: Default distance, in bond lengths d, beyond the growing grains that a radial fracture
#: must reach (:func:`radial_fractures`).
REACH = 3.0
#: Width, in bond lengths d, of the band beyond ``reach`` in which radial fractures are counted.
BAND = 2.0
ROW = 0.5 * math.sqrt(3.0)     # row spacing of the triangular lattice, in units of d


def _check_d(d: float) -> float:
    if not (d > 0 and math.isfinite(d)):
        raise ValueError(f"d = {d} is out of range: need 0 < d < inf")
    return float(d)


def _check_pairs(pairs: np.ndarray, n: int) -> np.ndarray:
    """(m, 2) int64 of 1-based particle ids in 1..n (from the bond dump's id1, id2)."""
    p = np.asarray(pairs, dtype=float)
    if p.size == 0:
        return np.zeros((0, 2), dtype=np.int64)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"pairs have shape {p.shape}: need (m, 2), the columns id1 id2")
    if np.any(p != np.round(p)) or np.any(p < 1) or np.any(p > n):
        bad = p[(p != np.round(p)) | (p < 1) | (p > n)][0]
        raise ValueError(f"particle id {bad} is out of range: need whole ids 1 <= id <= {n}")
    return p.astype(np.int64)


def _check_mask(mask: np.ndarray, n: int, name: str) -> np.ndarray:
    m = np.asarray(mask)
    if m.dtype != bool or m.shape != (n,):
        raise ValueError(f"{name} has shape {m.shape} and dtype {m.dtype}: need a boolean "
                         f"array of one value per particle, shape ({n},)")
    if not m.any():
        raise ValueError(f"{name} selects no particle: need at least one")
    return m


def _check_period(period: tuple[float, float] | None) -> np.ndarray | None:
    """The (x, y) lengths of a periodic box as an array, or None (a box with walls)."""
    if period is None:
        return None
    length = np.asarray(period, dtype=float).reshape(-1)
    if length.shape != (2,) or not np.all(np.isfinite(length) & (length > 0)):
        raise ValueError(f"period = {period} is out of range: need two box lengths "
                         "(x, y), each 0 < L < inf")
    return length


def bond_midpoints(pairs: np.ndarray, positions: np.ndarray,
                   period: tuple[float, float] | None = None) -> np.ndarray:
    """(m, 2) midpoints (x, y) of bonds (id1, id2), 1-based ids into ``positions``; with
    ``period`` (the (x, y) lengths of a periodic box) a bond across the seam is taken at
    its minimum image, its midpoint beside particle id1 (up to d/2 outside the cell)."""
    pos = np.asarray(positions, dtype=float)
    p = _check_pairs(pairs, len(pos))
    box = _check_period(period)
    a, b = pos[p[:, 0] - 1, :2], pos[p[:, 1] - 1, :2]
    sep = b - a
    if box is not None:
        sep -= box * np.round(sep / box)
    return a + 0.5 * sep


def _components(n: int, i: np.ndarray, j: np.ndarray) -> np.ndarray:
    """Connected components of n nodes joined by edges (i, j): labels 0, 1, ... in the
    order of each component's first node."""
    parent = list(range(n))

    def root(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in zip(i.tolist(), j.tolist()):
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([root(a) for a in range(n)], dtype=np.int64)
    _, labels = np.unique(roots, return_inverse=True)
    return labels.astype(np.int64)


def _group(midpoints: np.ndarray, d: float, period: np.ndarray | None = None) -> np.ndarray:
    """Fracture label of every midpoint: components of the midpoints at most LINK d apart
    (with ``period``, the box lengths of a periodic box: by minimum image, the midpoints
    searched together with their eight images shifted by the periods)."""
    m = len(midpoints)
    if m == 0:
        return np.zeros(0, dtype=np.int64)
    shifts = [(0.0, 0.0)]
    if period is not None:
        shifts += [(sx * period[0], sy * period[1]) for sx in (-1, 0, 1) for sy in (-1, 0, 1)
                   if sx or sy]
    p3 = np.zeros((m * len(shifts), 3))
    for k, (sx, sy) in enumerate(shifts):
        p3[k * m:(k + 1) * m, 0] = midpoints[:, 0] + sx
        p3[k * m:(k + 1) * m, 1] = midpoints[:, 1] + sy
    i, j, _ = pairs_within(p3, LINK * d)
    i, j = i % m, j % m
    keep = i != j
    return _components(m, i[keep], j[keep])


def fracture_labels(pairs: np.ndarray, positions: np.ndarray, d: float,
                    period: tuple[float, float] | None = None) -> np.ndarray:
    """Fracture label (0, 1, ...) of every broken bond (id1, id2): broken bonds whose
    midpoints in ``positions`` (the initial lattice of bond length d) are at most d apart
    belong to one fracture (the module's rule), and so do chains of them; with ``period``
    (the (x, y) lengths of a periodic box) by minimum image, across the seam."""
    box = _check_period(period)
    return _group(bond_midpoints(pairs, positions, period), _check_d(d), box)


def _mean_x(x: np.ndarray, period_x: float | None) -> float:
    """Mean of x, or on a circle of length ``period_x`` the circular mean (a fracture
    across the seam of a periodic box lies at the seam, not in the middle of the box),
    then in (-period_x / 2, period_x / 2]."""
    if period_x is None:
        return float(np.mean(x))
    phase = np.exp(2j * math.pi * x / period_x).mean()
    return float(np.angle(phase) / (2 * math.pi) * period_x)


def intergranular_fraction(pairs: np.ndarray, grain: np.ndarray) -> float | None:
    """Share of the broken bonds (id1, id2) whose particles lie in different grains
    (``grain``: one id per particle); None without broken bonds."""
    g = np.asarray(grain).reshape(-1)
    p = _check_pairs(pairs, len(g))
    if len(p) == 0:
        return None
    return float(np.mean(g[p[:, 0] - 1] != g[p[:, 1] - 1]))


def layer_fractures(pairs: np.ndarray, positions: np.ndarray, layer: np.ndarray,
                    d: float, period: tuple[float, float] | None = None) -> dict:
    """The fractures of a competent layer parallel to x (``layer``: its particles).

    Returns ``fraction_in_layer``, the share of broken bonds with both particles in the
    layer (None without broken bonds); ``fractures_in_layer``, the number of fractures
    crossing the layer; ``layer_fracture_x``, their positions along x (sorted);
    ``layer_thickness``; and ``spacing_to_thickness``, the mean gap between neighbouring
    crossing fractures over the layer thickness (None with fewer than two; periodic box:
    below).

    The layer's fractures are the fractures (:func:`fracture_labels`) of its own broken
    bonds, those with both particles in it: a crack that crosses the layer twice, joined
    through the matrix, is two crossings.  One of them crosses the layer when its broken
    bonds reach from within one row spacing (sqrt3/2 d) of the lower interface to within
    one row spacing of the upper one, the interfaces lying half a row outside the layer's
    outer particle rows: it has broken the outer row's bonds or those between the outer
    row and the next, on both sides.  Its position is the mean x of its bonds' midpoints.
    The thickness is the distance between the interfaces, (rows of the layer) x sqrt3/2 d,
    the convention of the box height.  The spacing uses the gaps between neighbouring
    crossing fractures only: the box's side walls, where the load is applied, are not
    fractures, so the matrix beyond the outermost crossings does not count.

    With ``period`` (the (x, y) lengths of a periodic box, no walls) the bonds across the
    seam are taken at their minimum image and grouped across it, a fracture's position is
    the circular mean of its midpoints' x, in [x0, x0 + L_x) with x0 the lowest particle x,
    and the n crossings lie on a ring of length L_x: the mean spacing is L_x / n, defined
    for one crossing too (the fracture and its periodic image).

    The scanline count (``scanline_fractures``, ``scanline_x``,
    ``scanline_spacing_to_thickness``) is the field's way of measuring spacing: the
    fractures a line along the middle of the layer meets.  The line runs along the layer's
    middle particle row (the row nearest the mid-thickness, the lower of two), where the
    only crack faces it can cross are those of the row's own x-parallel bonds: every crack
    that passes the row breaks one of them.  Broken bonds of that row that are neighbours
    (d apart: a particle cut out) count once; each count's position is their mean x.  It
    does not merge fractures that cross or touch elsewhere in the layer, which the
    crossing count (one fracture per group of broken bonds) does.  The spacing is as for
    the crossings (L_x / n in a periodic box; the mean gap otherwise).
    """
    pos = np.asarray(positions, dtype=float)
    d = _check_d(d)
    p = _check_pairs(pairs, len(pos))
    inside = _check_mask(layer, len(pos), "layer")
    y = pos[inside, 1]
    y_bot, y_top = float(y.min()), float(y.max())
    row = ROW * d
    thickness = y_top - y_bot + row
    both = inside[p[:, 0] - 1] & inside[p[:, 1] - 1] if len(p) else np.zeros(0, dtype=bool)
    box = _check_period(period)
    mid = bond_midpoints(p[both], pos, period)
    labels = _group(mid, d, box)
    tol = 1e-6 * d
    x0 = float(pos[:, 0].min())
    xs = []
    for k in range(int(labels.max()) + 1 if len(labels) else 0):
        mk = mid[labels == k]
        if mk[:, 1].min() <= y_bot + 0.5 * row + tol and mk[:, 1].max() >= y_top - 0.5 * row - tol:
            if box is None:
                xs.append(_mean_x(mk[:, 0], None))
            else:
                xs.append(x0 + (_mean_x(mk[:, 0], float(box[0])) - x0) % float(box[0]))
    xs.sort()
    scan = _scanline(p[both], pos, inside, d, box)
    return {"fractures_in_layer": len(xs),
            "fraction_in_layer": float(both.mean()) if len(p) else None,
            "spacing_to_thickness": _spacing(xs, box, thickness), "layer_thickness": thickness,
            "layer_fracture_x": xs, "scanline_fractures": len(scan), "scanline_x": scan,
            "scanline_spacing_to_thickness": _spacing(scan, box, thickness)}


def _spacing(xs: list[float], box: np.ndarray | None, thickness: float) -> float | None:
    """Mean spacing of sorted positions over the thickness: L_x / n in a periodic box, else
    the mean gap (None with too few)."""
    if box is not None:
        return float(box[0]) / len(xs) / thickness if xs else None
    return float(np.mean(np.diff(xs))) / thickness if len(xs) >= 2 else None


def _scanline(pairs: np.ndarray, pos: np.ndarray, inside: np.ndarray, d: float,
              box: np.ndarray | None) -> list[float]:
    """Sorted x of the fractures the layer's middle row meets (:func:`layer_fractures`):
    its broken x-parallel bonds, neighbours (d apart, across the seam too) counted once."""
    rows = np.unique(np.round(pos[inside, 1] / (0.01 * d))) * (0.01 * d)   # rows' y, sorted
    mid_y = 0.5 * (pos[inside, 1].min() + pos[inside, 1].max())
    row_y = rows[np.argmin(np.abs(rows - mid_y) - 1e-9 * d * (rows < mid_y))]  # ties: the lower
    tol = 0.1 * d      # the rows are sqrt3/2 d apart
    a, b = pos[pairs[:, 0] - 1, :2], pos[pairs[:, 1] - 1, :2]
    on_row = (np.abs(a[:, 1] - row_y) < tol) & (np.abs(b[:, 1] - row_y) < tol)
    x = np.sort(bond_midpoints(pairs[on_row], pos, None if box is None else tuple(box))[:, 0])
    if box is not None and len(x):
        x0 = float(pos[:, 0].min())
        x = np.sort(x0 + (x - x0) % float(box[0]))
    if len(x) == 0:
        return []
    # runs of neighbours (gaps of d); in a periodic box the last run may continue the first
    breaks = np.flatnonzero(np.diff(x) > LINK * d)
    runs = np.split(x, breaks + 1)
    if box is not None and len(runs) > 1 and x[0] + float(box[0]) - x[-1] <= LINK * d:
        runs = [np.concatenate([runs[-1], runs[0] + float(box[0])])] + runs[1:-1]
    out = []
    for r in runs:
        c = float(np.mean(r))
        if box is not None:
            x0 = float(pos[:, 0].min())
            c = x0 + (c - x0) % float(box[0])
        out.append(c)
    return sorted(out)


def radial_fractures(pairs: np.ndarray, positions: np.ndarray, growing: np.ndarray, d: float,
                     reach: float = REACH, period: tuple[float, float] | None = None) -> int:
    """Number of radial fractures around growing grains (``growing``: their particles).

    Broken bonds inside the growing grains (both particles growing) are left out; the rest
    are grouped into fractures (:func:`fracture_labels`).  A fracture starts at the grains
    when one of its bonds' midpoints lies within d of a growing particle: it has broken a
    bond of the grains' boundary or one between two particles next to it.  The radial
    fractures are the places where such fractures cross the contour at ``reach`` x d from
    the grains: the fractures' bonds whose midpoints lie between reach and reach + 2 bond
    lengths from the nearest growing particle, grouped by the same rule (a crack steps at
    most d outwards from one bond to the next, so each crossing of the band leaves at least
    two bonds in it).  A crack counts once when it reaches the contour, whether or not it
    branches beyond it; cracks that leave the grains separately count separately even if
    they join farther out or are joined at the boundary (by broken boundary bonds).  The
    default 3 d leaves out the one- and two-bond breaks of a crushed boundary.  With
    ``period`` (the (x, y) lengths of a periodic box) bonds, fractures and distances are
    taken by minimum image, across the seam.
    """
    pos = np.asarray(positions, dtype=float)
    d = _check_d(d)
    if not (reach >= 1 and math.isfinite(reach)):
        raise ValueError(f"reach = {reach} is out of range: need 1 <= reach < inf "
                         "(bond lengths beyond the growing grains)")
    p = _check_pairs(pairs, len(pos))
    grows = _check_mask(growing, len(pos), "growing")
    if len(p) == 0:
        return 0
    box = _check_period(period)
    p = p[~(grows[p[:, 0] - 1] & grows[p[:, 1] - 1])]
    mid = bond_midpoints(p, pos, period)
    labels = _group(mid, d, box)
    dist = _distance(mid, pos[_rim(pos, grows, d), :2], (reach + BAND) * d, box)
    touching = np.isin(labels, np.unique(labels[dist <= LINK * d]))
    band = touching & (dist >= reach * d) & (dist < (reach + BAND) * d)
    return int(_group(mid[band], d, box).max()) + 1 if band.any() else 0


def _rim(positions: np.ndarray, inside: np.ndarray, d: float) -> np.ndarray:
    """Indices of the selected particles with fewer than six selected lattice neighbours.

    For a point outside the selection the nearest selected particle is one of these: the
    Voronoi cell of a triangular lattice point is bounded by its six neighbours alone, so a
    point outside a particle's cell is closer to one of its neighbours.  Searching these
    only keeps the search linear in the growing grains' perimeter, not their area.
    """
    idx = np.flatnonzero(inside)
    p3 = np.zeros((len(idx), 3))
    p3[:, :2] = positions[idx, :2]
    i, j, _ = pairs_within(p3, (1.0 + 1e-6) * d)
    count = np.bincount(i, minlength=len(idx)) + np.bincount(j, minlength=len(idx))
    return idx[count < 6]


def _distance(points: np.ndarray, targets: np.ndarray, r: float,
              period: np.ndarray | None = None) -> np.ndarray:
    """Distance from each point (m, 2) to the nearest target (t, 2), inf beyond r; with
    ``period`` (the box lengths of a periodic box) to the nearest image of a target."""
    m = len(points)
    if period is not None:    # the targets and their eight images
        targets = np.vstack([targets + (sx * period[0], sy * period[1])
                             for sx in (-1, 0, 1) for sy in (-1, 0, 1)])
    both = np.zeros((m + len(targets), 3))
    both[:m, :2] = points
    both[m:, :2] = targets
    i, j, dist = pairs_within(both, r)
    out = np.full(m, np.inf)
    cross = (i < m) & (j >= m)
    np.minimum.at(out, i[cross], dist[cross])
    return out
