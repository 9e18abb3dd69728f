"""Crack rasters (bonded_lattice.crack_raster): constructed segments on small pixel grids
whose lit pixels and counts are known by hand, and the method choice.

Exact comparisons throughout: every expected pixel is fixed by construction (segments
along pixel rows, columns or diagonals, samples away from pixel edges or on corners that
floor() assigns one way), so no tolerance is needed.
"""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.crack_raster import (
    SEGMENT_LIMIT,
    PixelGrid,
    boundary_mask,
    choose_method,
    count_raster,
    crack_segments,
    first_value_raster,
    nearest_particle_raster,
    segment_pixels,
)

GRID = PixelGrid(0.0, 10.0, 0.0, 10.0, 10, 10)   # unit pixels


def test_grid_index_and_validation() -> None:
    assert GRID.px == 1.0 and GRID.py == 1.0
    # (x, y) = (3.2, 7.9) is column 3, row 7: flat 7 * 10 + 3; outside: -1
    assert GRID.flat_index(np.array([3.2, -0.1, 10.0]), np.array([7.9, 5.0, 5.0])).tolist() \
        == [73, -1, -1]
    with pytest.raises(ValueError, match="pixel grid of 0 x 5"):
        PixelGrid(0.0, 1.0, 0.0, 1.0, 0, 5)
    with pytest.raises(ValueError, match="is empty"):
        PixelGrid(1.0, 1.0, 0.0, 1.0, 5, 5)


def test_crack_segment_is_across_the_bond_at_its_midpoint() -> None:
    # bond (0,0)-(2,0): its crack segment of length 1 is x = 1, y from -0.5 to 0.5
    positions = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    seg = crack_segments(positions, np.array([0]), np.array([1]), 1.0)
    assert np.allclose(seg, [[[1.0, -0.5], [1.0, 0.5]]], atol=0.0, rtol=0.0)
    with pytest.raises(ValueError, match="length = 0"):
        crack_segments(positions, np.array([0]), np.array([1]), 0.0)


def test_a_bond_lights_the_pixels_of_its_crack() -> None:
    # bond (2.5, 3)-(4.5, 3): its crack segment, x = 3.5, y from 2.5 to 3.5, lies in rows 2
    # and 3 of column 3 (the ends on pixel edges: floor puts 2.5 in row 2, 3.5 in row 3)
    seg = crack_segments(np.array([[2.5, 3.0], [4.5, 3.0]]), np.array([0]), np.array([1]), 1.0)
    counts = count_raster(seg, GRID)
    assert np.nonzero(counts)[0].tolist() == [2, 3] and np.nonzero(counts)[1].tolist() == [3, 3]
    assert counts.sum() == 2


def test_vertical_segment_lights_its_column() -> None:
    # x = 3.5, y from 1.2 to 4.6: rows 1, 2, 3, 4 of column 3, once each
    counts = count_raster(np.array([[[3.5, 1.2], [3.5, 4.6]]]), GRID)
    expected = np.zeros((10, 10), dtype=int)
    expected[1:5, 3] = 1
    assert np.array_equal(counts, expected)


def test_counts_add_over_segments_and_drop_outside() -> None:
    segs = np.array([[[3.5, 1.2], [3.5, 4.6]],      # column 3, rows 1-4
                     [[3.5, 3.5], [3.5, 12.0]],     # column 3, rows 3-9, the rest outside
                     [[0.2, 5.5], [2.8, 5.5]]])     # row 5, columns 0-2
    counts = count_raster(segs, GRID)
    expected = np.zeros((10, 10), dtype=int)
    expected[1:5, 3] += 1
    expected[3:10, 3] += 1
    expected[5, 0:3] += 1
    assert np.array_equal(counts, expected)
    assert counts.sum() == 4 + 7 + 3


