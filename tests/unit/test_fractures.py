"""Fractures of constructed broken-bond sets with known answers (bonded_lattice.fractures).

The lattice is the scenes' (``scenes.box_lattice``: rows along x at y = j sqrt3/2 d + d/2,
particle i of row j at x = (i + 1/2 + (j mod 2)/2) d); cracks are made by breaking
every lattice bond that crosses a line segment.  Positions are exact multiples of d/2 and
sqrt3/2 d, so the known answers hold to rounding (tolerances 1e-12 relative).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bonded_lattice.fractures import (bond_midpoints, fracture_labels, intergranular_fraction,
                                      layer_fractures, radial_fractures)
from bonded_lattice.lattice import contact_pairs
from bonded_lattice.scene_study import fracture_summary
from bonded_lattice.scenes import ROW, Scene, box_lattice, build_model

D = 1.0e-3


def lattice(n_x: int, n_y: int):
    lat = box_lattice(n_x, n_y, D)
    return lat.positions, contact_pairs(lat) + 1      # 1-based ids, as in the bond dumps


def crossing(pos: np.ndarray, bonds: np.ndarray, a, b) -> np.ndarray:
    """The bonds whose segment crosses the segment a-b (a proper crossing)."""
    p, q = pos[bonds[:, 0] - 1, :2], pos[bonds[:, 1] - 1, :2]
    a, b = np.asarray(a, float), np.asarray(b, float)

    def side(u, v, w):
        return np.sign((v[..., 0] - u[..., 0]) * (w[..., 1] - u[..., 1])
                       - (v[..., 1] - u[..., 1]) * (w[..., 0] - u[..., 0]))

    hit = (side(a, b, p) * side(a, b, q) < 0) & (side(p, q, a) * side(p, q, b) < 0)
    return bonds[hit]


def vertical(pos, bonds, x, y0, y1):
    return crossing(pos, bonds, (x, y0), (x, y1))


def row_y(j: float) -> float:
    """y of row j (fractional j: between rows)."""
    return (j * ROW + 0.5) * D


def layer_mask(pos, first_row: int, rows: int) -> np.ndarray:
    j = np.round((pos[:, 1] - 0.5 * D) / (ROW * D)).astype(int)
    return (j >= first_row) & (j < first_row + rows)


# ---------------------------------------------------------------- grouping


def test_straight_crack_is_one_fracture_and_two_cracks_two_apart_are_two():
    pos, bonds = lattice(20, 12)
    top = pos[:, 1].max() + D
    a = vertical(pos, bonds, 5.25 * D, 0.0, top)
    b = vertical(pos, bonds, 7.25 * D, 0.0, top)   # two bonds further: distinct
    # a vertical line crosses every row's bond and every gap's diagonal: 12 + 11 bonds
    assert len(a) == len(b) == 2 * 12 - 1
    labels = fracture_labels(np.vstack([a, b]), pos, D)
    assert labels[:len(a)].tolist() == [0] * len(a)
    assert labels[len(a):].tolist() == [1] * len(b)


def test_en_echelon_row_bonds_are_one_fracture():
    """Only x-parallel bonds, stepping d/2 per row (a crack along 60 degrees that breaks
    no diagonal): consecutive midpoints are exactly d apart, one fracture."""
    pos, bonds = lattice(20, 12)
    mid = bond_midpoints(bonds, pos)
    horizontal = np.abs(pos[bonds[:, 0] - 1, 1] - pos[bonds[:, 1] - 1, 1]) < 1e-9 * D
    chosen = []
    for j in range(10):
        # row bonds' midpoints: even rows at whole multiples of d, odd rows at (i + 1/2) d
        x = (6.0 + 0.5 * j) * D
        k = np.flatnonzero(horizontal & (np.abs(mid[:, 0] - x) < 1e-9 * D)
                           & (np.abs(mid[:, 1] - row_y(j)) < 1e-9 * D))
        assert len(k) == 1
        chosen.append(k[0])
    steps = np.diff(mid[chosen], axis=0)
    assert np.allclose(np.hypot(steps[:, 0], steps[:, 1]), D, rtol=1e-12)
    assert set(fracture_labels(bonds[chosen], pos, D).tolist()) == {0}
    # every other row only: midpoints 2 d apart, five separate fractures
    assert sorted(fracture_labels(bonds[chosen[::2]], pos, D).tolist()) == [0, 1, 2, 3, 4]


# ---------------------------------------------------------------- layers


def test_three_crossing_cracks_a_half_crack_and_their_spacing():
    pos, bonds = lattice(40, 24)
    layer = layer_mask(pos, 9, 6)                 # rows 9-14: 3 even and 3 odd rows
    # from a quarter row below the layer's lowest row to a quarter row above its highest
    # (the interface diagonals cross a vertical line half a row outside: not broken)
    y0, y1 = row_y(8.75), row_y(14.25)
    top = pos[:, 1].max() + D
    cracks = [vertical(pos, bonds, x * D, y0, y1) for x in (8.25, 16.25, 24.25)]
    assert [len(c) for c in cracks] == [11, 11, 11]
    half = vertical(pos, bonds, 12.25 * D, y0, row_y(11.25))   # stops half-way
    through = vertical(pos, bonds, 32.25 * D, 0.0, top)            # the whole box
    broken = np.vstack(cracks + [half, through])
    out = layer_fractures(broken, pos, layer, D)
    assert out["fractures_in_layer"] == 4
    # in the layer a vertical line crosses 6 row bonds and 5 diagonals, mean x = the line's
    assert np.allclose(out["layer_fracture_x"], [8.25e-3, 16.25e-3, 24.25e-3, 32.25e-3],
                       rtol=1e-12)
    assert out["layer_thickness"] == pytest.approx(6 * ROW * D, rel=1e-12)
    assert out["spacing_to_thickness"] == pytest.approx(8.0 / (6 * ROW), rel=1e-12)
    # in-layer bonds: 3 x 11, the half crack's 5 (rows 9-11, two diagonals), 11 of the
    # through crack (of its 2 x 24 - 1 = 47)
    assert len(half) == 5 and len(through) == 47
    assert out["fraction_in_layer"] == pytest.approx(49 / 85, rel=1e-12)
    # the scanline along the middle row (rows 11 and 12 straddle the mid-thickness: the
    # lower, row 11, particles at whole multiples of d) meets all five cracks, the half one
    # too, each at the midpoint of the row bond it breaks: 8.5, 12.5, 16.5, 24.5, 32.5 d
    assert out["scanline_fractures"] == 5
    assert np.allclose(out["scanline_x"], np.array([8.5, 12.5, 16.5, 24.5, 32.5]) * D,
                       rtol=1e-12)
    assert out["scanline_spacing_to_thickness"] == pytest.approx(6.0 / (6 * ROW), rel=1e-12)


def test_scanline_counts_branches_that_the_crossing_count_joins():
    """A V: two cracks from one point at the layer's base, running up at +-(about) 60
    degrees, are one fracture crossing the layer (their bonds touch) but the scanline meets
    them twice; a particle cut out of the middle row (its two row bonds broken, d apart) is
    met once."""
    pos, bonds = lattice(40, 24)
    layer = layer_mask(pos, 9, 6)
    y0, y1 = row_y(8.75), row_y(14.25)
    left = crossing(pos, bonds, (20.1 * D, y0), (20.1 * D - 3.2 * D, y1))
    right = crossing(pos, bonds, (20.1 * D, y0), (20.1 * D + 3.2 * D, y1))
    v = np.unique(np.vstack([left, right]), axis=0)
    out = layer_fractures(v, pos, layer, D)
    assert out["fractures_in_layer"] == 1
    assert out["scanline_fractures"] == 2
    # mid row 11 (y = row_y(11)): the V's arms there, 2.25 of the 5.5 rows up, lie
    # 3.2 x 2.25 / 5.5 = 1.31 d either side of x = 20.1 d, in the row bonds between the
    # particles at 18 and 19 d and at 21 and 22 d
    assert np.allclose(out["scanline_x"], [18.5 * D, 21.5 * D], rtol=1e-12)
    # a particle of row 11 (x = 30 d) cut out: its two row bonds, one count at 30 d
    row11 = np.abs(pos[:, 1] - row_y(11)) < 1e-9 * D
    k = int(np.flatnonzero(row11 & (np.abs(pos[:, 0] - 30 * D) < 1e-9 * D))[0]) + 1
    cut = bonds[(bonds[:, 0] == k) | (bonds[:, 1] == k)]
    both = layer_fractures(np.vstack([v, cut]), pos, layer, D)
    assert both["scanline_fractures"] == 3
    assert both["scanline_x"][2] == pytest.approx(30 * D, rel=1e-12)


def test_crack_crossing_twice_through_the_matrix_is_two_crossings():
    pos, bonds = lattice(40, 24)
    layer = layer_mask(pos, 9, 6)
    y1 = row_y(14.25)
    left = vertical(pos, bonds, 10.25 * D, 2 * D, y1)
    right = vertical(pos, bonds, 20.25 * D, 2 * D, y1)
    floor = crossing(pos, bonds, (10.25 * D, 2.2 * D), (20.25 * D, 2.2 * D))
    broken = np.unique(np.vstack([left, right, floor]), axis=0)
    assert len(set(fracture_labels(broken, pos, D).tolist())) == 1
    out = layer_fractures(broken, pos, layer, D)
    assert out["fractures_in_layer"] == 2
    assert out["spacing_to_thickness"] == pytest.approx(10.0 / (6 * ROW), rel=1e-12)


def test_one_crossing_has_no_spacing_and_no_broken_bonds_no_fraction():
    pos, bonds = lattice(20, 16)
    layer = layer_mask(pos, 5, 6)
    one = vertical(pos, bonds, 8.25 * D, 0.0, pos[:, 1].max() + D)
    out = layer_fractures(one, pos, layer, D)
    assert out["fractures_in_layer"] == 1 and out["spacing_to_thickness"] is None
    empty = layer_fractures(np.zeros((0, 2)), pos, layer, D)
    assert empty["fractures_in_layer"] == 0 and empty["fraction_in_layer"] is None


def test_scene_layer_geometry():
    """The default layer scene: its layer's thickness is 0.2 of the box height to within
    one row (the layer is the rows whose centres fall in the slab)."""
    scene = Scene("layer-extension", n_x=40)
    model = build_model(scene)
    out = fracture_summary(scene, model, np.zeros((0, 2)))
    assert abs(out["layer_thickness"] - 0.2 * scene.height) <= ROW * scene.d
    assert out["fractures_in_layer"] == 0


# ---------------------------------------------------------------- grains


def test_intergranular_fraction_of_a_boundary_crack_and_a_grain_crack():
    pos, bonds = lattice(30, 10)
    grain = (pos[:, 0] > 15.2 * D).astype(int)      # boundary between x = 15 and 15.5 d
    top = pos[:, 1].max() + D
    boundary = vertical(pos, bonds, 15.25 * D, 0.0, top)
    inside = vertical(pos, bonds, 5.25 * D, 0.0, top)
    g = grain[boundary - 1]
    assert np.all(g[:, 0] != g[:, 1])
    frac = intergranular_fraction(np.vstack([boundary, inside]), grain)
    assert frac == pytest.approx(0.5, rel=1e-12)      # 19 bonds each
    assert intergranular_fraction(np.zeros((0, 2)), grain) is None


# ---------------------------------------------------------------- growing grains


def rays(pos, bonds, centre, angles, r1):
    return [crossing(pos, bonds, centre, (centre[0] + r1 * math.cos(t),
                                          centre[1] + r1 * math.sin(t))) for t in angles]


@pytest.mark.parametrize("k", [3, 5, 7])
def test_k_radial_cracks_around_a_disc(k):
    pos, bonds = lattice(50, 58)
    centre = np.array([25.3 * D, 25.1 * D])
    disc = np.hypot(pos[:, 0] - centre[0], pos[:, 1] - centre[1]) < 4.0 * D
    angles = [math.radians(10.0) + 2 * math.pi * m / k for m in range(k)]
    long = rays(pos, bonds, centre, angles, 14.0 * D)
    short = rays(pos, bonds, centre, [a + math.pi / k for a in angles], 5.5 * D)
    # a crack away from the disc, and broken bonds inside it: neither is radial
    away = vertical(pos, bonds, 45.25 * D, 2 * D, 20 * D)
    inner = bonds[disc[bonds[:, 0] - 1] & disc[bonds[:, 1] - 1]][:20]
    broken = np.unique(np.vstack(long + short + [away, inner]), axis=0)
    assert radial_fractures(broken, pos, disc, D) == k
    # a debonded boundary (every bond with one particle in the disc) joins all cracks
    # into one fracture; its outward branches are still k
    ring = bonds[disc[bonds[:, 0] - 1] ^ disc[bonds[:, 1] - 1]]
    with_ring = np.unique(np.vstack([broken, ring]), axis=0)
    assert radial_fractures(with_ring, pos, disc, D) == k
    # the short cracks end 1.5 d beyond the disc (their bonds' midpoints at most 1.8 d from
    # it); run out to 10 d from the centre, they count too
    longer = rays(pos, bonds, centre, [a + math.pi / k for a in angles], 10.0 * D)
    assert radial_fractures(np.vstack([broken] + longer), pos, disc, D) == 2 * k


# ---------------------------------------------------------------- checks


def test_bad_parameters_name_the_value_and_the_range():
    pos, bonds = lattice(10, 6)
    layer = layer_mask(pos, 2, 2)
    with pytest.raises(ValueError, match="d = 0"):
        layer_fractures(bonds[:3], pos, layer, 0.0)
    with pytest.raises(ValueError, match="particle id 61"):
        fracture_labels(np.array([[1, 61]]), pos, D)
    with pytest.raises(ValueError, match=r"shape \(3, 3\)"):
        intergranular_fraction(np.ones((3, 3)), np.zeros(len(pos), dtype=int))
    with pytest.raises(ValueError, match="selects no particle"):
        layer_fractures(bonds[:3], pos, np.zeros(len(pos), dtype=bool), D)
    with pytest.raises(ValueError, match="shape"):
        radial_fractures(bonds[:3], pos, layer[:5], D)
    with pytest.raises(ValueError, match="reach = 0.5"):
        radial_fractures(bonds[:3], pos, layer, D, reach=0.5)


def test_two_radial_cracks_that_join_farther_out_are_two():
    """A V: two cracks leave the disc (radius 4 d) 90 degrees apart and meet 20 d below its
    centre; the band 3-5 d beyond the disc cuts both arms, more than 3 d apart there."""
    pos, bonds = lattice(50, 58)
    centre = np.array([25.3 * D, 25.1 * D])
    disc = np.hypot(pos[:, 0] - centre[0], pos[:, 1] - centre[1]) < 4.0 * D
    tip = centre + np.array([0.0, -20.0 * D])
    arms = []
    for t in (math.radians(-45.0), math.radians(-135.0)):
        start = centre + 4.0 * D * np.array([math.cos(t), math.sin(t)])
        arms += [crossing(pos, bonds, centre, start), crossing(pos, bonds, start, tip)]
    broken = np.unique(np.vstack(arms), axis=0)
    outside = broken[~(disc[broken[:, 0] - 1] & disc[broken[:, 1] - 1])]
    assert set(fracture_labels(outside, pos, D).tolist()) == {0}     # one fracture
    assert radial_fractures(broken, pos, disc, D) == 2
