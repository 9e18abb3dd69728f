"""The opening of a deck: the system, the data file, the pair style, the neighbour lists."""

from __future__ import annotations

from .pair import PairStyle


def neighbours(d: float) -> str:
    """Neighbour-list and atom-sorting settings for particles of diameter d."""
    return f"""# a small skin keeps the search for new contacts cheap
neighbor        {0.1 * d:.6g} bin
# neighbour and atom-sorting bins of one cutoff (LAMMPS' default of half a
# cutoff takes 8x the bins in 3D, about 20 bytes per particle each)
neigh_modify    every 1 delay 0 check yes binsize {1.1 * d:.6g}
atom_modify     sort 1000 {1.1 * d:.6g}
"""


def opening(dim: int, boundary: str, atom_style: str, data_file: str, pair: PairStyle) -> str:
    """From ``units`` to ``atom_modify``: SI units, ``newton on``, the data file read with
    its Grains section if the model has grains, the pair style and the neighbour settings.

    atom_style: as written (e.g. ``sphere 1`` for diameters that change during a run);
    the pair style's own ``atom_style`` says whether it gets the diameter.
    """
    return f"""units           si
dimension       {dim}
boundary        {boundary}
atom_style      {atom_style}
newton          on
{pair.read_data(data_file)}
{pair.text()}{neighbours(pair.d)}"""
