"""A Mike/Elle scene's particles: the box lattice, its wall rows and its grains.

:func:`build_model` lays out the lattice of a :class:`bonded_lattice.scene_definition.Scene`
(:func:`box_lattice`, in a box with margins for the walls or periodic), gives it the grain
ids and stiffness factors of :func:`bonded_lattice.grains.grain_arrays` (a competent layer or
Voronoi grains: :func:`grain_model`, periodic in a periodic box) and picks the growing grains
(:func:`expanding_grains`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .grains import GrainModel, grain_arrays, voronoi_seeds
from .lattice import Lattice, contact_pairs, pairs_within
from .scene_definition import ROW, Scene


def box_lattice(n_x: int, n_y: int, d: float, periodic: bool = False) -> Lattice:
    """n_x x n_y particles: rows along x at y = d/2 + j sqrt3/2 d, odd rows shifted by d/2,
    so every row holds n_x particles; numbered row by row.

    periodic False: the box has a margin of 2 d around the particles (for the walls);
    True: the box is the lattice's periodic cell, n_x d wide and n_y sqrt3/2 d high (n_y
    even), from x = d/4 (so no particle lies on a face) and half a row below the first
    row: every particle has its six neighbours across the periodic faces."""
    if periodic and n_y % 2:
        raise ValueError(f"n_y = {n_y} is out of range for a periodic box: need an even "
                         "number of rows")
    j, i = np.meshgrid(np.arange(n_y), np.arange(n_x), indexing="ij")
    pos = np.zeros((n_x * n_y, 3))
    pos[:, 0] = ((i + 0.5 * (j % 2)) * d + 0.5 * d).reshape(-1)
    pos[:, 1] = (j * ROW * d + 0.5 * d).reshape(-1)
    if periodic:
        y0 = 0.5 * d - 0.5 * ROW * d
        box = np.array([[0.25 * d, (n_x + 0.25) * d], [y0, y0 + n_y * ROW * d],
                        [-0.5 * d, 0.5 * d]])
        return Lattice(pos, d, 2, box)
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    # margin 2 d: the walls move out by strain x half the box, a fraction of d
    box = np.array([[lo[0] - 2 * d, hi[0] + 2 * d], [lo[1] - 2 * d, hi[1] + 2 * d],
                    [-0.5 * d, 0.5 * d]])
    return Lattice(pos, d, 2, box)


def periodic_pairs(lattice: Lattice) -> np.ndarray:
    """Index pairs (i < j) of touching particles of a lattice in a box periodic in x and y
    (minimum image; :func:`box_lattice` with periodic True): the bonds the pair style
    makes, 3 per particle."""
    p = lattice.positions[:, :2]
    length = lattice.box[:2, 1] - lattice.box[:2, 0]
    if np.any(length < 3.0 * lattice.d):
        raise ValueError(f"box lengths {length.tolist()} are out of range: need >= 3 d per "
                         "periodic axis for minimum-image neighbours")
    # wrap a copy shifted by half a box: the pairs within d of the original and the
    # shifted copy's positions cover every minimum-image pair (none is longer than d)
    found = set()
    for shift in ((0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)):
        q = np.zeros((len(p), 3))
        q[:, :2] = np.mod(p - lattice.box[:2, 0] + np.array(shift) * length, length)
        i, j, r = pairs_within(q, 1.000001 * lattice.d)
        found.update(zip(i.tolist(), j.tolist()))
    return np.array(sorted(found), dtype=np.int64).reshape(-1, 2)


def lattice_bond_ids(lattice: Lattice, periodic: bool) -> np.ndarray:
    """(id1, id2) atom ids (from 1, the data file's numbering) of every bond the pair style
    makes in a scene's lattice: the touching pairs, across the seam too in a periodic box
    (:func:`periodic_pairs`)."""
    pairs = periodic_pairs(lattice) if periodic else contact_pairs(lattice)
    return pairs + 1


def box_period(lattice: Lattice) -> tuple[float, float]:
    """The (x, y) lengths of a lattice's box (the periods of a periodic box)."""
    length = lattice.box[:2, 1] - lattice.box[:2, 0]
    return float(length[0]), float(length[1])


def wall_masks(positions: np.ndarray, d: float) -> dict[str, np.ndarray]:
    """The four wall rows (the deck selects the same particles with regions)."""
    x, y = positions[:, 0], positions[:, 1]
    return {"left": x < x.min() + 0.6 * d, "right": x > x.max() - 0.6 * d,
            "bottom": y < y.min() + 0.1 * d, "top": y > y.max() - 0.1 * d}


def grain_box(lattice: Lattice, periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    """The rectangle (lo, hi) in x and y that the Voronoi points fill: the particles'
    outer extent (centres +- d/2) in a box with walls, the periodic cell in a periodic
    box (where the grains are periodic too)."""
    if periodic:
        return lattice.box[:2, 0].copy(), lattice.box[:2, 1].copy()
    p = lattice.positions[:, :2]
    return p.min(axis=0) - 0.5 * lattice.d, p.max(axis=0) + 0.5 * lattice.d


def expanding_grains(grain: np.ndarray, positions: np.ndarray, d: float, n_grains: int,
                     seed: int, count: int,
                     box: tuple[np.ndarray, np.ndarray] | None = None,
                     walls: bool = True) -> list[int]:
    """The ``count`` grains whose Voronoi seed points lie nearest the box centre, those
    that touch no wall row first (with few grains every grain may touch a wall: then the
    nearest ones that do; walls False, a periodic box: no grain touches a wall).

    box: the rectangle of the Voronoi points (:func:`grain_box`; default: the particles'
    outer extent)."""
    p = positions[:, :2]
    lo, hi = box if box is not None else (p.min(axis=0) - 0.5 * d, p.max(axis=0) + 0.5 * d)
    seeds = voronoi_seeds(lo, hi, n_grains, seed)
    walls_mask = np.zeros(len(p), dtype=bool)
    for mask in (wall_masks(positions, d).values() if walls else ()):
        walls_mask |= mask
    touching = set(np.unique(grain[walls_mask]).tolist())
    present = set(np.unique(grain).tolist())
    order = np.argsort(np.linalg.norm(seeds - 0.5 * (lo + hi), axis=1))
    inner = [int(g) for g in order if g in present and g not in touching]
    outer = [int(g) for g in order if g in present and g in touching]
    chosen = (inner + outer)[:count]
    if len(chosen) < count:
        raise ValueError(f"only {len(chosen)} grains have particles: need {count} growing "
                         "ones and one more (use more grains or fewer expanding ones)")
    return sorted(chosen)


@dataclass
class SceneModel:
    """The particles of a scene with their grain ids and stiffness factors (and strength
    factors, None unless the scene's matrix_strength differs from 1)."""

    lattice: Lattice
    grain: np.ndarray
    stiffness: np.ndarray
    expanding: list[int]
    strength: np.ndarray | None = None


def grain_model(scene: Scene) -> GrainModel:
    """The scene's grains as a :class:`bonded_lattice.grains.GrainModel`: a competent layer
    across the middle of the box (normal to y; parallel to x, so periodic along x by
    construction), or Voronoi grains with Gaussian stiffness factors (mean 1), periodic in x
    and y in a periodic box."""
    if scene.kind.startswith("layer"):
        return GrainModel("layer", layer_thickness=scene.layer_thickness * scene.height,
                          layer_contrast=scene.layer_contrast, layer_axis="y", seed=scene.seed)
    periodic = scene.boundary == "periodic"
    return GrainModel("voronoi", n_grains=scene.n_grains, stiffness_sd=scene.stiffness_sd,
                      seed=scene.seed, periodic=(periodic, periodic))


def build_model(scene: Scene) -> SceneModel:
    """Lattice, grain ids and stiffness (and strength) factors of a scene
    (:func:`bonded_lattice.grains.grain_arrays` of :func:`grain_model`)."""
    periodic = scene.boundary == "periodic"
    lat = box_lattice(scene.n_x, scene.rows, scene.d, periodic)
    box = grain_box(lat, periodic)
    grain, stiffness = grain_arrays(lat.positions, scene.d, grain_model(scene), box=box)
    expanding: list[int] = []
    if scene.kind == "expanding":
        expanding = expanding_grains(grain, lat.positions, scene.d, scene.n_grains, scene.seed,
                                     scene.n_expanding, box=box, walls=not periodic)
    strength = None
    if scene.matrix_strength != 1.0:    # the layer's particles are grain 1, the matrix's 0
        strength = np.where(grain == 0, scene.matrix_strength, 1.0)
    return SceneModel(lat, grain, stiffness, expanding, strength)
