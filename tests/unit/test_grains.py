"""Heterogeneous models (bonded_lattice.grains): grain assignment, stiffness statistics,
polygon files, the data file's Grains section and the deck's grain lines (LAMMPS reading
them: tests/integration/test_grain_decks.py).

Expected values are computed independently inside the tests (brute-force searches,
hand-placed points, closed-form moments of the truncated Gaussian).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from bonded_lattice.conversion import BondParameters
from bonded_lattice.decks import DeckSpec, deck_text
from bonded_lattice.grains import (
    GrainModel,
    GrainPairOptions,
    competent_layer,
    grain_arrays,
    grain_stiffness,
    layered_grains,
    map_polygons,
    particle_stiffness,
    points_in_polygon,
    polygon_grains,
    read_elle,
    read_elle_cell,
    read_polygons,
    voronoi_grains,
    voronoi_seeds,
)
from bonded_lattice.lattice import hex_block_2d, read_grain_strengths, read_grains, write_data

D = 1.0e-3
SQRT3 = math.sqrt(3.0)


# ---------------------------------------------------------------- Voronoi

def brute_force_nearest(points, seeds, lo, hi, periodic):
    """Nearest seed by explicit differences over every periodic image (-1, 0, +1 cell)."""
    length = np.asarray(hi) - np.asarray(lo)
    p = np.array(points, dtype=float)
    for k, per in enumerate(periodic):   # wrap into the cell as the code does
        if per:
            p[:, k] = lo[k] + np.mod(p[:, k] - lo[k], length[k])
    best = np.full(len(p), np.inf)
    owner = np.full(len(p), -1)
    shifts = [(i, j) for i in ((-1, 0, 1) if periodic[0] else (0,))
              for j in ((-1, 0, 1) if periodic[1] else (0,))]
    for s_index, s in enumerate(seeds):
        for i, j in shifts:
            image = s + np.array([i, j]) * length
            d2 = ((p - image) ** 2).sum(axis=1)
            closer = d2 < best
            best[closer] = d2[closer]
            owner[closer] = s_index
    return owner


@pytest.mark.parametrize("periodic", [(False, False), (True, False), (False, True), (True, True)])
@pytest.mark.parametrize("seed", [1, 7, 12345])
def test_voronoi_equals_brute_force_nearest_seed(periodic, seed):
    lo, hi = [0.0, -1.0], [3.0, 1.0]
    rng = np.random.default_rng(seed + 100)
    # points inside the box and, along periodic axes, outside it (they are wrapped)
    points = rng.uniform([-0.5, -1.5], [3.5, 1.5], size=(2000, 2))
    for k in range(2):
        if not periodic[k]:
            points[:, k] = np.clip(points[:, k], lo[k], hi[k])
    got = voronoi_grains(points, lo, hi, 25, seed, periodic)
    seeds = voronoi_seeds(lo, hi, 25, seed)
    expected = brute_force_nearest(points, seeds, lo, hi, periodic)
    assert np.array_equal(got, expected)
    if periodic != (False, False):   # the images change some assignments
        assert not np.array_equal(got, brute_force_nearest(points, seeds, lo, hi, (False, False)))


def test_voronoi_seeds_fill_the_box_and_depend_on_the_seed():
    a = voronoi_seeds([0, 0], [2, 1], 500, 3)
    assert a.shape == (500, 2)
    assert np.all((a >= [0, 0]) & (a <= [2, 1]))
    assert np.array_equal(a, voronoi_seeds([0, 0], [2, 1], 500, 3))
    assert not np.allclose(a, voronoi_seeds([0, 0], [2, 1], 500, 4))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_every_voronoi_grain_has_particles(seed):
    lat = hex_block_2d(60, D)                       # 4106 particles, ~137 per grain
    lo = lat.positions[:, :2].min(axis=0) - D / 2
    hi = lat.positions[:, :2].max(axis=0) + D / 2
    grain = voronoi_grains(lat.positions, lo, hi, 30, seed)
    counts = np.bincount(grain, minlength=30)
    assert len(counts) == 30 and counts.min() > 0


def test_voronoi_3d_equals_brute_force():
    rng = np.random.default_rng(5)
    points = rng.uniform(0, 1, size=(500, 3))
    grain = voronoi_grains(points, [0, 0, 0], [1, 1, 1], 12, 9, (False, False, False))
    seeds = voronoi_seeds([0, 0, 0], [1, 1, 1], 12, 9)
    expected = np.argmin(((points[:, None, :] - seeds[None]) ** 2).sum(axis=2), axis=1)
    assert np.array_equal(grain, expected)


# ---------------------------------------------------------------- stiffness

def test_grain_stiffness_statistics():
    n, mean, sd = 1000, 1.0, 0.2
    f = grain_stiffness(n, mean, sd, 4711)
    assert f.shape == (n,)
    # sample mean: standard error sd/sqrt(n) = 0.0063; 4 standard errors
    assert abs(f.mean() - mean) < 4 * sd / math.sqrt(n)
    # sample sd: its standard error is sd/sqrt(2n) = 2.2%; 10% is > 4 of them
    assert abs(f.std(ddof=1) / sd - 1) < 0.10


def test_non_positive_draws_are_redrawn_truncated_gaussian():
    n, mean, sd = 4000, 1.0, 1.0
    f = grain_stiffness(n, mean, sd, 99)
    assert f.min() > 0
    # moments of the Gaussian truncated at 0 (a = -mean/sd)
    a = -mean / sd
    phi = math.exp(-a * a / 2) / math.sqrt(2 * math.pi)
    tail = 1 - 0.5 * (1 + math.erf(a / math.sqrt(2)))
    lam = phi / tail
    t_mean = mean + sd * lam                          # 1.2876
    t_sd = sd * math.sqrt(1 + a * lam - lam ** 2)     # 0.7935
    assert abs(f.mean() - t_mean) < 4 * t_sd / math.sqrt(n)
    assert abs(f.std(ddof=1) / t_sd - 1) < 0.10


def test_grain_stiffness_is_deterministic_per_grain():
    a = grain_stiffness(50, 1.0, 0.3, 11)
    assert np.array_equal(a, grain_stiffness(50, 1.0, 0.3, 11))
    assert not np.any(a == grain_stiffness(50, 1.0, 0.3, 12))
    # a grain's value does not depend on how many grains there are, nor on their order
    assert np.array_equal(a[:10], grain_stiffness(10, 1.0, 0.3, 11))
    assert np.array_equal(grain_stiffness([42, 3, 17], 1.0, 0.3, 11), a[[42, 3, 17]])
    assert np.array_equal(grain_stiffness([1000], 1.0, 0.3, 11),
                          grain_stiffness(1001, 1.0, 0.3, 11)[1000:])


def test_particle_stiffness_is_its_grains():
    grain = np.array([4, 0, 4, 2, 2, 0, 9])
    per_grain = grain_stiffness(10, 2.0, 0.5, 3)
    assert np.array_equal(particle_stiffness(grain, 2.0, 0.5, 3), per_grain[grain])


def test_sd_zero_gives_the_mean():
    assert np.all(grain_stiffness(20, 1.5, 0.0, 1) == 1.5)


@pytest.mark.parametrize("mean,sd,seed,words", [
    (0.0, 0.1, 1, "mean = 0.0"),
    (-1.0, 0.1, 1, "mean = -1.0"),
    (1.0, -0.1, 1, "sd = -0.1"),
    (math.inf, 0.1, 1, "mean = inf"),
    (1.0, 3.0, 1, "mean / sd"),
    (1.0, 0.1, 0, "seed = 0"),
    (1.0, 0.1, 2**63, "seed = 9223372036854775808"),
])
def test_stiffness_validation(mean, sd, seed, words):
    with pytest.raises(ValueError, match=words.replace("/", "/").replace(".", r"\.")):
        grain_stiffness(5, mean, sd, seed)


# ---------------------------------------------------------------- pair_style options

def test_pair_style_options_text():
    opts = GrainPairOptions(0.5, 1.5, 4711, 0.5)
    assert opts.pair_style_args() == ("grain i_grain stiffness d_stiffness strength 0.5 1.5 "
                                      "seed 4711 boundary_strength 0.5")


@pytest.mark.parametrize("args,words", [
    ((0.0, 1.0, 1, 0.5), "strength min = 0.0"),
    ((1.5, 1.0, 1, 0.5), "strength max = 1.0"),
    ((0.5, math.nan, 1, 0.5), "strength max = nan"),
    ((0.5, 1.0, 1, 0.0), "boundary_strength = 0.0"),
    ((0.5, 1.0, 1, -2.0), "boundary_strength = -2.0"),
    ((0.5, 1.0, 0, 0.5), "seed = 0"),
    ((0.5, 1.0, 1.5, 0.5), "seed = 1.5"),
])
def test_pair_style_options_validation(args, words):
    with pytest.raises(ValueError, match=words.replace(".", r"\.")) as info:
        GrainPairOptions(*args)
    assert "range" in str(info.value)


def test_boundary_strength_above_one_is_allowed():
    assert GrainPairOptions(1.0, 1.0, 1, 2.0).boundary_strength == 2.0


# ---------------------------------------------------------------- polygons and Elle files

# four flynns in the unit cell: an L-shaped (non-convex) flynn 1, a square 2 sitting in
# its notch, a rectangle 5 that straddles the periodic boundary x = 0 / 1 (its nodes
# 30 and 31 are stored wrapped, at x = 0.1), and a triangle 7; node ids are not in order
ELLE = """# Created by hand for test_grains.py
OPTIONS
SwitchDistance 1.0e-02
CellBoundingBox 0.0 0.0
                1.0 0.0
                1.0 1.0
                0.0 1.0