def test_diagonal_segment_lights_the_diagonal_only() -> None:
    # along x = y every sample has floor(x) == floor(y): pixels (0,0) ... (4,4), nothing else
    owner, flat = segment_pixels(np.array([[[0.5, 0.5], [4.5, 4.5]]]), GRID)
    assert owner.tolist() == [0] * 5
    assert flat.tolist() == [0, 11, 22, 33, 44]


def test_first_value_is_the_smallest_through_each_pixel() -> None:
    segs = np.array([[[0.5, 2.5], [4.5, 2.5]],      # row 2, columns 0-4, step 5
                     [[2.5, 0.5], [2.5, 4.5]]])     # column 2, rows 0-4, step 2
    first = first_value_raster(segs, np.array([5.0, 2.0]), GRID)
    assert first[2, 2] == 2.0                                   # both: the smaller
    assert first[2, [0, 1, 3, 4]].tolist() == [5.0] * 4
    assert first[[0, 1, 3, 4], 2].tolist() == [2.0] * 4
    assert np.isnan(first).sum() == 100 - 9
    with pytest.raises(ValueError, match="1 values for 2 segments"):
        first_value_raster(segs, np.array([1.0]), GRID)


def test_nearest_particle_and_boundary() -> None:
    # particles at x = 1 and x = 3 (y = 2.5) on a 5 x 5 grid: pixel centres 0.5, 1.5 nearer
    # the first (the midline is x = 2), 2.5, 3.5, 4.5 the second; reach 2.2 leaves the
    # pixels farther than that blank (-1): e.g. the corner centre (4.5, 0.5) is 2.5 away
    grid = PixelGrid(0.0, 5.0, 0.0, 5.0, 5, 5)
    near = nearest_particle_raster(np.array([[1.0, 2.5], [3.0, 2.5]]), grid, reach=2.2)
    assert near[2].tolist() == [0, 0, 1, 1, 1]
    assert near[0, 4] == -1 and near[4, 4] == -1 and near[0, 0] == 0
    labels = np.where(near >= 0, near, -1)
    mask = boundary_mask(labels)
    # the boundary is column 1 (its right neighbour, column 2, holds the other particle),
    # in the rows where both are in reach
    assert set(zip(*np.nonzero(mask))) == {(r, 1) for r in range(5)
                                          if labels[r, 1] >= 0 and labels[r, 2] >= 0}
    with pytest.raises(ValueError, match="reach = 0"):
        nearest_particle_raster(np.zeros((1, 2)), grid, reach=0.0)


def test_choose_method() -> None:
    assert choose_method(SEGMENT_LIMIT) == "segments"
    assert choose_method(SEGMENT_LIMIT + 1) == "raster"
    assert choose_method(10, "raster") == "raster"
    assert choose_method(10**6, "segments") == "segments"
    with pytest.raises(ValueError, match="method = 'lines'"):
        choose_method(10, "lines")


def test_scene_bonds_png_both_ways(tmp_path) -> None:
    # a 12 x 12 box lattice, 3 of its bonds broken in tension and 1 in shear: both methods
    # draw a picture and return the 4 broken bonds; state 0 (intact) and 3 (contact) are not
    from bonded_lattice.lattice import contact_pairs
    from bonded_lattice.plotting import scene_bonds_png
    from bonded_lattice.scenes import box_lattice

    lattice = box_lattice(12, 12, 1e-3)
    pairs = contact_pairs(lattice) + 1
    records = np.column_stack([pairs, np.zeros(len(pairs))])
    records[:3, 2] = 1
    records[3, 2] = 2
    records[4, 2] = 3
    grain = (lattice.positions[:, 1] > 5e-3).astype(np.int64)
    for method in ("segments", "raster"):
        png = tmp_path / f"{method}.png"
        assert scene_bonds_png(png, lattice.positions, grain, records, 1e-3,
                               method=method) == 4
        assert png.stat().st_size > 0
    dated = {(int(a), int(b)): k for k, (a, b) in enumerate(pairs[:4].tolist())}
    assert scene_bonds_png(tmp_path / "steps.png", lattice.positions, grain, records, 1e-3,
                           broken_at=dated, method="raster") == 4
