"""compute lattice/bonds peratom tension|shear: per-particle maps of broken bonds."""

from __future__ import annotations

import pytest
from bonded_lattice.experiment import run_test
from bonded_lattice.io import read_atom_dump
from bonded_lattice.rocks import get_rock
from helpers.decks import run_deck


@pytest.mark.mpi
def test_per_atom_broken_counts_add_up_to_the_global_counts(tmp_path):
    # a 2D compression test to failure on 2 ranks: each broken bond counts at both
    # ends, also when the partner is a ghost (reverse communication)
    s = run_test(get_rock("quartz"), 2, "compression", 8, tmp_path, np_=2, progress=False)
    names, rows = read_atom_dump(tmp_path / "dump.final")
    tension = rows[:, names.index("c_ntension")].sum()
    shear = rows[:, names.index("c_nshear")].sum()
    assert s["broken_bonds"]["tension"] > 0 and s["broken_bonds"]["shear"] > 0
    assert tension == 2 * s["broken_bonds"]["tension"]
    assert shear == 2 * s["broken_bonds"]["shear"]
    # every bond is intact, broken in tension or broken in shear
    _, first = read_atom_dump(tmp_path / "dump.initial")
    intact0 = first[:, names.index("c_nbonds")].sum()
    intact = rows[:, names.index("c_nbonds")].sum()
    assert intact + tension + shear == intact0


@pytest.mark.parametrize("args,fragment", [
    ("peratom broken", "compute lattice/bonds peratom broken is not valid: use intact, "
                       "tension or shear"),
    ("count shear", "Unknown compute lattice/bonds keyword count"),
    ("peratom", "expected compute ID group lattice/bonds [peratom intact|tension|shear]"),
])
def test_bad_peratom_keyword_is_named(tmp_path, args, fragment):
    deck = f"""
units si
atom_style sphere
region box block -1 1 -1 1 -1 1
create_box 1 box
pair_style lattice/bond
pair_coeff * * 1.0e3 0 1.0e-3 1.0 0.1
compute c all lattice/bonds {args}
"""
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    assert fragment in result.output
