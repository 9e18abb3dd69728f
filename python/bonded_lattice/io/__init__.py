"""Readers of the files LAMMPS writes for the package: one reader per file format.

- :mod:`.dump`: text dumps of atoms (``dump custom``, ``write_dump``; one frame, or a
  trajectory through MDAnalysis) and of local quantities (``dump local`` of
  ``compute lattice/bond/local``, the bond dumps: :func:`read_bond_dump`);
- :mod:`.thermo`: the thermo tables of a LAMMPS screen output or log file;
- :mod:`.ave_time`: the files of ``fix ave/time ... file`` (the decks' ``breaking.dat``);
- :mod:`.table`: tables with a ``# name ...`` header line (the scene decks' ``scene.dat``);
- :mod:`.data`: the sections of a data file that :func:`bonded_lattice.lattice.write_data`
  adds (``Grains``).

The library, the benchmarks and the tests read these files through these functions only.
"""

from .ave_time import read_ave_time
from .data import GRAINS_SECTION, read_grain_strengths, read_grains
from .dump import (read_atom_dump, read_atom_frame, read_bond_dump, read_frames,
                   read_local_dump)
from .table import read_table
from .thermo import Thermo, parse_thermo, read_thermo

__all__ = ["GRAINS_SECTION", "Thermo", "parse_thermo", "read_atom_dump", "read_atom_frame",
           "read_ave_time",
           "read_bond_dump", "read_frames", "read_grain_strengths", "read_grains", "read_local_dump", "read_table",
           "read_thermo"]
