"""A heterogeneous block's grains and bond strengths, as the decks and data files take them.

:class:`GrainModel` says where a block's grains come from and :func:`grain_arrays` makes
its per-particle grain ids and stiffness factors (the data file's Grains section);
:class:`GrainPairOptions` holds the pair style's strength keywords.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..io.elle import read_elle, read_elle_cell
from ..io.polygons import read_polygons
from .checks import (check_axis, check_n_grains, check_points, check_seed, check_stiffness_distribution,
                     check_strength)
from .layers import competent_layer
from .polygons import map_polygons, polygon_grains
from .stiffness import particle_stiffness
from .voronoi import voronoi_grains


@dataclass(frozen=True)
class GrainPairOptions:
    """The ``pair_style lattice/bond`` keywords of a heterogeneous model.

    strength_min, strength_max: each bond's breaking thresholds are the
        pair_coeff's times a factor drawn uniformly in [min, max] (in C++, from
        a hash of seed and the two atom tags: the same on any number of ranks);
    boundary_strength: extra factor for bonds whose particles are in different
        grains (the seed's models: 0.5);
    seed: of the strength draws;
    particle_strength: the data file also gives each particle a strength factor
        (``d_strength``, a bond takes the mean of its particles'; keyword
        ``strength_factor``).
    The stiffness factors come from the data file (``d_stiffness``); the C++
    side defines the keywords (docs/pair_lattice_bond.rst).
    """

    strength_min: float = 1.0
    strength_max: float = 1.0
    seed: int = 1
    boundary_strength: float = 0.5
    particle_strength: bool = False

    def __post_init__(self) -> None:
        check_strength(self.strength_min, self.strength_max, self.boundary_strength)
        check_seed(self.seed)

    def pair_style_args(self) -> str:
        """``grain i_grain stiffness d_stiffness strength MIN MAX seed S boundary_strength F``
        (and ``strength_factor d_strength``)."""
        extra = " strength_factor d_strength" if self.particle_strength else ""
        return (f"grain i_grain stiffness d_stiffness strength {self.strength_min!r} "
                f"{self.strength_max!r} seed {self.seed} "
                f"boundary_strength {self.boundary_strength!r}{extra}")

    def properties(self) -> str:
        """The per-atom properties of the data file's Grains section, in its column order
        (``fix property/atom``)."""
        return "i_grain d_stiffness" + (" d_strength" if self.particle_strength else "")


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
            check_axis(self.layer_axis)
            if not (self.layer_thickness > 0 and math.isfinite(self.layer_thickness)):
                raise ValueError(f"layer_thickness = {self.layer_thickness} is out of range: "
                                 "need 0 < layer_thickness < inf")
            if not (self.layer_contrast > 0 and math.isfinite(self.layer_contrast)):
                raise ValueError(f"layer_contrast = {self.layer_contrast} is out of range: "
                                 "need 0 < layer_contrast < inf")


def grain_arrays(positions: np.ndarray, d: float, model: GrainModel,
                 box: tuple[Sequence[float], Sequence[float]] | None = None
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Grain id and stiffness factor of every particle of a block, for the data file.

    positions: (n, 2 or 3) particle centres; d: particle diameter.  The
    block's rectangle is the particles' outer extent (centres +- d/2), or
    ``box`` = (lo, hi) in x and y if given (a periodic box: its cell, so
    that periodic Voronoi grains repeat with the box): the Voronoi points
    fill it, the Elle unit cell is mapped onto it, the layer is centred on
    the particles.
    """
    p = check_points(positions, 2)
    if not (d > 0 and math.isfinite(d)):
        raise ValueError(f"d = {d} is out of range: need 0 < d < inf")
    if len(p) == 0:
        raise ValueError("no particles")
    full = np.asarray(positions, dtype=float)
    if box is None:
        lo, hi = p.min(axis=0) - 0.5 * d, p.max(axis=0) + 0.5 * d
    else:
        lo, hi = (np.asarray(b, dtype=float).reshape(-1)[:2] for b in box)
        if not np.all(hi > lo) or not np.all(np.isfinite(lo) & np.isfinite(hi)):
            raise ValueError(f"box = ({lo.tolist()}, {hi.tolist()}) is out of range: need "
                             "finite lo < hi in x and y")
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
        k = check_axis(model.layer_axis)
        coord = full[:, k]
        centre = 0.5 * (coord.min() + coord.max())
        grain, extra = competent_layer(full, k, centre, model.layer_thickness,
                                       model.layer_contrast)
    stiffness = particle_stiffness(grain, model.stiffness_mean, model.stiffness_sd,
                                   model.seed) * extra
    return grain, stiffness
