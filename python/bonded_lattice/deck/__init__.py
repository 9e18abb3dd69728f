"""The sections every LAMMPS deck of the package is made of, shared by the rock tests
(:mod:`bonded_lattice.decks`) and the Mike/Elle scenes (:mod:`bonded_lattice.scene_deck`).

Each section is a function that returns deck text (whole lines, each ending in a newline):

- :mod:`.pair`: the pair style and its per-atom properties: ``pair_style lattice/bond``
  with the grain, stiffness and strength keywords of a heterogeneous model and the
  ``diameter`` of ``atom_style atomic`` (:class:`PairStyle`), the ``fix property/atom``
  that holds the grain ids and stiffness factors, ``pair_coeff``;
- :mod:`.opening`: units, dimension, boundary, atom style, ``read_data`` (with the
  Grains section), the pair style, the neighbour and atom-sorting settings;
- :mod:`.integrator`: ``fix lattice/nve`` and the damping ``fix lattice/viscous``;
- :mod:`.walls`: smooth platens and side walls (``fix lattice/wall``, moving or servo),
  and the rows of wall particles held by ``fix setforce`` (the scenes' deformation box);
- :mod:`.grips`: the end layers' spring grips (``fix addforce`` towards moving smooth planes)
  and the grips' names in a deck's comments;
- :mod:`.outputs`: the bond counts (``compute lattice/bonds``), the per-atom and per-bond
  records and their dumps, the energy budget (``compute lattice/energy``), thermo.

A pipeline (rock test or scene) writes its own title, measurements and loading between
these sections.
"""

from .integrator import integrator
from .opening import neighbours, opening
from .outputs import (ATOM_DUMP_COLUMNS, BOND_COUNTS, BOND_RECORDS, atom_bond_counts,
                      bond_counts, bond_records, energy_budget, thermo)
from .pair import PROPERTY_FIX, PairStyle
from .walls import smooth_wall, wall_rows

__all__ = ["ATOM_DUMP_COLUMNS", "BOND_COUNTS", "BOND_RECORDS", "PROPERTY_FIX", "PairStyle",
           "atom_bond_counts", "bond_counts", "bond_records", "energy_budget", "integrator",
           "neighbours", "opening", "smooth_wall", "thermo", "wall_rows"]