SimpleShearOffset 0.0
FLYNNS
1 6 10 11 12 13 14 15
2 4 20 21 22 23
5 4 32 30 31 33
7 3 40 41 42
EULER_3
Default 0.0 0.0 0.0
1 10.0 20.0 30.0
LOCATION
10 0.1 0.1
11 0.6 0.1
12 0.6 0.3
13 0.3 0.3
14 0.3 0.6
15 0.1 0.6
20 0.35 0.35
21 0.7 0.35
22 0.7 0.7
23 0.35 0.7
30 0.1 0.75
31 0.1 0.95
32 0.9 0.75
33 0.9 0.95
40 0.75 0.1
41 0.95 0.1
42 0.85 0.3
UNODES
0 0.5 0.5
1 0.25 0.25
"""

# hand-placed points and the flynn containing each (-1: none)
MEMBERS = [
    ((0.2, 0.2), 1), ((0.5, 0.2), 1), ((0.2, 0.5), 1),   # the three arms of the L
    ((0.5, 0.5), 2), ((0.4, 0.4), 2),                    # the L's notch is flynn 2
    ((0.95, 0.85), 5), ((0.05, 0.85), 5),                # both sides of the wrap
    ((0.85, 0.15), 7),
    ((0.5, 0.85), -1), ((0.76, 0.29), -1), ((0.32, 0.32), -1), ((0.2, 0.68), -1),
]


@pytest.fixture
def elle_file(tmp_path):
    path = tmp_path / "grains.elle"
    path.write_text(ELLE)
    return path


def test_read_elle_polygons(elle_file):
    polygons = read_elle(elle_file)
    assert [p.grain for p in polygons] == [1, 2, 5, 7]
    assert [len(p.vertices) for p in polygons] == [6, 4, 4, 3]
    # flynn 5 is unwrapped: its nodes at x = 0.1 move to x = 1.1, next to those at 0.9
    assert np.allclose(polygons[2].vertices, [[0.9, 0.75], [1.1, 0.75], [1.1, 0.95],
                                              [0.9, 0.95]])
    assert polygons[0].line == 10
    lo, hi = read_elle_cell(elle_file)
    assert np.array_equal(lo, [0, 0]) and np.array_equal(hi, [1, 1])


def test_elle_membership_of_chosen_points(elle_file):
    polygons = read_elle(elle_file)
    points = np.array([p for p, _ in MEMBERS])
    expected = np.array([g for _, g in MEMBERS])
    inside = expected >= 0
    got = polygon_grains(points[inside], polygons, [0, 0], [1, 1], (True, True))
    assert np.array_equal(got, expected[inside])
    # without periodic images the wrapped half of flynn 5 (x < 0.1) is lost
    with pytest.raises(ValueError, match="1 particles lie in no polygon"):
        polygon_grains(points[inside], polygons)


def test_points_outside_every_polygon(elle_file):
    polygons = read_elle(elle_file)
    points = np.array([p for p, _ in MEMBERS])
    with pytest.raises(ValueError, match=r"4 particles lie in no polygon, e\.g\. particle "
                                         r"index 8 at \(0\.5, 0\.85\)"):
        polygon_grains(points, polygons, [0, 0], [1, 1], (True, True))
    got = polygon_grains(points, polygons, [0, 0], [1, 1], (True, True), outside="nearest")
    # nearest outlines: (0.5, 0.85) is 0.15 above flynn 2, 0.25 above flynn 1, 0.4 from 5;
    # (0.76, 0.29) is ~0.03 from the triangle's edge; (0.32, 0.32) is 0.02 from the L's
    # inner corner and 0.03 from flynn 2; (0.2, 0.68) is 0.08 above the L, 0.12 from the
    # periodic image of flynn 5's corner (0.1 - 1, 0.75) and 0.15 from flynn 2
    assert got[8:].tolist() == [2, 7, 1, 1]


def test_mapped_elle_cell(elle_file):
    # the unit cell mapped onto a 4 mm x 2 mm block starting at (1, -1) mm
    polygons = map_polygons(read_elle(elle_file), [0, 0], [1, 1], [1e-3, -1e-3], [5e-3, 1e-3])
    points = np.array([p for p, g in MEMBERS if g >= 0]) * [4e-3, 2e-3] + [1e-3, -1e-3]
    got = polygon_grains(points, polygons, [1e-3, -1e-3], [5e-3, 1e-3], (True, True))
    assert np.array_equal(got, [g for _, g in MEMBERS if g >= 0])


def test_points_in_non_convex_polygon():
    # a "U": the notch between the arms is outside
    u = np.array([[0, 0], [3, 0], [3, 3], [2, 3], [2, 1], [1, 1], [1, 3], [0, 3]], float)
    points = [[0.5, 2], [2.5, 2], [1.5, 0.5], [1.5, 2], [3.5, 1], [-0.1, 1]]
    assert points_in_polygon(np.array(points), u).tolist() == [True, True, True, False,
                                                                False, False]
    # the sense of the corners does not matter
    assert points_in_polygon(np.array(points), u[::-1]).tolist() == [True, True, True, False,
                                                                      False, False]


def test_shared_edge_belongs_to_one_polygon():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    t = np.random.default_rng(3).uniform(0, 1, 300)
    cases = [  # two polygons and points on their shared edge
        (square, square + [1, 0], np.c_[np.ones_like(t), t]),          # vertical edge
        (square, square + [0, 1], np.c_[t, np.ones_like(t)]),          # horizontal edge
        # a slanted edge from (1, 0) to (0.3, 1), run in opposite senses by the two
        (np.array([[0, 0], [1, 0], [0.3, 1]]), np.array([[1, 0], [1.3, 1], [0.3, 1]]),
         np.array([1.0, 0.0]) + t[:, None] * [-0.7, 1.0]),
    ]
    for a, b, on_edge in cases:
        count = points_in_polygon(on_edge, a).astype(int) + points_in_polygon(on_edge, b)
        assert np.all(count == 1)


def elle_with(flynns: str, locations: str) -> str:
    return f"FLYNNS\n{flynns}\nLOCATION\n{locations}\n"


@pytest.mark.parametrize("text,words", [
    (elle_with("1 4 1 2 3", "1 0 0\n2 1 0\n3 1 1"), r"line 2: flynn 1 declares 4 nodes but "
                                                    r"lists 3"),
    (elle_with("1 3 1 2 9", "1 0 0\n2 1 0\n3 1 1"), r"line 2: flynn 1: node 9 has no position"),
    (elle_with("1 2 1 2", "1 0 0\n2 1 0"), r"line 2: flynn 1 has 2 nodes: need at least 3"),
    (elle_with("1 3 1 2 x", "1 0 0\n2 1 0\n3 1 1"), r"line 2: flynn record"),
    (elle_with("1 3 1 2 3", "1 0 0\n2 1\n3 1 1"), r"line 5: location record '2 1'"),
    (elle_with("1 3 1 2 3", "1 0 0\n2 1 0\n2 1 1"), r"line 6: node 2 is located twice"),
    (elle_with("1 3 1 2 3\n1 3 1 2 3", "1 0 0\n2 1 0\n3 1 1"), r"line 3: flynn 1 is defined "
                                                               r"twice"),
    ("LOCATION\n1 0 0\n", r"no FLYNNS section"),
    ("FLYNNS\n1 3 1 2 3\n", r"no LOCATION section"),
    ("OPTIONS\nCellBoundingBox 0 0\n1 0\n1.2 1\n0.2 1\n" + elle_with("1 3 1 2 3",
                                                                     "1 0 0\n2 1 0\n3 1 1"),
     r"line 2: CellBoundingBox .* sheared unit cells are not supported"),
    ("REGIONS\n1 0 0 3 1 2 3\n", r"line 1: the old REGIONS format is not supported"),
    # an outline that goes once around the periodic cell (steps of 0.3 to the nearest
    # image: 0.1 -> 0.4 -> 0.7 -> 1.1) does not close after unwrapping
    (elle_with("1 3 1 2 3", "1 0.1 0.2\n2 0.4 0.3\n3 0.7 0.2"),
     r"line 2: flynn 1 wraps around the periodic unit cell"),
])
def test_elle_reader_errors(tmp_path, text, words):
    path = tmp_path / "bad.elle"
    path.write_text(text)
    with pytest.raises(ValueError, match=words):
        read_elle(path)


def test_plain_polygon_file(tmp_path):
    path = tmp_path / "grains.txt"
    path.write_text("# grain x y ...\n3 0 0 1 0 1 1 0 1\n\n8 1 0 2 0 2 1   # a triangle\n")
    polygons = read_polygons(path)
    assert [p.grain for p in polygons] == [3, 8]
    assert [p.line for p in polygons] == [2, 4]
    got = polygon_grains(np.array([[0.5, 0.5], [1.9, 0.5], [1.2, 0.1], [0.9, 0.9]]), polygons)
    assert got.tolist() == [3, 8, 8, 3]
    # (1.2, 0.9) lies above the triangle's diagonal y = x - 1, outside both
    with pytest.raises(ValueError, match=r"1 particles lie in no polygon.*\(1\.2, 0\.9\)"):
        polygon_grains(np.array([[0.5, 0.5], [1.2, 0.9]]), polygons)


@pytest.mark.parametrize("text,words", [
    ("3 0 0 1 0 1\n", r"line 1: grain 3 has 5 coordinates"),
    ("# ok\n3 0 0 1 0\n", r"line 2: grain 3 has 4 coordinates"),
    ("3 0 0 1 0 1 1\n-1 0 0 1 0 1 1\n", r"line 2: grain id: '-1'"),
    ("3 0 0 1 zero 1 1\n", r"line 1: grain 3 corners"),
    ("# nothing\n", r"no polygons"),
])
def test_plain_polygon_file_errors(tmp_path, text, words):
    path = tmp_path / "bad.txt"
    path.write_text(text)
    with pytest.raises(ValueError, match=words):
        read_polygons(path)


# a periodic tiling of the unit cell by 9 squares of side 1/3 whose corners sit at
# 1/6, 1/2 and 5/6: the squares of the last column and row straddle the cell boundary
def tiling_elle() -> str:
    c = [1 / 6, 1 / 2, 5 / 6]
    node = {(i, j): 3 * j + i for i in range(3) for j in range(3)}
    flynns = []
    for j in range(3):
        for i in range(3):
            corners = [(i, j), ((i + 1) % 3, j), ((i + 1) % 3, (j + 1) % 3), (i, (j + 1) % 3)]
            flynns.append(f"{3 * j + i} 4 " + " ".join(str(node[k]) for k in corners))
    locations = [f"{node[(i, j)]} {c[i]!r} {c[j]!r}" for j in range(3) for i in range(3)]
    return "FLYNNS\n" + "\n".join(flynns) + "\nLOCATION\n" + "\n".join(locations) + "\n"


def test_grain_arrays_from_a_periodic_elle_tiling(tmp_path):
    path = tmp_path / "tiling.elle"
    path.write_text(tiling_elle())
    lat = hex_block_2d(30, D)
    grain, stiffness = grain_arrays(lat.positions, D, GrainModel("elle", path=str(path),
                                                                 stiffness_sd=0.1, seed=5))
    # independently: the cell [0, 1]^2 is mapped onto the block's outer rectangle, and
    # square (i, j) covers cell coordinates (1/6 + i/3, 1/6 + (i+1)/3) modulo 1
    lo = lat.positions[:, :2].min(axis=0) - D / 2
    hi = lat.positions[:, :2].max(axis=0) + D / 2
    u = (lat.positions[:, :2] - lo) / (hi - lo)
    t = np.mod(u - 1 / 6, 1.0) * 3
    index = np.floor(t).astype(int)
    # not on a square's edge (the edges at 5 d, 15 d, 25 d pass through 7% of the centres)
    clear = np.all(np.abs(t - np.round(t)) > 1e-9, axis=1)
    assert clear.sum() > 0.9 * lat.n
    assert np.array_equal(grain[clear], (3 * index[:, 1] + index[:, 0])[clear])
    assert np.array_equal(np.unique(grain), np.arange(9))
    assert np.array_equal(stiffness, grain_stiffness(9, 1.0, 0.1, 5)[grain])


# ---------------------------------------------------------------- layers

def test_layered_grains_exact_on_a_lattice():
    lat = hex_block_2d(8, D)                        # rows at y = d/2 + j sqrt(3)/2 d
    row = np.round((lat.positions[:, 1] - D / 2) / (SQRT3 / 2 * D)).astype(int)
    # boundaries half-way between rows 2|3 and 5|6, and one exactly on row 7
    b = [D / 2 + 2.5 * SQRT3 / 2 * D, D / 2 + 5.5 * SQRT3 / 2 * D, D / 2 + 7 * SQRT3 / 2 * D]
    layer = layered_grains(lat.positions, "y", b)
    expected = (row >= 3).astype(int) + (row >= 6) + (row >= 7)
    assert np.array_equal(layer, expected)
    assert np.array_equal(layered_grains(lat.positions, 1, b), layer)


def test_competent_layer():
    lat = hex_block_2d(15, D)
    y = lat.positions[:, 1]
    centre = 0.5 * (y.min() + y.max())
    grain, stiffness = competent_layer(lat.positions, "y", centre, 3 * D, 4.0)
    in_layer = np.abs(y - centre) < 1.5 * D      # no row lies exactly on an interface here
    assert np.array_equal(grain, in_layer.astype(int))
    assert np.array_equal(stiffness, np.where(in_layer, 4.0, 1.0))
    # 3 d covers 3 or 4 rows of 14-15 particles
    assert 3 * 14 <= grain.sum() <= 4 * 15


@pytest.mark.parametrize("call,words", [
    (lambda p: layered_grains(p, "w", [0.0]), "axis = 'w'"),
    (lambda p: layered_grains(p, 1, [2.0, 1.0]), r"boundaries = \[2\.0, 1\.0\]"),
    (lambda p: competent_layer(p, "y", 0.0, -1.0, 2.0), r"thickness = -1\.0"),
    (lambda p: competent_layer(p, "y", 0.0, 1.0, 0.0), r"contrast = 0\.0"),
])
def test_layer_validation(call, words):
    with pytest.raises(ValueError, match=words):
        call(np.zeros((3, 3)))


# ---------------------------------------------------------------- data file and deck

def test_grains_section_round_trip(tmp_path):
    lat = hex_block_2d(8, D)
    grain = voronoi_grains(lat.positions, [0, 0], [8 * D, 8 * D], 5, 3)
    stiffness = particle_stiffness(grain, 1.0, 0.25, 3)
    path = tmp_path / "data.lattice"
    write_data(lat, path, 2.295e-3, grain=grain, stiffness=stiffness)
    ids, g, s = read_grains(path)
    assert np.array_equal(ids, np.arange(1, lat.n + 1))
    assert np.array_equal(g, grain)
    assert np.array_equal(s, stiffness)             # repr: exact round trip
    text = path.read_text()
    assert "\n\nGrains\n\n1 " in text
    assert np.array_equal(read_grain_strengths(path), np.ones(lat.n))   # three columns: 1


def test_grains_section_with_strength_factors(tmp_path):
    lat = hex_block_2d(6, D)
    grain = np.arange(lat.n) % 3
    stiffness = 1.0 + 0.1 * grain
    strength = 0.5 + 0.25 * grain
    path = tmp_path / "data.lattice"
    write_data(lat, path, 2.295e-3, grain=grain, stiffness=stiffness, strength=strength)
    ids, g, s = read_grains(path)
    assert np.array_equal(g, grain) and np.array_equal(s, stiffness)
    assert np.array_equal(read_grain_strengths(path), strength)
    with pytest.raises(ValueError, match="strength factor -1.0 \\(particle index 0\\)"):
        write_data(lat, path, 2.295e-3, grain=grain, stiffness=stiffness,
                   strength=-np.ones(lat.n))
    with pytest.raises(ValueError, match="give grain and stiffness too"):
        write_data(lat, path, 2.295e-3, strength=strength)
    # a section whose lines mix three and four columns names the line
    text = path.read_text().splitlines()
    k = text.index("Grains") + 3
    text[k] = " ".join(text[k].split()[:3])
    path.write_text("\n".join(text) + "\n")
    with pytest.raises(ValueError, match=f"line {k + 1}: .*as the section's first line"):
        read_grains(path)


def test_deck_grain_lines():
    bond = BondParameters(1e10, 1e9, 1e-7, 1e4, 0.2)
    common = dict(test="tension", dim=2, d=D, bond=bond, data_file="data.lattice", area=D,
                  eta=0.0, speed=0.1, steps=10)
    plain = deck_text(DeckSpec(**common))
    assert "property/atom" not in plain and "pair_style      lattice/bond\n" in plain
    text = deck_text(DeckSpec(**common, grains=GrainPairOptions(0.5, 1.5, 4711, 0.5),
                              shear_frame="corotational"))
    lines = text.splitlines()
    fix = lines.index("fix             grains all property/atom i_grain d_stiffness ghost yes")
    read = lines.index("read_data       data.lattice fix grains NULL Grains")
    assert fix < read
    assert ("pair_style      lattice/bond grain i_grain stiffness d_stiffness strength 0.5 1.5 "
            "seed 4711 boundary_strength 0.5 shear_frame corotational") in lines


def test_write_data_checks_the_arrays(tmp_path):
    lat = hex_block_2d(4, D)
    with pytest.raises(ValueError, match="both or neither"):
        write_data(lat, tmp_path / "d", 1.0, grain=np.zeros(lat.n, int))
    with pytest.raises(ValueError, match="17 grain ids"):
        write_data(lat, tmp_path / "d", 1.0, grain=np.zeros(17, int), stiffness=np.ones(17))
    with pytest.raises(ValueError, match="grain id -1"):
        write_data(lat, tmp_path / "d", 1.0, grain=-np.ones(lat.n, int),
                   stiffness=np.ones(lat.n))
    with pytest.raises(ValueError, match=r"stiffness factor 0\.0 \(particle index 0\)"):
        write_data(lat, tmp_path / "d", 1.0, grain=np.zeros(lat.n, int),
                   stiffness=np.zeros(lat.n))


def test_grain_model_validation():
    with pytest.raises(ValueError, match="source = 'hexagons'"):
        GrainModel("hexagons")
    with pytest.raises(ValueError, match="n_grains = 0"):
        GrainModel("voronoi")
    with pytest.raises(ValueError, match="needs a path"):
        GrainModel("elle")
    with pytest.raises(ValueError, match=r"layer_thickness = 0\.0"):
        GrainModel("layer")


def test_generate_command_writes_a_heterogeneous_block(tmp_path, capsys):
    from bonded_lattice.cli import main

    out = tmp_path / "poly"
    assert main(["generate", "--dim", "2", "--n", "15", "--test", "tension", "--grains", "8",
                 "--stiffness-sd", "0.2", "--strength", "0.5", "1.5", "--boundary-strength",
                 "0.4", "--grain-seed", "21", "--out", str(out)]) == 0
    ids, grain, stiffness = read_grains(out / "data.lattice")
    lat = hex_block_2d(15, D)
    assert len(ids) == lat.n == 247
    lo = lat.positions[:, :2].min(axis=0) - D / 2
    hi = lat.positions[:, :2].max(axis=0) + D / 2
    assert np.array_equal(grain, voronoi_grains(lat.positions, lo, hi, 8, 21))
    assert np.array_equal(stiffness, grain_stiffness(8, 1.0, 0.2, 21)[grain])
    deck = (out / "in.tension").read_text()
    assert "read_data       data.lattice fix grains NULL Grains" in deck
    # equal particles: atom_style atomic, the diameter given to the pair style
    assert ("lattice/bond grain i_grain stiffness d_stiffness strength 0.5 1.5 seed 21 "
            f"boundary_strength 0.4 diameter {D!r}\n") in deck
    assert "atom_style      atomic\n" in deck
    assert "8 grains of" in capsys.readouterr().out
    # bad input: the message names the value, exit status 2
    assert main(["generate", "--dim", "2", "--n", "15", "--grains", "8", "--boundary-strength",
                 "0", "--out", str(tmp_path / "bad")]) == 2
    assert "boundary_strength = 0.0 is out of range" in capsys.readouterr().err


def test_generate_command_layer(tmp_path):
    from bonded_lattice.cli import main

    out = tmp_path / "layer"
    assert main(["generate", "--dim", "2", "--n", "15", "--layer", "3e-3", "4",
                 "--out", str(out)]) == 0
    _, grain, stiffness = read_grains(out / "data.lattice")
    x = hex_block_2d(15, D).positions[:, 0]
    centre = 0.5 * (x.min() + x.max())          # 7 mm: the layer spans 5.5 to 8.5 mm
    in_layer = (x >= centre - 1.5e-3) & (x < centre + 1.5e-3)
    assert np.array_equal(grain, in_layer.astype(int))
    assert np.array_equal(stiffness, np.where(in_layer, 4.0, 1.0))
