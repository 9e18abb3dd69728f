"""Layer fractures in the periodic box (``boundary="periodic"``), and the fracture measures
along the loading from the bond dumps (``scene_study.fractures_along``).

The lattice is the periodic scenes' (``scenes.box_lattice(..., periodic=True)``): rows along
x at y = j sqrt3/2 d + d/2, particle i of row j at x = (i + 1/2 + (j mod 2)/2) d, the cell
from x = d/4 to (n_x + 1/4) d.  Cracks are made by breaking every bond (at its minimum
image) that crosses a vertical segment; positions are exact multiples of d/2 and sqrt3/2 d,
so the known answers hold to rounding (tolerances 1e-12 relative; 1e-9 where a circular mean
of exact positions is taken, which rounds through a complex exponential).
"""

from __future__ import annotations

import numpy as np
import pytest

from bonded_lattice.fractures import (bond_midpoints, fracture_labels, layer_fractures,
                                      radial_fractures)
from bonded_lattice.scene_study import fracture_summary, fractures_along
from bonded_lattice.scenes import (ROW, Scene, box_lattice, box_period, build_model,
                                   lattice_bond_ids)

D = 1.0e-3


def periodic_lattice(n_x: int, n_y: int):
    lat = box_lattice(n_x, n_y, D, periodic=True)
    return lat.positions, lattice_bond_ids(lat, True), np.array(box_period(lat))


def vertical(pos, bonds, period, x, y0, y1) -> np.ndarray:
    """Bonds (at their minimum image, from id1) crossing the vertical segment x, y0..y1,
    or one of its images x +- L_x."""
    p = pos[bonds[:, 0] - 1, :2]
    sep = pos[bonds[:, 1] - 1, :2] - p
    sep -= period * np.round(sep / period)
    hit = np.zeros(len(bonds), dtype=bool)
    for xc in (x - period[0], x, x + period[0]):
        t = (xc - p[:, 0]) / np.where(sep[:, 0] != 0, sep[:, 0], np.inf)
        y = p[:, 1] + t * sep[:, 1]
        hit |= (t > 0) & (t < 1) & (y > y0) & (y < y1)
    return bonds[hit]


def layer_rows(pos, first_row: int, rows: int) -> np.ndarray:
    j = np.round((pos[:, 1] - 0.5 * D) / (ROW * D)).astype(int)
    return (j >= first_row) & (j < first_row + rows)


def row_y(j: float) -> float:
    return (j * ROW + 0.5) * D


def test_a_crack_on_the_seam_is_one_crossing_and_the_spacing_is_the_period_over_the_count():
    pos, bonds, period = periodic_lattice(40, 24)
    layer = layer_rows(pos, 9, 6)
    y0, y1 = row_y(8.75), row_y(14.25)
    # three cracks inside the cell and one on its left face (x = d/4), across the seam
    cracks = [vertical(pos, bonds, period, x * D, y0, y1) for x in (8.25, 16.25, 24.25, 0.25)]
    assert [len(c) for c in cracks] == [11, 11, 11, 11]
    broken = np.vstack(cracks)
    out = layer_fractures(broken, pos, layer, D, tuple(period))
    assert out["fractures_in_layer"] == 4
    # positions in [x0, x0 + L_x), x0 = d/2 the lowest particle x: the seam crack at
    # d/4 + L_x = 40.25 d
    assert np.allclose(out["layer_fracture_x"], [8.25e-3, 16.25e-3, 24.25e-3, 40.25e-3],
                       rtol=1e-9)
    thickness = 6 * ROW * D
    assert out["spacing_to_thickness"] == pytest.approx(40 * D / 4 / thickness, rel=1e-12)
    assert out["fraction_in_layer"] == pytest.approx(1.0, rel=1e-12)
    # the scanline meets the seam crack once, across the seam, and spaces the four by L_x / 4
    assert out["scanline_fractures"] == 4
    assert out["scanline_spacing_to_thickness"] == pytest.approx(40 * D / 4 / thickness,
                                                                 rel=1e-12)
    # the seam crack's bonds are all across the seam: one fracture, midpoints within d/2
    # of the face by minimum image; without the period they lie in the middle of the box
    # (between the particles at x = d/2 or d and those at 39.5 d or 40 d), and the layer
    # seems to break there
    seam = cracks[3]
    assert set(fracture_labels(seam, pos, D, tuple(period)).tolist()) == {0}
    off = bond_midpoints(seam, pos, tuple(period))[:, 0] - 0.25 * D    # beside id1: mod L_x
    off -= period[0] * np.round(off / period[0])
    assert np.all(np.abs(off) <= 0.25 * D * (1 + 1e-9))
    assert layer_fractures(seam, pos, layer, D)["layer_fracture_x"] == pytest.approx(
        [20.25e-3], rel=1e-12)


