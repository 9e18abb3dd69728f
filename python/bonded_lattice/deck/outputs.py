"""Outputs of a deck: bond counts, per-atom and per-bond records, the energy budget, thermo.

- ``compute bonds`` (lattice/bonds): the global counts :data:`BOND_COUNTS` (intact, broken
  in tension, broken in shear, contacts);
- per atom (:func:`atom_bond_counts`): intact bonds, bonds broken in tension and in shear,
  the columns :data:`ATOM_DUMP_COLUMNS` of the atom dumps (read by
  :func:`bonded_lattice.io.read_atom_dump`);
- per bond (:func:`bond_records`): ``compute bl`` (lattice/bond/local) with the columns
  id1 id2 state x y z, dumped as :data:`BOND_RECORDS` (read by
  :func:`bonded_lattice.io.read_bond_dump`);
- :func:`energy_budget`: ``compute energy`` (lattice/energy) and its ten thermo columns;
- :func:`thermo`: the thermo table.
"""

from __future__ import annotations

BOND_COUNTS = "c_bonds[1] c_bonds[2] c_bonds[3] c_bonds[4]"
ATOM_DUMP_COLUMNS = "id type x y z c_nbonds c_ntension c_nshear"
BOND_RECORDS = "c_bl[*]"
ENERGY_TERMS = 10


def bond_counts() -> str:
    """``compute bonds``: the global bond counts (:data:`BOND_COUNTS`)."""
    return "compute         bonds all lattice/bonds\n"


def atom_bond_counts() -> str:
    """Per-atom bond counts for the atom dumps (:data:`ATOM_DUMP_COLUMNS`)."""
    return ("compute         nbonds all lattice/bonds\n"
            "compute         ntension all lattice/bonds peratom tension\n"
            "compute         nshear all lattice/bonds peratom shear\n")


def bond_records() -> str:
    """``compute bl``: one record per bond (id1 id2 state x y z) for ``dump local``."""
    return "compute         bl all lattice/bond/local id1 id2 state x y z\n"


def energy_budget(work: str = "") -> tuple[str, str]:
    """``compute energy`` (lattice/energy) and its thermo columns (each with a leading space).

    work: groups whose prescribed motion does external work (``compute lattice/energy
    ... work GROUPS``), e.g. ``"top bottom"``.  The compute must follow the fixes that add
    forces.
    """
    groups = f" work {work}" if work else ""
    text = ("# energy budget: elastic, kinetic, gravity, viscous heat, breaking heat (normal,\n"
            "# shear), frictional heat, external work, total, balance error\n"
            f"compute         energy all lattice/energy{groups}\n")
    return text, "".join(f" c_energy[{k}]" for k in range(1, ENERGY_TERMS + 1))


def thermo(columns: str, every: int, flush: bool = False) -> str:
    """``thermo_style custom COLUMNS``, totals (``norm no``), every ``every`` steps."""
    modify = "norm no flush yes" if flush else "norm no"
    return (f"thermo_style    custom {columns}\n"
            f"thermo_modify   {modify}\n"
            f"thermo          {every}\n")
