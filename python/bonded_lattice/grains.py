"""Heterogeneous rock: grains, layers and per-particle stiffness factors.

The heterogeneous models of the Mike/Elle spring lattice (issue 7): every
particle belongs to a grain, each grain has its own stiffness, bonds inside a
grain and across grain boundaries break at different thresholds.  This module
makes the per-particle arrays; the pair style does the rest:

- grain ids from a seeded Voronoi tessellation (:func:`voronoi_grains`), from
  grain polygons (:func:`read_elle`, :func:`read_polygons`,
  :func:`polygon_grains`) or from layers (:func:`layered_grains`,
  :func:`competent_layer`);
- a stiffness factor per grain drawn from a Gaussian, deterministic per grain
  (:func:`grain_stiffness`, :func:`particle_stiffness`);
- the options of ``pair_style lattice/bond`` that use them
  (:class:`GrainPairOptions`): per-bond strength factors drawn uniformly in
  C++ from a hash of the seed and the two atom tags, weakened across grain
  boundaries.

The arrays go into the data file's ``Grains`` section
(:func:`bonded_lattice.lattice.write_data`), read by LAMMPS' own
``fix property/atom i_grain d_stiffness`` (:mod:`bonded_lattice.decks`).

Every function checks its parameters and raises ``ValueError`` naming the
value and its valid range.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import numpy as np

# distances in one chunk of the nearest-seed search (~32 MB of float64)
CHUNK_ELEMENTS = 4_000_000
MAX_SEED = 2**63 - 1          # LAMMPS reads the pair_style seed as a bigint
MAX_GRAIN = 2**31 - 1         # i_ properties of fix property/atom are 32-bit ints
MAX_REDRAWS = 1000            # per grain: non-positive stiffness draws are redrawn
AXES = {"x": 0, "y": 1, "z": 2}


# ---------------------------------------------------------------- validation

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


def check_stiffness_factors(stiffness: np.ndarray) -> np.ndarray:
    """Per-particle stiffness factors: 0 < factor < inf."""
    s = np.asarray(stiffness, dtype=float).reshape(-1)
    bad = ~(np.isfinite(s) & (s > 0))
    if bad.any():
        k = int(np.argmax(bad))
        raise ValueError(f"stiffness factor {s[k]} (particle index {k}) is out of range: "
                         "need 0 < factor < inf")
    return s


def _box(box_lo: Sequence[float], box_hi: Sequence[float],
         periodic: Sequence[bool]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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


def _points(positions: np.ndarray, dim: int) -> np.ndarray:
    p = np.asarray(positions, dtype=float)
    if p.ndim != 2 or p.shape[1] < dim:
        raise ValueError(f"positions have shape {p.shape}: need (n, {dim}) or more columns")
    p = p[:, :dim]
    if not np.all(np.isfinite(p)):
        raise ValueError("positions contain a non-finite value")
    return p


# ---------------------------------------------------------------- Voronoi grains

def voronoi_seeds(box_lo: Sequence[float], box_hi: Sequence[float], n_grains: int,
                  seed: int) -> np.ndarray:
    """The (n_grains, dim) seed points of :func:`voronoi_grains`, uniform in the box.

    Drawn with ``numpy.random.default_rng(seed)``: the same seed gives the same
    points on any machine and with any numpy that keeps PCG64 (numpy >= 1.17).
    """
    check_seed(seed)
    check_n_grains(n_grains)
    lo, hi, _ = _box(box_lo, box_hi, [False] * len(np.atleast_1d(box_lo)))
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
    lo, hi, per = _box(box_lo, box_hi, periodic)
    dim = len(lo)
    p = _points(positions, dim).copy()
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


# ---------------------------------------------------------------- grain polygons

@dataclass(frozen=True)
class Polygon:
    """One grain's outline.

    grain: the grain id its particles get (Elle: the flynn number).
    vertices: (k, 2) corners in order around the polygon (either sense), the
        first not repeated at the end; from an Elle file unwrapped across the
        periodic cell, so that consecutive corners are neighbours.
    line: the line of the source file that defines it (0: none), for messages.
    """

    grain: int
    vertices: np.ndarray
    line: int = 0


def _fail(path: str | Path, line: int, text: str) -> ValueError:
    return ValueError(f"{path}, line {line}: {text}")


def _numbers(tokens: list[str], path: str | Path, line: int, what: str) -> list[float]:
    try:
        values = [float(t) for t in tokens]
    except ValueError:
        raise _fail(path, line, f"{what}: {' '.join(tokens)!r} are not all numbers") from None
    if not all(math.isfinite(v) for v in values):
        raise _fail(path, line, f"{what}: {' '.join(tokens)!r} contains a non-finite number")
    return values


def _integers(tokens: list[str], path: str | Path, line: int, what: str) -> list[int]:
    if not all(re.fullmatch(r"[0-9]+", t) for t in tokens):
        raise _fail(path, line, f"{what}: {' '.join(tokens)!r} are not all integers >= 0")
    return [int(t) for t in tokens]


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


@dataclass
class _ElleFile:
    cell_lo: np.ndarray
    cell_hi: np.ndarray
    flynns: list[tuple[int, list[int], int]]   # (flynn id, node ids, line)
    nodes: dict[int, tuple[float, float]]


def _parse_elle(path: str | Path) -> _ElleFile:
    """Read the OPTIONS CellBoundingBox, FLYNNS and LOCATION sections of an Elle file."""
    section = None
    flynns: list[tuple[int, list[int], int]] = []
    nodes: dict[int, tuple[float, float]] = {}
    seen: set[str] = set()
    bbox: list[float] = []
    bbox_line = 0
    in_bbox = False
    for number, raw in enumerate(Path(path).read_text().splitlines(), start=1):
        tokens = raw.split("#", 1)[0].split()
        if not tokens:
            continue
        head = tokens[0]
        if head[0].isalpha() and not any(_is_number(t) for t in tokens[1:]):
            # a section keyword (alone or followed by names, e.g. "STRESS TAU_XX")
            section = head
            in_bbox = False
            if head == "REGIONS":
                raise _fail(path, number, "the old REGIONS format is not supported: "
                            "convert the file to FLYNNS with a current Elle")
            if head in seen and head in ("FLYNNS", "LOCATION"):
                raise _fail(path, number, f"a second {head} section")
            seen.add(head)
            continue
        if section == "OPTIONS":
            if head == "CellBoundingBox":
                bbox, bbox_line, in_bbox = [], number, True
                bbox += _numbers(tokens[1:], path, number, "CellBoundingBox")
            elif head[0].isalpha():
                in_bbox = False      # another option: ignored
            elif in_bbox:            # the corners continue on the next lines
                bbox += _numbers(tokens, path, number, "CellBoundingBox")
            else:
                raise _fail(path, number, f"unexpected numbers {raw.strip()!r} in OPTIONS")
        elif section == "FLYNNS":
            if head[0].isalpha():
                raise _fail(path, number, f"unexpected entry {head!r} in FLYNNS: need "
                            "'flynn-id number-of-nodes node-id ...'")
            values = _integers(tokens, path, number, "flynn record")
            if len(values) < 2:
                raise _fail(path, number, "flynn record: need 'flynn-id number-of-nodes "
                            "node-id ...'")
            flynn, count, ids = values[0], values[1], values[2:]
            if count < 3:
                raise _fail(path, number, f"flynn {flynn} has {count} nodes: need at least 3")
            if len(ids) != count:
                raise _fail(path, number, f"flynn {flynn} declares {count} nodes but lists "
                            f"{len(ids)} (one flynn per line)")
            if any(f[0] == flynn for f in flynns):
                raise _fail(path, number, f"flynn {flynn} is defined twice")
            flynns.append((flynn, ids, number))
        elif section == "LOCATION":
            if len(tokens) != 3:
                raise _fail(path, number, f"location record {raw.strip()!r}: need "
                            "'node-id x y'")
            node = _integers(tokens[:1], path, number, "node id")[0]
            x, y = _numbers(tokens[1:], path, number, f"node {node} position")
            if node in nodes:
                raise _fail(path, number, f"node {node} is located twice")
            nodes[node] = (x, y)
        # every other section (UNODES, attributes, PARENTS, ...) is skipped
    if "FLYNNS" not in seen or not flynns:
        raise ValueError(f"{path}: no FLYNNS section with flynns (is it an Elle file?)")
    if "LOCATION" not in seen:
        raise ValueError(f"{path}: no LOCATION section (node positions)")
    cell_lo, cell_hi = np.zeros(2), np.ones(2)
    if bbox_line:
        if len(bbox) != 8:
            raise _fail(path, bbox_line, f"CellBoundingBox has {len(bbox)} numbers: need "
                        "the x y of its 4 corners")
        c = np.array(bbox).reshape(4, 2)   # base left, base right, top right, top left
        rectangle = (c[0, 1] == c[1, 1] and c[2, 1] == c[3, 1] and c[0, 0] == c[3, 0]
                     and c[1, 0] == c[2, 0] and c[1, 0] > c[0, 0] and c[3, 1] > c[0, 1])
        if not rectangle:
            raise _fail(path, bbox_line, f"CellBoundingBox {bbox} is not an upright "
                        "rectangle (base left, base right, top right, top left): sheared "
                        "unit cells are not supported")
        cell_lo, cell_hi = c[0].copy(), c[2].copy()
    return _ElleFile(cell_lo, cell_hi, flynns, nodes)


def read_elle_cell(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper corners of an Elle file's periodic unit cell.

    From ``CellBoundingBox`` in OPTIONS (an upright rectangle; sheared cells
    raise), else Elle's default, the unit square.
    """
    elle = _parse_elle(path)
    return elle.cell_lo, elle.cell_hi