def test_one_crossing_in_a_periodic_box_is_spaced_by_the_box_length():
    pos, bonds, period = periodic_lattice(30, 20)
    layer = layer_rows(pos, 7, 4)
    one = vertical(pos, bonds, period, 12.25 * D, 0.0, period[1] + D)   # the whole height
    out = layer_fractures(one, pos, layer, D, tuple(period))
    assert out["fractures_in_layer"] == 1
    assert out["spacing_to_thickness"] == pytest.approx(30.0 / (4 * ROW), rel=1e-12)
    # the crack crosses all 20 rows and 20 gaps (the seam's too): 40 bonds, 7 in the layer
    # (4 rows, 3 gaps)
    assert len(one) == 40
    assert out["fraction_in_layer"] == pytest.approx(7 / 40, rel=1e-12)
    none = layer_fractures(np.zeros((0, 2)), pos, layer, D, tuple(period))
    assert none["fractures_in_layer"] == 0 and none["spacing_to_thickness"] is None


@pytest.mark.parametrize("period", [(1.0,), (0.0, 1.0), (1.0, float("inf"))])
def test_a_bad_period_is_refused(period):
    pos, bonds, _ = periodic_lattice(10, 6)
    with pytest.raises(ValueError, match="period"):
        layer_fractures(bonds[:3], pos, layer_rows(pos, 2, 2), D, period)


def write_dump(path, records: np.ndarray) -> None:
    """A one-frame bond dump in the scene decks' format (id1 id2 state x y z)."""
    lines = ["ITEM: TIMESTEP", "0", "ITEM: NUMBER OF ENTRIES", str(len(records)),
             "ITEM: BOX BOUNDS pp pp pp", "0 1", "0 1", "-0.5 0.5",
             "ITEM: ENTRIES c_bl[1] c_bl[2] c_bl[3] c_bl[4] c_bl[5] c_bl[6]"]
    lines += [f"{int(a)} {int(b)} {int(s)} 0 0 0" for a, b, s in records]
    path.write_text("\n".join(lines) + "\n")


