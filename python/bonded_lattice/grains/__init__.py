"""Heterogeneous rock: grains, layers and per-particle stiffness factors.

The heterogeneous models of the Mike/Elle spring lattice (issue 7): every
particle belongs to a grain, each grain has its own stiffness, bonds inside a
grain and across grain boundaries break at different thresholds.  This package
makes the per-particle arrays; the pair style does the rest.  One module each:

- :mod:`.checks`: the parameter checks (seeds, grain ids, factors, boxes, axes);
- :mod:`.voronoi`: grain ids from a seeded Voronoi tessellation (:func:`voronoi_grains`);
- :mod:`.polygons`: grain ids from grain polygons (:func:`polygon_grains`,
  :func:`map_polygons`), read from Elle or plain polygon files by
  :func:`bonded_lattice.io.read_elle` and :func:`bonded_lattice.io.read_polygons`;
- :mod:`.layers`: layers (:func:`layered_grains`, :func:`competent_layer`);
- :mod:`.stiffness`: a stiffness factor per grain drawn from a Gaussian,
  deterministic per grain (:func:`grain_stiffness`, :func:`particle_stiffness`);
- :mod:`.model`: a block's grains and factors from one description
  (:class:`GrainModel`, :func:`grain_arrays`) and the options of ``pair_style
  lattice/bond`` that use them (:class:`GrainPairOptions`): per-bond strength
  factors drawn uniformly in C++ from a hash of the seed and the two atom tags,
  weakened across grain boundaries.

The arrays go into the data file's ``Grains`` section
(:func:`bonded_lattice.lattice.write_data`), read by LAMMPS' own
``fix property/atom i_grain d_stiffness`` (:mod:`bonded_lattice.deck.pair`).

Every function checks its parameters and raises ``ValueError`` naming the
value and its valid range.
"""

from ..io.elle import read_elle, read_elle_cell
from ..io.polygons import Polygon, read_polygons
from .checks import (AXES, MAX_GRAIN, MAX_SEED, check_grain_ids, check_n_grains, check_seed,
                     check_stiffness_distribution, check_stiffness_factors, check_strength)
from .layers import competent_layer, layered_grains
from .model import SOURCES, GrainModel, GrainPairOptions, grain_arrays
from .polygons import map_polygons, points_in_polygon, polygon_grains
from .stiffness import MAX_REDRAWS, grain_stiffness, particle_stiffness
from .voronoi import CHUNK_ELEMENTS, nearest_seed, voronoi_grains, voronoi_seeds

__all__ = ["AXES", "CHUNK_ELEMENTS", "MAX_GRAIN", "MAX_REDRAWS", "MAX_SEED", "SOURCES",
           "GrainModel", "GrainPairOptions", "Polygon", "check_grain_ids", "check_n_grains",
           "check_seed", "check_stiffness_distribution", "check_stiffness_factors",
           "check_strength", "competent_layer", "grain_arrays", "grain_stiffness",
           "layered_grains", "map_polygons", "nearest_seed", "particle_stiffness",
           "points_in_polygon", "polygon_grains", "read_elle", "read_elle_cell",
           "read_polygons", "voronoi_grains", "voronoi_seeds"]