def read_elle(path: str | Path) -> list[Polygon]:
    """The grain polygons (flynns) of an Elle file, one :class:`Polygon` per flynn.

    Supported: sections separated by keyword lines; ``#`` comments;
    ``FLYNNS`` with one flynn per line, ``flynn-id number-of-nodes node-id ...``
    (nodes in order around the flynn); ``LOCATION`` with ``node-id x y``;
    ``OPTIONS`` ``CellBoundingBox`` (an upright rectangle, default the unit
    square).  Other sections (UNODES, attributes, PARENTS) are skipped.

    Elle's unit cell is periodic and stores node positions wrapped into it: a
    flynn that straddles the cell boundary has nodes on both sides.  As Elle
    itself does when it draws a flynn, each node is moved by whole cell lengths
    to lie within half a cell of the previous node; a flynn can therefore stick
    out of the cell by up to half a cell (:func:`polygon_grains` with
    ``periodic`` wraps it back).  A flynn that wraps all the way around the cell
    (a band across the periodic box) raises ``ValueError``, as do a malformed
    line (named by its number), a missing section and a flynn whose node has no
    location.
    """
    elle = _parse_elle(path)
    length = elle.cell_hi - elle.cell_lo
    polygons = []
    for flynn, ids, line in elle.flynns:
        missing = [n for n in ids if n not in elle.nodes]
        if missing:
            raise _fail(path, line, f"flynn {flynn}: node {missing[0]} has no position in "
                        "LOCATION")
        xy = np.array([elle.nodes[n] for n in ids])
        out = np.empty_like(xy)
        out[0] = xy[0]
        for k in range(1, len(xy)):
            step = xy[k] - out[k - 1]
            out[k] = out[k - 1] + step - length * np.round(step / length)
        closing = xy[0] - out[-1]
        closing_image = closing - length * np.round(closing / length)
        if not np.allclose(closing, closing_image, rtol=0, atol=1e-12 * length.max()):
            raise _fail(path, line, f"flynn {flynn} wraps around the periodic unit cell "
                        "(a band across the cell): not supported")
        polygons.append(Polygon(flynn, out, line))
    return polygons


