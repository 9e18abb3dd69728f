"""Where the first breaks lie (bonded_lattice.first_breaks): constructed break dates,
points and bond dumps whose answers are counted by hand.

The shares are ratios of small integers (or of areas of rectangles), compared to
1e-15 relative: floating-point rounding of one division.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from bonded_lattice.first_breaks import (
    band_area_share,
    break_order,
    break_sites,
    first_breaks,
    first_breaks_png,
    outline,
    wall_share,
)

DATED = {(5, 6): 2, (1, 2): 1, (3, 4): 1, (7, 8): 2, (9, 10): 2, (11, 12): 3}


def test_break_order_by_step_then_id() -> None:
    assert [pair for pair, _ in break_order(DATED)] == [(1, 2), (3, 4), (5, 6), (7, 8),
                                                       (9, 10), (11, 12)]


def test_first_breaks_complete_the_step() -> None:
    # two breaks in step 1, three in step 2, one in step 3
    pairs, steps = first_breaks(DATED, 2)
    assert pairs.tolist() == [[1, 2], [3, 4]] and steps.tolist() == [1, 1]
    pairs, steps = first_breaks(DATED, 3)          # the third is in step 2: all of step 2
    assert len(pairs) == 5 and steps.tolist() == [1, 1, 2, 2, 2]
    pairs, _ = first_breaks(DATED, 100)            # fewer breaks than asked: all
    assert len(pairs) == 6
    assert first_breaks({}, 5)[0].shape == (0, 2)
    with pytest.raises(ValueError, match="k = 0"):
        first_breaks(DATED, 0)


def test_wall_share_and_area_share() -> None:
    box = (0.0, 10.0, 0.0, 6.0)
    # band 1: (0.5, 3) and (9.5, 3) by the side walls, (5, 0.2) by the bottom; 7 inside
    points = np.array([[0.5, 3.0], [9.5, 3.0], [5.0, 0.2]] + [[5.0, 3.0]] * 7)
    assert wall_share(points, box, 1.0) == pytest.approx(0.3, rel=1e-15)
    # 1 - (10 - 2)(6 - 2) / 60 = 28 / 60
    assert band_area_share(box, 1.0) == pytest.approx(28.0 / 60.0, rel=1e-15)
    assert band_area_share(box, 4.0) == 1.0       # the band covers the box
    assert np.isnan(wall_share(np.zeros((0, 2)), box, 1.0))
    with pytest.raises(ValueError, match="band = -1"):
        wall_share(points, box, -1.0)
    with pytest.raises(ValueError, match="is empty"):
        band_area_share((0.0, 0.0, 0.0, 1.0), 0.1)


def _dump(path: Path, rows: list[tuple[int, int, int]], pos: np.ndarray) -> None:
    """A bond dump of (id1, id2, state) rows, x y z at the bond midpoints."""
    lines = ["ITEM: TIMESTEP", "0", "ITEM: NUMBER OF ENTRIES", str(len(rows)),
             "ITEM: BOX BOUNDS ff ff pp", "0 1", "0 1", "0 1",
             "ITEM: ENTRIES c_bl[1] c_bl[2] c_bl[3] c_bl[4] c_bl[5] c_bl[6]"]
    for i, j, s in rows:
        m = 0.5 * (pos[i - 1] + pos[j - 1])
        lines.append(f"{i} {j} {s} {m[0]} {m[1]} 0")
    path.write_text("\n".join(lines) + "\n")


def test_break_sites_from_dumps(tmp_path: Path) -> None:
    # a row of 11 particles at x = 0 ... 10 and one at (5, 4): box 10 x 4; band 1.5 (d = 0.5,
    # band 3 d).  Bonds (i, i+1) along the row, midpoints x = 0.5 ... 9.5 at y = 0 (all on
    # the bottom wall), and (6, 12) from (5, 0) to (5, 4), midpoint (5, 2): 2 from every side.
    pos = np.array([[float(x), 0.0] for x in range(11)] + [[5.0, 4.0]])
    bonds = [(i, i + 1) for i in range(1, 11)] + [(6, 12)]
    # step 1 breaks (6, 12) and (1, 2); step 2 breaks (5, 6); contact (1, 12) is no bond
    _dump(tmp_path / "bonds.1.txt", [(i, j, 1 if (i, j) in [(6, 12), (1, 2)] else 0)
                                     for i, j in bonds], pos)
    final = [(i, j, 1 if (i, j) in [(6, 12), (1, 2), (5, 6)] else 0) for i, j in bonds]
    _dump(tmp_path / "bonds.2.txt", final, pos)
    _dump(tmp_path / "bonds.final.txt", final + [(1, 12, 3)], pos)
    sites = break_sites(tmp_path, pos, d=0.5, k=2, band=3.0, label="row")
    assert outline(pos) == (0.0, 10.0, 0.0, 4.0)
    assert len(sites.points) == 2 and sites.steps.tolist() == [1, 1]
    assert sites.share == pytest.approx(0.5, rel=1e-15)            # (1, 2) yes, (6, 12) no
    assert sites.bond_share == pytest.approx(10.0 / 11.0, rel=1e-15)
    assert sites.area_share == pytest.approx(1.0 - 7.0 * 1.0 / 40.0, rel=1e-15)
    assert sites.enrichment == pytest.approx(0.5 * 11.0 / 10.0, rel=1e-15)
    assert break_sites(tmp_path, pos, d=0.5, k=3).steps.tolist() == [1, 1, 2]
    with pytest.raises(ValueError, match="no bond dumps"):
        break_sites(tmp_path / "none", pos, d=0.5)
    first_breaks_png(tmp_path / "first.png", [sites, sites])
    assert (tmp_path / "first.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match="0 runs with no breaks"):
        first_breaks_png(tmp_path / "none.png", [])


def test_break_sites_in_a_periodic_box(tmp_path: Path) -> None:
    # box outline 10 x 4 (a row at y = 0 from x = 0 to 10, particle 14 at (5, 4)), periods
    # (11, 9): particles 12 (0, 2) and 13 (10, 2) are neighbours across the x seam.  Their
    # bond's midpoint is (5, 2) without the period, 2 from every side (not within band 1.5);
    # with it (-0.5, 2), between the images, at the outline (distance 0).  (1, 2) lies on
    # the bottom row, (6, 14) at (5, 2) either way (4 < 9 / 2: no image nearer).  Exact
    # ratios of small integers.
    pos = np.array([[float(x), 0.0] for x in range(11)] + [[0.0, 2.0], [10.0, 2.0], [5.0, 4.0]])
    bonds = [(1, 2), (12, 13), (6, 14)]
    rows = [(i, j, 1 if (i, j) == (12, 13) else 0) for i, j in bonds]
    _dump(tmp_path / "bonds.1.txt", rows, pos)
    _dump(tmp_path / "bonds.final.txt", rows, pos)
    walls = break_sites(tmp_path, pos, d=0.5, k=1, band=3.0)
    periodic = break_sites(tmp_path, pos, d=0.5, k=1, band=3.0, period=(11.0, 9.0))
    assert walls.points.tolist() == [[5.0, 2.0]] and periodic.points.tolist() == [[-0.5, 2.0]]
    assert (walls.share, periodic.share) == (0.0, 1.0)
    assert walls.bond_share == pytest.approx(1.0 / 3.0, rel=1e-15)
    assert periodic.bond_share == pytest.approx(2.0 / 3.0, rel=1e-15)
