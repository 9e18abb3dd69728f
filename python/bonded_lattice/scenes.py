"""The Mike/Elle scenes: a 2D central-spring lattice in a deformation box.

The seed's model (issue 7): a triangular lattice of particles joined by
central springs (``Ks = 0``, ``mu_p = 0``) that break in tension and then
only repel, inside a "deformation box": a row of wall particles on each of
the four sides, held perpendicular to its wall and free to slide along it
(frictionless walls).  Scenes (:data:`KINDS`):

- ``layer-extension``, ``layer-compression``: a competent (stiffer) layer in
  a weak matrix (:func:`bonded_lattice.grains.competent_layer`), layer
  parallel to x, pure shear along the layer: x scaled by (1 + e), y by
  1/(1 + e) (extension) or the reverse (compression);
- ``polycrystal``: Voronoi grains with Gaussian stiffness factors and
  uniform bond strengths, weak grain boundaries, pure shear (x extended);
- ``expanding``: Voronoi grains of which a few near the centre grow (their
  particles' diameters, hence the rest lengths r_i + r_j of their bonds,
  increase step by step), the walls held.

Two loadings (:data:`MODES`):

- ``quasistatic``: the seed's loop in LAMMPS: a strain step by ``change_box
  ... remap`` (the affine pre-displacement) or a diameter step, then
  ``lattice/quasistatic ftol F break one`` (FIRE), repeated;
- ``dynamic``: the walls move at a constant strain rate (their normal
  velocity held: ``fix setforce`` zeroes the normal force), the lattice
  integrated by ``fix lattice/nve`` and damped by ``fix lattice/viscous``;
  the pair style breaks bonds as it goes.  The expanding grains grow at a
  constant rate (``fix adapt``).

The wall reaction is the force ``fix setforce`` removes (its global vector),
so the wall stress is the same quantity in both modes.  Every deck writes
``scene.dat``: one line per strain step (quasi-static) or per output interval
(dynamic) with the cumulative step count (time steps, or minimiser
iterations), the wall strains, the wall stresses and the bond counts; and
``bonds.final.txt``, a ``dump local`` of ``compute lattice/bond/local id1
id2 state x y z``.  With ``bond_dumps`` > 0 it also writes that dump every
few strain steps (``bonds.<step>.txt``), from which :func:`break_steps`
dates each broken bond; with ``break_order`` > 0 (quasi-static) it also writes it after each
of the first breaks (``break.<n>.txt``), from which :func:`break_sequence` gives their exact
order.

With ``boundary="periodic"`` the box is periodic in x and y instead, with no walls: the
lattice fills its periodic cell, the strain steps are the same ``change_box ... remap``, and
the stresses are minus the virial pressure tensor (``compute pressure NULL virial``).

The scenes are made in layers, one module each: the definition
(:mod:`bonded_lattice.scene_definition`: :class:`Scene`, :func:`central_spring_bond`), the
particles and grains (:mod:`bonded_lattice.scene_model`: :func:`build_model`), the deck and
data file (:mod:`bonded_lattice.scene_deck`: :func:`write_scene`, from the sections of
:mod:`bonded_lattice.deck`) and what a finished run shows
(:mod:`bonded_lattice.scene_analysis`); :mod:`bonded_lattice.scene_study` runs, measures and
plots a scene (:class:`~bonded_lattice.scene_study.SceneStudy`).  This module keeps every name
of the first four importable from here.
"""

from __future__ import annotations

from .io.dump import read_bond_dump
from .scene_analysis import (bond_angles, break_sequence, break_steps, broken_bonds,
                             crack_normal_stats, edge_distance, first_breaks_near_edges,
                             relaxation_costs)
from .scene_deck import (ATOMIC_SAVING_PER_PARTICLE, BYTES_PER_PARTICLE, BYTES_PER_RANK,
                         DATA_FILE, SCENE_COLUMNS, TITLES, deck_text, expected_memory,
                         read_scene_dat, resume_deck, scene_title, write_scene)
from .scene_definition import (BOUNDARIES, DEFAULT_FTOL, DEFORMATIONS, KINDS, MODES, RELAXATIONS,
                               ROW, SQRT3, Scene, central_spring_bond, plane_moduli)
from .scene_model import (SceneModel, box_lattice, box_period, build_model, expanding_grains,
                          grain_box, grain_model, lattice_bond_ids, periodic_pairs, wall_masks)

__all__ = ["ATOMIC_SAVING_PER_PARTICLE", "BOUNDARIES", "BYTES_PER_PARTICLE", "BYTES_PER_RANK",
           "DATA_FILE", "DEFAULT_FTOL", "DEFORMATIONS", "KINDS", "MODES", "RELAXATIONS", "ROW",
           "SCENE_COLUMNS", "SQRT3", "TITLES", "Scene", "SceneModel", "bond_angles", "box_lattice",
           "box_period", "break_sequence", "break_steps", "broken_bonds", "build_model",
           "central_spring_bond", "crack_normal_stats", "deck_text", "edge_distance",
           "expanding_grains", "expected_memory", "first_breaks_near_edges", "grain_box",
           "grain_model", "lattice_bond_ids", "periodic_pairs", "plane_moduli", "read_bond_dump",
           "read_scene_dat", "relaxation_costs", "resume_deck", "scene_title", "wall_masks",
           "write_scene"]