def read_polygons(path: str | Path) -> list[Polygon]:
    """Grain polygons from a plain text file: one per line, ``grain x1 y1 x2 y2 x3 y3 ...``.

    At least three corners, in order around the polygon; ``#`` starts a
    comment.  Malformed lines raise ``ValueError`` naming the line.
    """
    polygons = []
    for number, raw in enumerate(Path(path).read_text().splitlines(), start=1):
        tokens = raw.split("#", 1)[0].split()
        if not tokens:
            continue
        grain = _integers(tokens[:1], path, number, "grain id")[0]
        xy = _numbers(tokens[1:], path, number, f"grain {grain} corners")
        if len(xy) % 2 or len(xy) < 6:
            raise _fail(path, number, f"grain {grain} has {len(xy)} coordinates: need "
                        "x y pairs of at least 3 corners")
        polygons.append(Polygon(grain, np.array(xy).reshape(-1, 2), number))
    if not polygons:
        raise ValueError(f"{path}: no polygons")
    return polygons


def map_polygons(polygons: Sequence[Polygon], from_lo: Sequence[float],
                 from_hi: Sequence[float], to_lo: Sequence[float],
                 to_hi: Sequence[float]) -> list[Polygon]:
    """The polygons mapped linearly from one rectangle onto another (e.g. the
    Elle unit cell onto the particle block)."""
    f_lo, f_hi, _ = _box(from_lo, from_hi, (False, False))
    t_lo, t_hi, _ = _box(to_lo, to_hi, (False, False))
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
    p = _points(positions, 2).copy()
    per = np.asarray(periodic, dtype=bool).reshape(-1)
    if len(per) != 2:
        raise ValueError(f"periodic = {list(periodic)}: need two flags (x, y)")
    shifts = np.zeros((1, 2))
    if per.any():
        if box_lo is None or box_hi is None:
            raise ValueError("a periodic axis needs box_lo and box_hi (the periodic cell)")
        lo, hi, _ = _box(box_lo, box_hi, per)
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


