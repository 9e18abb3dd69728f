"""The periodic box of the Mike/Elle scenes (boundary = "periodic"): the lattice fills the
periodic cell, its bonds (3 per particle, across the seam too), the periodic Voronoi grains,
the option's checks and the edge-strip statistics of the first breaks.  Pure Python."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bonded_lattice.scenes import (BOUNDARIES, ROW, Scene, box_lattice, box_period,
                                   break_sequence, build_model, deck_text, edge_distance,
                                   first_breaks_near_edges, grain_box, lattice_bond_ids,
                                   periodic_pairs)
from bonded_lattice.grains import voronoi_seeds

D = 1.0e-3


@pytest.mark.parametrize("n_x, n_y", [(5, 4), (12, 10), (40, 46)])
def test_periodic_lattice_has_three_bonds_per_particle(n_x, n_y):
    """A full triangular lattice in its periodic cell: every particle has 6 neighbours at
    exactly d, so 3 N bonds (N = n_x n_y), and the box is n_x d by n_y sqrt3/2 d."""
    lat = box_lattice(n_x, n_y, D, periodic=True)
    assert box_period(lat) == pytest.approx((n_x * D, n_y * ROW * D), rel=1e-12)
    pairs = periodic_pairs(lat)
    assert len(pairs) == 3 * n_x * n_y
    assert np.all(np.bincount(pairs.ravel(), minlength=lat.n) == 6)
    # every pair is at distance d by minimum image
    length = np.array(box_period(lat))
    sep = lat.positions[pairs[:, 1], :2] - lat.positions[pairs[:, 0], :2]
    sep -= length * np.round(sep / length)
    assert np.allclose(np.linalg.norm(sep, axis=1), D, rtol=1e-12)
    # no particle on a face of the box (LAMMPS would have to decide which image it is)
    lo, hi = lat.box[:2, 0], lat.box[:2, 1]
    assert np.all(lat.positions[:, :2] > lo + 0.2 * D) and np.all(lat.positions[:, :2] < hi)


def test_bond_ids_of_walls_and_periodic_box():
    """Walls: n_y (n_x - 1) + (2 n_x - 1)(n_y - 1) bonds (counted by hand); periodic: 3 N;
    the ids count from 1, as in the data file."""
    n_x, n_y = 8, 6
    walls = lattice_bond_ids(box_lattice(n_x, n_y, D), periodic=False)
    periodic = lattice_bond_ids(box_lattice(n_x, n_y, D, periodic=True), periodic=True)
    assert len(walls) == n_y * (n_x - 1) + (2 * n_x - 1) * (n_y - 1)
    assert len(periodic) == 3 * n_x * n_y
    for ids in (walls, periodic):
        assert ids.min() == 1 and ids.max() == n_x * n_y


def test_periodic_voronoi_grains_are_the_minimum_image_cells():
    """In a periodic box every particle is in the grain of its nearest seed point by
    minimum image (brute force over all seeds), so the grains continue across the seam;
    the seeds fill the periodic cell."""
    scene = Scene("polycrystal", n_x=24, n_grains=7, boundary="periodic", seed=3)
    model = build_model(scene)
    lo, hi = grain_box(model.lattice, periodic=True)
    seeds = voronoi_seeds(lo, hi, scene.n_grains, scene.seed)
    length = hi - lo
    sep = model.lattice.positions[:, None, :2] - seeds[None, :, :]
    sep -= length * np.round(sep / length)
    assert np.array_equal(model.grain, np.argmin((sep ** 2).sum(axis=2), axis=1))


def test_boundary_option_is_checked():
    """A bad value names the valid ones; the periodic box needs an even number of rows
    and quasi-static loading."""
    assert BOUNDARIES == ("walls", "periodic")
    with pytest.raises(ValueError, match=r"boundary = 'open' is not known: use one of "
                                         r"walls, periodic"):
        Scene("polycrystal", boundary="open")
    with pytest.raises(ValueError, match="n_y = 7 .* even number of rows"):
        Scene("polycrystal", boundary="periodic", n_y=7)
    with pytest.raises(ValueError, match="mode = 'dynamic'"):
        Scene("polycrystal", boundary="periodic", mode="dynamic")
    with pytest.raises(ValueError, match="n_y = 5 .* even number of rows"):
        box_lattice(6, 5, D, periodic=True)
    # the square box's default row count is even: allowed
    assert Scene("layer-extension", n_x=41, boundary="periodic").rows % 2 == 0


def test_periodic_deck_has_no_walls():
    """The periodic deck: boundary p p p, no wall rows or setforce fixes, the stress from
    the virial pressure tensor; the wall deck keeps its walls."""
    periodic = deck_text(Scene("polycrystal", n_x=12, n_grains=4, boundary="periodic"))
    walls = deck_text(Scene("polycrystal", n_x=12, n_grains=4))
    assert "boundary        p p p" in periodic and "boundary        f f p" in walls
    assert "setforce" not in periodic and "setforce" in walls
    assert "compute         press all pressure NULL virial" in periodic
    assert "variable        sxx equal -c_press[1]" in periodic
    assert "change_box      all x scale" in periodic


def test_edge_distance_of_constructed_bonds():
    """A 10 x 10 periodic lattice: a bond across the x seam (ids 1 and 10 of the first
    row, minimum image) is at distance 0; the horizontal bond of row 4 from particle 5 to 6
    has its midpoint at x = 5.5 d (from the first column at 0.5 d: 5 d; from the last at
    9.5 d (even row): 4 d) and y = 0.5 d + 4 sqrt3/2 d (from the first row: 4 sqrt3/2 d =
    3.46 d; from the last, row 9: 5 sqrt3/2 d): distance 2 sqrt3 d."""
    lat = box_lattice(10, 10, D, periodic=True)
    period = box_period(lat)
    pairs = np.array([[1, 10], [4 * 10 + 5, 4 * 10 + 6]])
    dist = edge_distance(pairs, lat.positions, period)
    assert dist[0] == 0.0
    assert dist[1] == pytest.approx(2 * math.sqrt(3) * D, rel=1e-12)
    # across the y seam: particle 1 (row 0, x = 0.5 d) and 91 (row 9, x = d); without
    # the period its midpoint would lie halfway up the box, 0.25 d from the first column
    seam_y = np.array([[1, 91]])
    assert edge_distance(seam_y, lat.positions, period)[0] == 0.0
    assert edge_distance(seam_y, lat.positions)[0] == pytest.approx(0.25 * D, rel=1e-12)


def _dump(path, rows):
    """A bond dump in the format of the scene decks' dump local (id1 id2 state x y z)."""
    lines = ["ITEM: TIMESTEP", "0", "ITEM: NUMBER OF ENTRIES", str(len(rows)),
             "ITEM: BOX BOUNDS pp pp pp", "0 1", "0 1", "0 1",
             "ITEM: ENTRIES c_bl[1] c_bl[2] c_bl[3] c_bl[4] c_bl[5] c_bl[6]"]
    lines += [f"{i} {j} {s} 0 0 0" for i, j, s in rows]
    path.write_text("\n".join(lines) + "\n")


