"""Orientation of the blocks to the load: the turned 3D block, the choice of how the ends are
loaded (platens or held end layers), the decks that choice writes, and the closed forms of
the anisotropy section (:mod:`bonded_lattice.validation.anisotropy`)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bonded_lattice.cli import main
from bonded_lattice.conversion import rock_to_bond
from bonded_lattice.decks import deck_text
from bonded_lattice.experiment import (build_lattice, choose_ends, deck_spec, end_band_particles,
                                       end_contacts, plan_test)
from bonded_lattice.lattice import close_packed_block_3d, contact_pairs, turned_block_3d
from bonded_lattice.validation.anisotropy import (affine_tu_2d, bulk_3d_elastic,
                                                  lattice_direction, mirror_angle)
from helpers.materials import D, QUARTZ_ROCK

ROCK = QUARTZ_ROCK


def _bond_axes(lattice):
    pairs = contact_pairs(lattice)
    sep = lattice.positions[pairs[:, 1]] - lattice.positions[pairs[:, 0]]
    return np.abs(sep) / lattice.d


@pytest.mark.parametrize("n_y", [2, 4, 6, 8])
def test_turned_block_keeps_the_block_and_puts_rows_along_z(n_y):
    block = close_packed_block_3d(n_y, D)
    turned = turned_block_3d(block, 90.0)
    assert turned.n == block.n
    assert len(contact_pairs(turned)) == len(contact_pairs(block))
    assert turned.positions.min(axis=0) == pytest.approx([0.5 * D] * 3, abs=1e-12)
    # the bonds along the rows (y, one diameter) now lie along z, the loading axis
    rows_before = np.count_nonzero(np.isclose(_bond_axes(block)[:, 1], 1.0, atol=1e-9))
    rows_after = np.count_nonzero(np.isclose(_bond_axes(turned)[:, 2], 1.0, atol=1e-9))
    assert rows_after == rows_before > 0
    # the papers' block has no bond along z (its layers lie across it)
    assert not np.any(np.isclose(_bond_axes(block)[:, 2], 1.0, atol=1e-9))
    assert turned_block_3d(block, 0.0) is block


@pytest.mark.parametrize("orientation", [45.0, -90.0, 30.0, math.nan])
def test_turned_block_refuses_other_angles(orientation):
    with pytest.raises(ValueError, match="orientation"):
        build_lattice(3, 6, D, orientation)


def test_turned_block_refuses_2d():
    with pytest.raises(ValueError, match="dim"):
        turned_block_3d(build_lattice(2, 8, D), 90.0)


@pytest.mark.parametrize("dim,n", [(2, 2), (2, 4), (2, 8), (2, 15), (3, 2), (3, 4), (3, 6),
                                   (3, 8)])
def test_papers_blocks_keep_their_platens(dim, n):
    lattice = build_lattice(dim, n, D)
    assert end_contacts(lattice) == end_band_particles(lattice)
    for test in ("compression", "elastic", "confined"):
        assert choose_ends(lattice, test) == "platens"


@pytest.mark.parametrize("dim,n,orientation", [(2, 15, 5.0), (2, 15, 20.0), (2, 15, 30.0),
                                               (2, 8, 40.0), (3, 6, 90.0)])
def test_stepped_ends_are_held(dim, n, orientation):
    lattice = build_lattice(dim, n, D, orientation)
    # a platen touches the lowest particles of the steps only
    assert end_contacts(lattice) < end_band_particles(lattice)
    assert choose_ends(lattice, "compression") == "layers"
    assert choose_ends(lattice, "compression", "platens") == "platens"
    assert choose_ends(lattice, "tension") == "platens"   # tension always holds its ends


def test_unknown_ends_are_refused():
    with pytest.raises(ValueError, match="ends = 'glued'"):
        choose_ends(build_lattice(2, 8, D), "compression", "glued")


def _deck(test: str, ends: str, orientation: float = 20.0) -> str:
    lattice = build_lattice(2, 8, D, orientation)
    bond = rock_to_bond(ROCK.E, ROCK.nu, ROCK.Tu, ROCK.Cu, ROCK.mu_i, D, 2)
    plan = plan_test(ROCK, bond, lattice, test, confining=5e6 if test == "confined" else 0.0)
    return deck_text(deck_spec(plan, test, 2, bond, 5e6 if test == "confined" else 0.0,
                               ends=ends))


@pytest.mark.parametrize("test", ["compression", "elastic", "confined"])
def test_held_ends_push_the_end_layers_together(test):
    held, platens = _deck(test, "layers"), _deck(test, "platens")
    assert "fix             ptop top move linear NULL -" in held
    assert "fix             pbot bottom move linear NULL " in held
    assert "lattice/wall ylo" not in held and "lattice/wall ylo" in platens
    assert ("servo" in held) == (test == "confined")   # the side walls stay


def test_tension_deck_does_not_depend_on_ends():
    assert _deck("tension", "layers") == _deck("tension", "platens")


def test_deck_refuses_unknown_ends():
    with pytest.raises(ValueError, match="ends"):
        _deck("compression", "glued")


@pytest.mark.parametrize("angle,inside", [(0.0, 0.0), (20.0, 20.0), (40.0, 20.0),
                                          (-20.0, 20.0), (80.0, 20.0), (30.0, 30.0),
                                          (90.0, 30.0), (55.0, 5.0)])
def test_mirror_angle(angle, inside):
    assert mirror_angle(angle) == pytest.approx(inside)


@pytest.mark.parametrize("angle,direction", [(0.0, 90.0), (30.0, 60.0), (40.0, 50.0),
                                             (-60.0, 150.0), (60.0, 30.0)])
def test_lattice_direction(angle, direction):
    # the paper's formula directions 90, 30 and 150 degrees are orientations 0, 60, -60
    assert lattice_direction(angle) == pytest.approx(direction)


def test_affine_tensile_strength():
    E, nu, xb = ROCK.E, ROCK.nu, 1.9e-7
    # orientation 0: the bonds at 60 and 120 degrees to x stretch by (3/4 - nu/4) of the
    # axial strain; orientation 30: the bond along the load by all of it
    assert affine_tu_2d(0.0, E, nu, xb, D) == pytest.approx(E * xb / (D * (0.75 - 0.25 * nu)))
    assert affine_tu_2d(30.0, E, nu, xb, D) == pytest.approx(E * xb / D)
    assert affine_tu_2d(80.0, E, nu, xb, D) == pytest.approx(affine_tu_2d(20.0, E, nu, xb, D))
    assert affine_tu_2d(-20.0, E, nu, xb, D) == pytest.approx(affine_tu_2d(20.0, E, nu, xb, D))
    with pytest.raises(ValueError, match="nu"):
        affine_tu_2d(0.0, E, 0.5, xb, D)
    with pytest.raises(ValueError, match="Xb"):
        affine_tu_2d(0.0, E, nu, -xb, D)


def test_unbounded_3d_lattice_meets_the_formulas_across_its_layers():
    # the 2017 formulas are those of the lattice loaded across its layers: the unbounded
    # lattice's E and nu there equal the rock's to rounding
    bulk = bulk_3d_elastic(ROCK.E, ROCK.nu, ROCK.Tu, ROCK.Cu, ROCK.mu_i)
    assert bulk["E_across_layers"] == pytest.approx(0.0, abs=1e-9)
    assert bulk["nu_across_layers"] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("args,held", [(["--dim", "2", "--orientation", "20"], True),
                                       (["--dim", "2", "--orientation", "20", "--ends",
                                         "platens"], False),
                                       (["--dim", "2"], False),
                                       (["--dim", "3", "--orientation", "90"], True)])
def test_generate_writes_the_chosen_ends(tmp_path, args, held):
    assert main(["generate", "--n", "4", "--test", "compression", "--out", str(tmp_path),
                 *args]) == 0
    deck = (tmp_path / "in.compression").read_text()
    assert ("fix             ptop top move" in deck) == held
    assert ("lattice/wall" in deck) == (not held)