# ---------------------------------------------------------------- layers

def _axis(axis: int | str) -> int:
    if isinstance(axis, str):
        if axis not in AXES:
            raise ValueError(f"axis = {axis!r} is not known: use 'x', 'y', 'z' or 0, 1, 2")
        return AXES[axis]
    if axis not in (0, 1, 2):
        raise ValueError(f"axis = {axis!r} is out of range: use 0, 1, 2 or 'x', 'y', 'z'")
    return int(axis)


def layered_grains(positions: np.ndarray, axis: int | str,
                   boundaries: Sequence[float]) -> np.ndarray:
    """Layer index of every particle: how many of the (increasing) boundaries lie
    at or below its coordinate along ``axis``.

    With boundaries b0 < b1 < ..., layer 0 is below b0, layer 1 between b0
    and b1, and so on; a particle exactly on a boundary belongs to the layer
    above it.
    """
    k = _axis(axis)
    b = np.asarray(boundaries, dtype=float).reshape(-1)
    if not np.all(np.isfinite(b)) or np.any(np.diff(b) <= 0):
        raise ValueError(f"boundaries = {b.tolist()} are out of range: need finite, "
                         "strictly increasing values")
    p = _points(positions, k + 1)
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


# ---------------------------------------------------------------- stiffness

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


# ---------------------------------------------------------------- pair style and lattice

@dataclass(frozen=True)
class GrainPairOptions:
    """The ``pair_style lattice/bond`` keywords of a heterogeneous model.

    strength_min, strength_max: each bond's breaking thresholds are the
        pair_coeff's times a factor drawn uniformly in [min, max] (in C++, from
        a hash of seed and the two atom tags: the same on any number of ranks);
    boundary_strength: extra factor for bonds whose particles are in different
        grains (the seed's models: 0.5);
    seed: of the strength draws.
    The stiffness factors come from the data file (``d_stiffness``); the C++
    side defines the keywords (docs/pair_lattice_bond.rst).
    """

    strength_min: float = 1.0
    strength_max: float = 1.0
    seed: int = 1
    boundary_strength: float = 0.5

    def __post_init__(self) -> None:
        check_strength(self.strength_min, self.strength_max, self.boundary_strength)
        check_seed(self.seed)

    def pair_style_args(self) -> str:
        """``grain i_grain stiffness d_stiffness strength MIN MAX seed S boundary_strength F``."""
        return (f"grain i_grain stiffness d_stiffness strength {self.strength_min!r} "
                f"{self.strength_max!r} seed {self.seed} "
                f"boundary_strength {self.boundary_strength!r}")


