"""bonded_lattice.dumps on synthetic dumps of known affine deformations."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from bonded_lattice import dumps
from bonded_lattice.lattice import close_packed_block_3d, hex_block_2d

REL = 1e-9
STEPS = [0, 100, 200, 300, 400, 500]


def write_dump(path: Path, frames: list[tuple[int, np.ndarray, np.ndarray]],
               box: tuple[float, float] = (-1e-3, 2e-2)) -> None:
    """Write (step, ids, positions) frames as the decks do: custom columns, %.17g."""
    with open(path, "w") as f:
        for step, ids, x in frames:
            f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(ids)}\n"
                    "ITEM: BOX BOUNDS ff ff ff\n")
            f.write(f"{box[0]:.16e} {box[1]:.16e}\n" * 3)
            f.write("ITEM: ATOMS id type x y z c_nbonds\n")
            f.writelines(f"{i} 1 {p[0]:.17g} {p[1]:.17g} {p[2]:.17g} 6\n" for i, p in zip(ids, x))


def deform(x0: np.ndarray, g: np.ndarray, shift: np.ndarray) -> np.ndarray:
    """x = x0 + u0 + G (x0 - centre): an affine deformation plus a rigid shift."""
    return x0 + shift + (x0 - x0.mean(axis=0)) @ g.T


def loading_frames(x0: np.ndarray, diag: tuple[float, float, float]):
    """Frames k = 0..5 with strain k * diag and a drifting rigid shift."""
    ids = np.arange(1, len(x0) + 1)
    shift = np.array([3e-7, -2e-7, 1e-7 if np.ptp(x0[:, 2]) > 0 else 0.0])
    return [(s, ids, deform(x0, np.diag(diag) * k, shift * k)) for k, s in enumerate(STEPS)]


@pytest.fixture
def x2d() -> np.ndarray:
    return hex_block_2d(15, 1e-3).positions + [2e-3, 1e-3, 0.0]


@pytest.fixture
def x3d() -> np.ndarray:
    return close_packed_block_3d(6, 1e-3).positions


def test_read_frames_float64_absolute_metres(tmp_path, x2d):
    # 1e-7 m steps on 1e-2 m coordinates: lost in float32 or %g
    x1 = x2d * (1 + 1e-5) + 1e-7
    ids = np.arange(1, len(x2d) + 1)
    write_dump(tmp_path / "d", [(0, ids, x2d), (7, ids, x1)])
    steps, x = dumps.read_frames(tmp_path / "d")
    assert steps.tolist() == [0, 7]
    assert x.dtype == np.float64 and x.shape == (2, len(x2d), 3)
    np.testing.assert_array_equal(x[0], x2d)  # not shifted to the box corner
    np.testing.assert_array_equal(x[1], x1)


def test_read_frames_sorts_by_id(tmp_path, x3d):
    rng = np.random.default_rng(1)
    ids = np.arange(1, len(x3d) + 1)
    x1 = x3d + 1e-6 * rng.standard_normal(x3d.shape)
    frames = []
    for step, x in [(0, x3d), (10, x1)]:
        order = rng.permutation(len(x))
        frames.append((step, ids[order], x[order]))
    assert not np.array_equal(frames[0][1], frames[1][1])
    write_dump(tmp_path / "d", frames)
    _, x = dumps.read_frames(tmp_path / "d")
    np.testing.assert_array_equal(x[0], x3d)
    np.testing.assert_array_equal(x[1], x1)


@pytest.mark.parametrize("content", [None, ""])
def test_missing_or_empty_file_names_it(tmp_path, content):
    path = tmp_path / "dump.nothere"
    if content is not None:
        path.write_text(content)
    with pytest.raises(ValueError, match="dump.nothere"):
        dumps.read_frames(path)


def test_atoms_changing_between_frames(tmp_path, x2d):
    ids = np.arange(1, len(x2d) + 1)
    write_dump(tmp_path / "fewer", [(0, ids, x2d), (1, ids[:-1], x2d[:-1])])
    with pytest.raises(ValueError, match="fewer"):
        dumps.read_frames(tmp_path / "fewer")
    other = ids.copy()
    other[-1] += 1000
    write_dump(tmp_path / "renumbered", [(0, ids, x2d), (1, other, x2d)])
    with pytest.raises(ValueError, match="renumbered.*step 1"):
        dumps.read_frames(tmp_path / "renumbered")


def test_incomplete_last_frame(tmp_path, x2d):
    """A dump read while LAMMPS is still writing it: MDAnalysis alone drops the frame."""
    ids = np.arange(1, len(x2d) + 1)
    write_dump(tmp_path / "d", [(0, ids, x2d), (1, ids, x2d)])
    lines = (tmp_path / "d").read_text().splitlines(keepends=True)
    (tmp_path / "cut").write_text("".join(lines[:-5]))
    with pytest.raises(ValueError, match="cut.*incomplete"):
        dumps.read_frames(tmp_path / "cut")


def test_displacement_gradient_3d(x3d):
    g = np.array([[1.0, 2.0, -0.5], [0.3, -1.5, 0.7], [-0.2, 0.4, 2.5]]) * 1e-4
    x = deform(x3d, g, np.array([1e-6, -2e-6, 3e-6]))
    np.testing.assert_allclose(dumps.displacement_gradient(x3d, x), g, rtol=REL, atol=REL * 1e-4)
    sel = x3d[:, 0] < x3d[:, 0].mean()
    np.testing.assert_allclose(dumps.displacement_gradient(x3d, x, sel), g, rtol=REL, atol=REL * 1e-4)


def test_displacement_gradient_2d_leaves_z_zero(x2d):
    g = np.array([[0.16, 0.05, 0.0], [-0.03, -1.0, 0.0], [0.0, 0.0, 0.0]]) * 1e-4
    x = deform(x2d, g, np.array([1e-6, -2e-6, 0.0]))
    got = dumps.displacement_gradient(x2d, x)
    np.testing.assert_allclose(got, g, rtol=REL, atol=REL * 1e-4)
    assert np.all(got[2] == 0) and np.all(got[:, 2] == 0)


def test_displacement_gradient_needs_spanning_points(x2d):
    one_row = x2d[:, 1] == x2d[0, 1]
    with pytest.raises(ValueError, match="span"):
        dumps.displacement_gradient(x2d, x2d, one_row)


def test_central_selection_middle_half():
    rng = np.random.default_rng(2)
    h = np.linspace(0.0, 1.0, 11)  # no point on the quarter marks
    x0 = np.column_stack([rng.random(11), h, rng.random(11)])
    np.testing.assert_array_equal(dumps.central_selection(x0, 1), (h > 0.26) & (h < 0.74))
    assert dumps.central_selection(x0, 1).sum() == 5
    assert dumps.central_selection(x0, 1, 1.0).all()
    x0[:, [1, 2]] = x0[:, [2, 1]]
    np.testing.assert_array_equal(dumps.central_selection(x0, 2, 0.3), (h > 0.36) & (h < 0.64))
    with pytest.raises(ValueError, match="height_fraction"):
        dumps.central_selection(x0, 2, 0.0)


def test_strains_2d(tmp_path, x2d):
    write_dump(tmp_path / "d", loading_frames(x2d, (0.16e-4, -1e-4, 0.0)))
    s = dumps.strains_from_dump(tmp_path / "d", 2)
    k = np.arange(len(STEPS))
    assert s["step"].tolist() == STEPS
    np.testing.assert_allclose(s["axial"], -1e-4 * k, rtol=REL, atol=1e-4 * REL)
    np.testing.assert_allclose(s["lateral"], 0.16e-4 * k, rtol=REL, atol=1e-4 * REL)
    assert np.isnan(s["lateral_x"]).all() and np.isnan(s["lateral_y"]).all()
    assert dumps.poisson_ratio_from_dump(tmp_path / "d", 2) == pytest.approx(0.16, rel=REL)


def test_strains_3d_separates_lateral_axes(tmp_path, x3d):
    write_dump(tmp_path / "d", loading_frames(x3d, (0.1e-4, 0.2e-4, -1e-4)))
    s = dumps.strains_from_dump(tmp_path / "d", 3)
    k = np.arange(len(STEPS))
    for key, eps in [("axial", -1e-4), ("lateral_x", 0.1e-4), ("lateral_y", 0.2e-4),
                     ("lateral", 0.15e-4)]:
        np.testing.assert_allclose(s[key], eps * k, rtol=REL, atol=1e-4 * REL, err_msg=key)
    assert dumps.poisson_ratio_from_dump(tmp_path / "d", 3) == pytest.approx(0.15, rel=REL)


def test_strains_use_only_the_central_zone(tmp_path, x2d):
    """Extra bulging at the ends (like platen friction) must not reach the gauge."""
    y = x2d[:, 1]
    mid, height = 0.5 * (y.min() + y.max()), np.ptp(y)
    end = np.maximum(0.0, np.abs(y - mid) - 0.3 * height)  # zero over the middle 60 %
    ids = np.arange(1, len(x2d) + 1)
    frames = []
    for k, step in enumerate(STEPS):
        x = deform(x2d, np.diag([0.2e-4, -1e-4, 0.0]) * k, np.zeros(3))
        x[:, 0] += 0.05 * k * end * (x2d[:, 0] - x2d[:, 0].mean())
        frames.append((step, ids, x))
    write_dump(tmp_path / "d", frames)
    assert dumps.poisson_ratio_from_dump(tmp_path / "d", 2) == pytest.approx(0.2, rel=REL)
    whole = dumps.poisson_ratio_from_dump(tmp_path / "d", 2, height_fraction=1.0)
    assert whole > 0.2 * (1 + 1e-3)


def test_dim_must_match_dump(tmp_path, x2d):
    write_dump(tmp_path / "d", loading_frames(x2d, (0.16e-4, -1e-4, 0.0)))
    with pytest.raises(ValueError, match="dim = 3"):
        dumps.strains_from_dump(tmp_path / "d", 3)


def test_read_atom_frame_picks_one_frame_sorted_by_id(tmp_path, x2d):
    """read_atom_frame returns exactly the rows of the asked frame (ids written reversed, read
    back in order) and names the file when the frame is missing."""
    from bonded_lattice.io import read_atom_frame

    ids = np.arange(len(x2d), 0, -1)
    frames = [(step, ids, x2d + 1e-6 * k) for k, step in enumerate(STEPS)]
    write_dump(tmp_path / "t.lammpstrj", frames)
    names, rows = read_atom_frame(tmp_path / "t.lammpstrj", STEPS[3])
    assert names == ["id", "type", "x", "y", "z", "c_nbonds"]
    assert rows[:, 0].tolist() == list(range(1, len(x2d) + 1))
    # row of id i is the position written for id i: x2d[len - i] shifted by frame 3's 3e-6
    np.testing.assert_allclose(rows[:, 2:5], (x2d + 3e-6)[::-1], rtol=REL, atol=0)
    with pytest.raises(ValueError, match="t.lammpstrj: no frame at time step 7"):
        read_atom_frame(tmp_path / "t.lammpstrj", 7)
