"""A Mike/Elle scene's particles: the box lattice, its wall rows and its grains.

:func:`build_model` lays out the lattice of a :class:`bonded_lattice.scene_definition.Scene`
(:func:`box_lattice`), gives it the grain ids and stiffness factors of
:func:`bonded_lattice.grains.grain_arrays` (a competent layer or Voronoi grains:
:func:`grain_model`) and picks the growing grains (:func:`expanding_grains`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .grains import GrainModel, grain_arrays, voronoi_seeds
from .lattice import Lattice
from .scene_definition import ROW, Scene


def box_lattice(n_x: int, n_y: int, d: float) -> Lattice:
    """n_x x n_y particles: rows along x at y = (j + 1/2) sqrt3/2 d... from d/2, odd rows
    shifted by d/2, so every row holds n_x particles; numbered row by row."""
    j, i = np.meshgrid(np.arange(n_y), np.arange(n_x), indexing="ij")
    pos = np.zeros((n_x * n_y, 3))
    pos[:, 0] = ((i + 0.5 * (j % 2)) * d + 0.5 * d).reshape(-1)
    pos[:, 1] = (j * ROW * d + 0.5 * d).reshape(-1)
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    # margin 2 d: the walls move out by strain x half the box, a fraction of d
    box = np.array([[lo[0] - 2 * d, hi[0] + 2 * d], [lo[1] - 2 * d, hi[1] + 2 * d],
                    [-0.5 * d, 0.5 * d]])
    return Lattice(pos, d, 2, box)


def wall_masks(positions: np.ndarray, d: float) -> dict[str, np.ndarray]:
    """The four wall rows (the deck selects the same particles with regions)."""
    x, y = positions[:, 0], positions[:, 1]
    return {"left": x < x.min() + 0.6 * d, "right": x > x.max() - 0.6 * d,
            "bottom": y < y.min() + 0.1 * d, "top": y > y.max() - 0.1 * d}


def expanding_grains(grain: np.ndarray, positions: np.ndarray, d: float, n_grains: int,
                     seed: int, count: int) -> list[int]:
    """The ``count`` grains whose Voronoi seed points lie nearest the box centre, those
    that touch no wall row first (with few grains every grain may touch a wall: then the
    nearest ones that do)."""
    p = positions[:, :2]
    lo, hi = p.min(axis=0) - 0.5 * d, p.max(axis=0) + 0.5 * d
    seeds = voronoi_seeds(lo, hi, n_grains, seed)
    walls = np.zeros(len(p), dtype=bool)
    for mask in wall_masks(positions, d).values():
        walls |= mask
    touching = set(np.unique(grain[walls]).tolist())
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
    """The particles of a scene with their grain ids and stiffness factors."""

    lattice: Lattice
    grain: np.ndarray
    stiffness: np.ndarray
    expanding: list[int]


def grain_model(scene: Scene) -> GrainModel:
    """The scene's grains as a :class:`bonded_lattice.grains.GrainModel`: a competent layer
    across the middle of the box (normal to y), or Voronoi grains with Gaussian stiffness
    factors (mean 1)."""
    if scene.kind.startswith("layer"):
        return GrainModel("layer", layer_thickness=scene.layer_thickness * scene.height,
                          layer_contrast=scene.layer_contrast, layer_axis="y", seed=scene.seed)
    return GrainModel("voronoi", n_grains=scene.n_grains, stiffness_sd=scene.stiffness_sd,
                      seed=scene.seed)


def build_model(scene: Scene) -> SceneModel:
    """Lattice, grain ids and stiffness factors of a scene
    (:func:`bonded_lattice.grains.grain_arrays` of :func:`grain_model`)."""
    lat = box_lattice(scene.n_x, scene.rows, scene.d)
    grain, stiffness = grain_arrays(lat.positions, scene.d, grain_model(scene))
    expanding: list[int] = []
    if scene.kind == "expanding":
        expanding = expanding_grains(grain, lat.positions, scene.d, scene.n_grains, scene.seed,
                                     scene.n_expanding)
    return SceneModel(lat, grain, stiffness, expanding)
