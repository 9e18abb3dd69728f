"""The shared deck sections (bonded_lattice.deck) and the readers the scene modules use.

The rock tests' decks and the scenes' decks must write their common sections through the
one builder: the same opening text appears verbatim in both.
"""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.conversion import BondParameters
from bonded_lattice.deck import PairStyle, integrator, opening, smooth_wall, thermo
from bonded_lattice.decks import DeckSpec, deck_text
from bonded_lattice.grains import GrainPairOptions
from bonded_lattice.io import read_bond_dump, read_table
from bonded_lattice.scenes import Scene, read_scene_dat
from bonded_lattice.scenes import deck_text as scene_deck_text
from helpers.materials import D


@pytest.mark.parametrize("atom_style", ["sphere", "atomic"])
def test_rock_test_and_scene_share_the_opening(atom_style):
    scene = Scene("polycrystal", n_x=12, n_grains=3, atom_style=atom_style)
    spec = DeckSpec(test="compression", dim=2, d=D, bond=scene.bond, data_file="data.scene",
                    area=1e-2, eta=1.0, speed=0.01, steps=10, grains=scene.pair_options(),
                    atom_style=atom_style)
    shared = opening(2, "f f p", atom_style, "data.scene",
                     PairStyle(scene.bond, D, atom_style, scene.pair_options()))
    assert shared in deck_text(spec)
    assert shared in scene_deck_text(scene)
    assert "fix             grains all property/atom i_grain d_stiffness ghost yes\n" in shared
    assert ("diameter 0.001" in shared) == (atom_style == "atomic")


def test_pair_style_keywords():
    bond = BondParameters(1e10, 1e9, 1e-7, 1e4, 0.2)
    assert PairStyle(bond, D).keywords() == ""
    pair = PairStyle(bond, D, "atomic", GrainPairOptions(0.5, 1.5, 4711, 0.4), "corotational")
    assert pair.keywords() == (" grain i_grain stiffness d_stiffness strength 0.5 1.5 seed 4711 "
                               f"boundary_strength 0.4 diameter {D!r} shear_frame corotational")
    assert "uniform in [0.5, 1.5), x 0.4 across grain boundaries" in pair.text()
    assert pair.read_data("x.data").endswith("read_data       x.data fix grains NULL Grains\n")
    assert PairStyle(bond, D).read_data("x.data") == "read_data       x.data\n"
    with pytest.raises(ValueError, match="shear_frame = 'rotating'"):
        PairStyle(bond, D, shear_frame="rotating")


def test_sections_text():
    assert integrator("inner", 2.5) == (
        "fix             integrate inner lattice/nve    # velocity Verlet; in 2D x and y only\n"
        "fix             damp inner lattice/viscous 2.5\n")
    assert "fix             damp inner lattice/viscous" in integrator("all", 1.0, "inner")
    assert smooth_wall("top", "yhi", "v_wtop", 2e10) == \
        "fix             top all lattice/wall yhi v_wtop 2e+10 0 0\n"
    assert smooth_wall("s", "xlo", "0.0", 1.0, "servo 5e6 0.01").endswith(" 1 0 0 servo 5e6 0.01\n")
    assert thermo("step ke", 10, flush=True).splitlines() == [
        "thermo_style    custom step ke", "thermo_modify   norm no flush yes", "thermo          10"]


def test_read_table(tmp_path):
    path = tmp_path / "scene.dat"
    names = ("k", "step", "exx", "eyy", "sxx", "syy", "intact", "tension", "shear",
             "contacts", "growth")
    path.write_text("# " + " ".join(names) + "\n0 0 0 0 0 0 10 0 0 0 0\n"
                    "1 100 1e-4 -1e-4 2e5 -1e5 9 1 0 0 0\n")
    dat = read_scene_dat(path)
    assert list(dat) == list(names)
    assert np.array_equal(dat["step"], [0, 100]) and dat["tension"][-1] == 1
    with pytest.raises(ValueError, match="need \\['a', 'b'\\]"):
        read_table(path, ("a", "b"))
    (tmp_path / "bare.dat").write_text("1 2\n")
    with pytest.raises(ValueError, match="header"):
        read_table(tmp_path / "bare.dat")
    (tmp_path / "short.dat").write_text("# a b c\n1 2\n")
    with pytest.raises(ValueError, match="2 values per line for the 3 columns"):
        read_table(tmp_path / "short.dat")


def test_read_bond_dump_without_bonds(tmp_path):
    path = tmp_path / "bonds.final.txt"
    path.write_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ENTRIES\n0\nITEM: BOX BOUNDS ff ff pp\n"
                    "0 1\n0 1\n0 1\nITEM: ENTRIES c_bl[1] c_bl[2] c_bl[3] c_bl[4] c_bl[5] "
                    "c_bl[6]\n")
    assert read_bond_dump(path).shape == (0, 6)