SOURCES = ("voronoi", "elle", "polygons", "layer")


@dataclass(frozen=True)
class GrainModel:
    """How to give a block its grains and stiffness factors (:func:`grain_arrays`).

    source: ``voronoi`` (n_grains seeded cells in the block's rectangle),
        ``elle`` (an Elle file's flynns, its unit cell mapped onto the block,
        periodic as in Elle), ``polygons`` (a plain polygon file, in the
        particles' coordinates) or ``layer`` (:func:`competent_layer` of
        layer_thickness and layer_contrast across the middle of the block,
        normal to layer_axis).
    stiffness_mean, stiffness_sd, seed: per-grain Gaussian factors
        (:func:`grain_stiffness`; sd = 0 gives every grain the mean), and the
        seed of the Voronoi points.
    outside: polygons only, for particles in no polygon (:func:`polygon_grains`).
    """

    source: str
    n_grains: int = 0
    path: str | None = None
    periodic: tuple[bool, bool] = (False, False)
    layer_thickness: float = 0.0
    layer_contrast: float = 1.0
    layer_axis: str = "y"
    stiffness_mean: float = 1.0
    stiffness_sd: float = 0.0
    seed: int = 1
    outside: str = "error"

    def __post_init__(self) -> None:
        if self.source not in SOURCES:
            raise ValueError(f"source = {self.source!r} is not known: use one of "
                             f"{', '.join(SOURCES)}")
        check_seed(self.seed)
        check_stiffness_distribution(self.stiffness_mean, self.stiffness_sd)
        if self.source == "voronoi":
            check_n_grains(self.n_grains)
        if self.source in ("elle", "polygons") and not self.path:
            raise ValueError(f"source = {self.source!r} needs a path")
        if self.source == "layer":
            _axis(self.layer_axis)
            if not (self.layer_thickness > 0 and math.isfinite(self.layer_thickness)):
                raise ValueError(f"layer_thickness = {self.layer_thickness} is out of range: "
                                 "need 0 < layer_thickness < inf")
            if not (self.layer_contrast > 0 and math.isfinite(self.layer_contrast)):
                raise ValueError(f"layer_contrast = {self.layer_contrast} is out of range: "
                                 "need 0 < layer_contrast < inf")


def grain_arrays(positions: np.ndarray, d: float,
                 model: GrainModel) -> tuple[np.ndarray, np.ndarray]:
    """Grain id and stiffness factor of every particle of a block, for the data file.

    positions: (n, 2 or 3) particle centres; d: particle diameter.  The
    block's rectangle is the particles' outer extent (centres +- d/2): the
    Voronoi points fill it, the Elle unit cell is mapped onto it, the layer
    is centred in it.
    """
    p = _points(positions, 2)
    if not (d > 0 and math.isfinite(d)):
        raise ValueError(f"d = {d} is out of range: need 0 < d < inf")
    if len(p) == 0:
        raise ValueError("no particles")
    full = np.asarray(positions, dtype=float)
    lo, hi = p.min(axis=0) - 0.5 * d, p.max(axis=0) + 0.5 * d
    extra = np.ones(len(p))
    if model.source == "voronoi":
        grain = voronoi_grains(p, lo, hi, model.n_grains, model.seed, model.periodic)
    elif model.source == "elle":
        cell_lo, cell_hi = read_elle_cell(model.path)
        polygons = map_polygons(read_elle(model.path), cell_lo, cell_hi, lo, hi)
        grain = polygon_grains(p, polygons, lo, hi, (True, True), model.outside)
    elif model.source == "polygons":
        grain = polygon_grains(p, read_polygons(model.path), lo, hi, model.periodic,
                               model.outside)
    else:
        k = _axis(model.layer_axis)
        coord = full[:, k]
        centre = 0.5 * (coord.min() + coord.max())
        grain, extra = competent_layer(full, k, centre, model.layer_thickness,
                                       model.layer_contrast)
    stiffness = particle_stiffness(grain, model.stiffness_mean, model.stiffness_sd,
                                   model.seed) * extra
    return grain, stiffness