SEAM, INNER, SEAM2 = (1, 10), (45, 46), (11, 20)   # bonds of the 10 x 10 periodic lattice


def _breaking(folder, prefix: str, order: list) -> tuple:
    """Dumps ``<prefix>.1.txt`` ... of a 10 x 10 periodic lattice in which the bonds of
    ``order`` break one per dump; returns the lattice, its period and its bond ids."""
    for k in range(1, len(order) + 1):
        _dump(folder / f"{prefix}.{k}.txt", [(*b, int(n < k)) for n, b in enumerate(order)])
    lat = box_lattice(10, 10, D, periodic=True)
    return lat, box_period(lat), lattice_bond_ids(lat, periodic=True)


def test_first_breaks_near_edges_of_a_constructed_run(tmp_path):
    """Three strain steps' dumps of a 10 x 10 periodic lattice: step 1 breaks the seam
    bond (1, 10) (distance 0), step 2 the inner bond (45, 46) (2 sqrt3 d = 3.46 d, outside a
    3 d strip), step 3 one more seam bond.  The first 2 breaks: steps 1-2, half of them
    within 3 d; the first 1: step 1 only, all of them.  The expected share is the strip's
    share of all 300 bonds, counted here by brute force."""
    lat, period, bonds = _breaking(tmp_path, "bonds", [SEAM, INNER, SEAM2])
    two = first_breaks_near_edges(tmp_path, lat.positions, bonds, D, count=2, period=period)
    assert (two["order"], two["n"], two["step"], two["near"]) == ("step", 2, 2, 0.5)
    one = first_breaks_near_edges(tmp_path, lat.positions, bonds, D, count=1, period=period)
    assert (one["n"], one["step"], one["near"]) == (1, 1, 1.0)
    p = lat.positions[:, :2]
    lo, hi = p.min(axis=0), p.max(axis=0)
    length = np.array(period)
    near = 0
    for i, j in bonds.tolist():
        sep = p[j - 1] - p[i - 1]
        mid = p[i - 1] + 0.5 * (sep - length * np.round(sep / length))
        near += max(0.0, min(*(mid - lo), *(hi - mid))) <= 3 * D
    assert two["expected"] == pytest.approx(near / len(bonds), rel=1e-12)
    with pytest.raises(ValueError, match="count = 0"):
        first_breaks_near_edges(tmp_path, lat.positions, bonds, D, count=0)


def test_break_sequence_and_exact_first_breaks(tmp_path):
    """Dumps after each break (break.<n>.txt, as a deck with break_order writes them): the
    sequence is the bond each dump adds; first_breaks_near_edges then takes the first
    ``count`` exactly: here the inner bond (3.46 d) first, then two seam bonds (0 d)."""
    lat, period, bonds = _breaking(tmp_path, "break", [INNER, SEAM, SEAM2])
    assert break_sequence(tmp_path).tolist() == [list(INNER), list(SEAM), list(SEAM2)]
    two = first_breaks_near_edges(tmp_path, lat.positions, bonds, D, count=2, period=period)
    assert (two["order"], two["n"], two["near"]) == ("break", 2, 0.5)
    assert two["first_d"] == pytest.approx(2 * math.sqrt(3), rel=1e-12)
    # a dump that adds two broken bonds at once is not a dump per break
    _dump(tmp_path / "break.1.txt", [(*INNER, 1), (*SEAM, 1), (*SEAM2, 0)])
    with pytest.raises(ValueError, match="2 new broken bonds"):
        break_sequence(tmp_path)


def test_break_order_option():
    """break_order writes the maxbreak-1 loop into the quasi-static deck; negative values
    and dynamic loading are refused."""
    deck = deck_text(Scene("polycrystal", n_x=12, n_grains=4, break_order=50))
    assert "maxbreak 1" in deck and "write_dump all local break.${nb1}.txt" in deck
    assert "maxbreak" not in deck_text(Scene("polycrystal", n_x=12, n_grains=4))
    with pytest.raises(ValueError, match="break_order = -1 is out of range"):
        Scene("polycrystal", break_order=-1)
    with pytest.raises(ValueError, match="break_order = 5 with mode = 'dynamic'"):
        Scene("polycrystal", break_order=5, mode="dynamic")
