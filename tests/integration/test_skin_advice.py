"""The pair style warns once, with the line to add, when the neighbour skin leaves every
particle with tens of unbonded candidate pairs (LAMMPS' default skin in SI units is 0.001 m,
a whole diameter of a 1 mm particle); with a skin of a tenth of a diameter it stays quiet."""

from __future__ import annotations


import pytest
from helpers.decks import run_deck, shaken_block
from helpers.materials import D, QUARTZ_3D

ADVICE = "pair_style lattice/bond: the neighbor skin"


def deck(neighbor: str) -> str:
    return shaken_block(3) + f"""
pair_style      lattice/bond
pair_coeff      * * {QUARTZ_3D}
{neighbor}
fix             nve all lattice/nve
timestep        1e-8
run             10
run             10
"""


def test_default_skin_gets_one_warning_with_the_line_to_add(tmp_path):
    res = run_deck(deck(""), tmp_path)
    assert res.returncode == 0, res.error
    # once for the two runs, naming the skin, its size in diameters and the line to add
    assert res.output.count(ADVICE) == 1, res.output
    line = next(l for l in res.output.splitlines() if ADVICE in l)
    assert "the neighbor skin 0.001 is 1 particle diameters" in line
    assert f"For this model add: neighbor {0.1 * D:.3g} bin" in line


@pytest.mark.parametrize("skin", [0.1 * D, 0.3 * D])
def test_a_short_skin_gets_no_warning(tmp_path, skin):
    res = run_deck(deck(f"neighbor {skin} bin"), tmp_path)
    assert res.returncode == 0, res.error
    assert ADVICE not in res.output