def test_fractures_along_the_loading_from_constructed_dumps(tmp_path):
    """Three dumps of a periodic layer scene: none broken, one crack across the layer,
    then a second one half the box away; each row carries its strain from scene.dat."""
    scene = Scene("layer-extension", n_x=20, n_y=20, boundary="periodic", bond_dumps=1)
    model = build_model(scene)
    pos = model.lattice.positions
    period = np.array(box_period(model.lattice))
    bonds = lattice_bond_ids(model.lattice, True)
    y = pos[model.grain == 1, 1]
    y_lo, y_hi = y.min() - 0.75 * ROW * D, y.max() + 0.75 * ROW * D
    a = vertical(pos, bonds, period, 5.25 * D, y_lo, y_hi)
    b = vertical(pos, bonds, period, 15.25 * D, y_lo, y_hi)
    strains = [0.0, 1e-5, 2e-5, 3e-5]
    (tmp_path / "scene.dat").write_text(
        "# k step exx eyy sxx syy intact tension shear contacts growth\n"
        + "".join(f"{k} 0 {e} {-e} 0 0 0 0 0 0 0\n" for k, e in enumerate(strains)))
    state = {tuple(x) for x in a.tolist()}
    write_dump(tmp_path / "bonds.1.txt", np.column_stack([bonds, np.zeros(len(bonds))]))
    write_dump(tmp_path / "bonds.2.txt", np.column_stack(
        [bonds, [1 if tuple(x) in state else 0 for x in bonds.tolist()]]))
    state |= {tuple(x) for x in b.tolist()}
    write_dump(tmp_path / "bonds.3.txt", np.column_stack(
        [bonds, [1 if tuple(x) in state else 0 for x in bonds.tolist()]]))
    write_dump(tmp_path / "bonds.final.txt", np.column_stack([bonds, np.zeros(len(bonds))]))
    along = fractures_along(scene, tmp_path, model)
    assert [r["step"] for r in along] == [1, 2, 3]
    assert [r["strain"] for r in along] == strains[1:]
    assert [r["broken"] for r in along] == [0, len(a), len(a) + len(b)]
    assert [r["fractures_in_layer"] for r in along] == [0, 1, 2]
    thickness = fracture_summary(scene, model, np.zeros((0, 2)))["layer_thickness"]
    assert along[1]["spacing_to_thickness"] == pytest.approx(period[0] / thickness, rel=1e-12)
    assert along[2]["spacing_to_thickness"] == pytest.approx(period[0] / 2 / thickness,
                                                             rel=1e-12)
    assert np.allclose(along[2]["layer_fracture_x"], [5.25e-3, 15.25e-3], rtol=1e-9)
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "scene.dat").write_text((tmp_path / "scene.dat").read_text())
    with pytest.raises(ValueError, match="no bonds"):
        fractures_along(scene, empty, model)
    with pytest.raises(ValueError, match="quasistatic"):
        fractures_along(Scene("layer-extension", n_x=20, mode="dynamic"), tmp_path, model)


def periodic_crossing(pos, bonds, period, a, b) -> np.ndarray:
    """Bonds (at their minimum image, from id1) crossing the segment a-b or one of its images
    shifted by the periods (a proper crossing)."""
    p = pos[bonds[:, 0] - 1, :2]
    sep = pos[bonds[:, 1] - 1, :2] - p
    sep -= period * np.round(sep / period)
    q = p + sep

    def side(u, v, w):
        return np.sign((v[..., 0] - u[..., 0]) * (w[..., 1] - u[..., 1])
                       - (v[..., 1] - u[..., 1]) * (w[..., 0] - u[..., 0]))

    hit = np.zeros(len(bonds), dtype=bool)
    for sx in (-1, 0, 1):
        for sy in (-1, 0, 1):
            shift = np.array([sx * period[0], sy * period[1]])
            u, v = np.asarray(a, float) + shift, np.asarray(b, float) + shift
            hit |= (side(u, v, p) * side(u, v, q) < 0) & (side(p, q, u) * side(p, q, v) < 0)
    return bonds[hit]


@pytest.mark.parametrize("k", [3, 5])
def test_k_radial_cracks_around_a_disc_on_the_seam(k):
    """A growing disc centred 1.2 d from the periodic box's left face: some of its k radial
    cracks cross the seam (and the disc itself spans it); by minimum image they are still
    k, the short cracks (ending 1.5 d beyond the disc) none."""
    pos, bonds, period = periodic_lattice(50, 58)
    centre = np.array([1.45 * D, 25.1 * D])
    rel = pos[:, :2] - centre
    rel -= period * np.round(rel / period)
    disc = np.hypot(rel[:, 0], rel[:, 1]) < 4.0 * D
    angles = [np.radians(10.0) + 2 * np.pi * m / k for m in range(k)]

    def rays(turn, r1):
        return [periodic_crossing(pos, bonds, period, centre,
                                  centre + r1 * np.array([np.cos(t + turn), np.sin(t + turn)]))
                for t in angles]

    broken = np.unique(np.vstack(rays(0.0, 14.0 * D) + rays(np.pi / k, 5.5 * D)), axis=0)
    assert any(np.any(pos[c[:, 0] - 1, 0] > 0.5 * period[0]) for c in rays(0.0, 14.0 * D)[1:]), \
        "some crack must lie across the seam"
    assert radial_fractures(broken, pos, disc, D, period=period) == k
