"""The Mike/Elle scenes (bonded_lattice.scenes): geometry, decks, elastic wall stress and
where the first bonds break.

Each run is a few hundred to a thousand particles and a few strain steps (< 10 s).
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from bonded_lattice import runner
from bonded_lattice.conversion import BondParameters
from bonded_lattice.io import read_local_dump
from bonded_lattice.lattice import pairs_within, read_grain_strengths, read_grains
from bonded_lattice.scene_study import fracture_summary
from bonded_lattice.scenes import (Scene, bond_angles, box_lattice, break_sequence, break_steps,
                                   broken_bonds, build_model, central_spring_bond, plane_moduli,
                                   read_scene_dat, wall_masks, write_scene)

D = 1.0e-3


def run(scene: Scene, tmp_path, name: str = "run"):
    info = write_scene(scene, tmp_path / name)
    res = runner.run_deck(info["deck"], tmp_path / name, progress=False)
    assert res.returncode == 0, res.error
    return tmp_path / name, res


# ---------------------------------------------------------------- geometry, deck, data file

@pytest.mark.parametrize("n_x, n_y", [(5, 4), (12, 9), (30, 34)])
def test_box_lattice_is_a_full_triangular_lattice(n_x, n_y):
    """Every row holds n_x particles and every neighbour pair touches: horizontal bonds
    n_y (n_x - 1), bonds between neighbouring rows (2 n_x - 1) (n_y - 1) (counted by hand
    for rows alternately shifted by d/2)."""
    lat = box_lattice(n_x, n_y, D)
    assert lat.n == n_x * n_y
    i, j, r = pairs_within(lat.positions, 1.5 * D)
    assert np.allclose(r, D, rtol=1e-12)        # no second neighbours within 1.5 d
    assert len(r) == n_y * (n_x - 1) + (2 * n_x - 1) * (n_y - 1)
    walls = wall_masks(lat.positions, D)
    assert walls["left"].sum() == walls["right"].sum() == n_y
    assert walls["bottom"].sum() == walls["top"].sum() == n_x


def test_seed_resolutions_particle_counts():
    """The seed's medium and high resolutions: 184,800 and 737,600 particles in a square box."""
    medium = Scene("layer-extension", n_x=400, n_y=462, mode="dynamic")
    high = Scene("layer-extension", n_x=800, n_y=922, mode="dynamic")
    assert (medium.n, high.n) == (184_800, 737_600)
    for s in (medium, high):
        assert abs(s.height / s.width - 1) < 0.002     # square deformation box


def test_central_spring_bond_gives_the_rock_modulus():
    """Ks = 0 and mu_p = 0; the plane modulus 2 Kn / sqrt3 is E / (1 - nu^2) with nu = 1/4
    (plane strain), and the breaking stretch Xb = Tu d / (sqrt3 Kn)."""
    b = central_spring_bond(90e9, 25e6, D)
    assert b.Ks == 0.0 and b.mu_p == 0.0
    lam, mu = plane_moduli(b.Kn)
    assert 4 * mu * (lam + mu) / (lam + 2 * mu) == pytest.approx(90e9 / (1 - 0.25 ** 2), rel=1e-12)
    assert lam / (lam + 2 * mu) == pytest.approx(1 / 3, rel=1e-12)   # plane Poisson's ratio
    assert b.Xb == pytest.approx(25e6 * D / (math.sqrt(3) * b.Kn), rel=1e-12)


def test_scene_checks_its_parameters():
    with pytest.raises(ValueError, match="kind"):
        Scene("fold")
    with pytest.raises(ValueError, match="Ks"):
        Scene("polycrystal", bond=BondParameters(1e10, 1e9, 1e-7, 1.0, 0.0))
    with pytest.raises(ValueError, match="n_expanding"):
        Scene("expanding", n_grains=3, n_expanding=3)
    with pytest.raises(ValueError, match="strength"):
        Scene("polycrystal", strength_min=1.2, strength_max=0.8)
    with pytest.raises(ValueError, match="matrix_strength = 2.0 with kind = 'polycrystal'"):
        Scene("polycrystal", matrix_strength=2.0)
    with pytest.raises(ValueError, match="matrix_strength = 0.0 is out of range"):
        Scene("layer-extension", matrix_strength=0.0)


def test_matrix_strength_scales_the_matrix_bonds(tmp_path):
    """matrix_strength 4: the data file gives the matrix's particles strength factor 4 and
    the layer's 1; in LAMMPS a bond's breaking force is Kn Xb times its draw in [0.8, 1.2)
    times the mean of its particles' factors: [0.8, 1.2) in the layer, [3.2, 4.8) in the
    matrix, 2.5 x [0.8, 1.2) across the interfaces (boundary_strength 1)."""
    scene = Scene("layer-extension", n_x=16, matrix_strength=4.0, n_steps=1)
    model = build_model(scene)
    info = write_scene(scene, tmp_path)
    assert np.array_equal(read_grain_strengths(info["data"]),
                          np.where(model.grain == 0, 4.0, 1.0))
    deck = open(info["deck"]).read()
    assert "boundary_strength 1.0 strength_factor d_strength" in deck
    assert "property/atom i_grain d_stiffness d_strength ghost yes" in deck
    # the model as the deck builds it, before the loading: every bond's breaking force
    head = deck.split("# ---- quasi-static loading")[0] + (
        "compute         fb all lattice/bond/local id1 id2 fb\n"
        "dump            fbd all local 1 fb.txt c_fb[*]\n"
        "run             0 post no\n")
    (tmp_path / "in.fb").write_text(head)
    res = runner.run_deck(tmp_path / "in.fb", tmp_path, progress=False)
    assert res.returncode == 0, res.error
    rows = read_local_dump(tmp_path / "fb.txt")[1]
    g1, g2 = (model.grain[rows[:, k].astype(int) - 1] for k in (0, 1))
    factor = rows[:, 2] / (scene.bond.Kn * scene.bond.Xb)
    for mask, mean in ((g1 + g2 == 2, 1.0), (g1 + g2 == 0, 4.0), (g1 != g2, 2.5)):
        assert mask.sum() > 20
        # the draw's range [0.8, 1.2) times the mean factor, to round-off
        assert factor[mask].min() >= 0.8 * mean * (1 - 1e-12)
        assert factor[mask].max() < 1.2 * mean * (1 + 1e-12)


@pytest.mark.parametrize("kind", ["layer-extension", "polycrystal", "expanding"])
def test_data_file_and_deck_round_trip(kind, tmp_path):
    """The data file's Grains section gives back the model's arrays bit for bit, and the
    deck carries the pair style's grain keywords and the loading of its mode."""
    scene = Scene(kind, n_x=16, n_grains=6, n_expanding=1)
    model = build_model(scene)
    for mode in ("quasistatic", "dynamic"):
        info = write_scene(Scene(**{**scene.__dict__, "mode": mode}), tmp_path)
        ids, grain, stiffness = read_grains(info["data"])
        assert np.array_equal(ids, np.arange(1, scene.n + 1))
        assert np.array_equal(grain, model.grain)
        assert np.array_equal(stiffness, model.stiffness)
        deck = open(info["deck"]).read()
        factor = 1.0 if kind.startswith("layer") else 0.5
        assert f"strength 0.8 1.2 seed 1 boundary_strength {factor}" in deck
        assert ("lattice/quasistatic ftol" in deck) == (mode == "quasistatic")
        assert ("fix             integrate all lattice/nve" in deck) == (mode == "dynamic")
        assert ("fix             expand grow adapt" in deck) == (kind == "expanding"
                                                               and mode == "dynamic")
    if kind == "layer-extension":
        # the layer: grain 1, the stiffness contrast, 20 % of the height across the middle
        y = model.lattice.positions[:, 1]
        inside = model.grain == 1
        assert set(np.unique(model.stiffness[inside])) == {3.0}
        assert abs(np.ptp(y[inside]) - 0.2 * np.ptp(y)) < 1.5 * D
        assert abs(y[inside].mean() - y.mean()) < D


def test_cli_writes_a_scene(tmp_path):
    out = tmp_path / "cli"
    res = subprocess.run([sys.executable, "-m", "bonded_lattice.cli", "scene", "polycrystal",
                          "--n", "20", "--mode", "dynamic", "--out", str(out)],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    assert "20 particles" not in res.stdout and "480 particles" in res.stdout
    assert (out / "in.polycrystal.dynamic").exists()
    assert "expected memory" in res.stdout


# ---------------------------------------------------------------- elastic wall stress

def test_elastic_step_wall_stress_matches_the_plane_moduli(tmp_path):
    """One pure-shear step (x by 1 + e, y by 1/(1 + e)) of an unbreakable homogeneous box.

    The affine displacement of change_box is already the equilibrium (every
    wall particle's bonds are symmetric about its wall's normal), so the
    relaxation ends at once and the wall reactions are those of a homogeneous
    strain.  Expected: sigma = (lambda + 2 mu) e_own + lambda e_other, lambda = mu
    = sqrt3/4 Kn.  sigma_yy: the top row's 2 n_x - 1 bonds carry (n_x - 1/2) d
    exactly; sigma_xx: a column is crossed by n_y horizontal and n_y - 1 diagonal
    bonds, an edge term: for pure shear the wall force is (3 n_y + 1)/(3 n_y)
    times the continuum value (1.4 % for n_y = 24), computed here bond by bond.
    Tolerances: 1e-4 for the discrete values (geometric nonlinearity, O(e) =
    1e-5) and 2 % for the continuum value of sigma_xx.
    """
    scene = Scene("polycrystal", n_x=20, n_steps=1, strain_step=1e-5, stiffness_sd=0.0,
                  strength_min=100.0, strength_max=100.0)
    folder, _ = run(scene, tmp_path)
    dat = read_scene_dat(folder / "scene.dat")
    exx, eyy, sxx, syy = dat["exx"][-1], dat["eyy"][-1], dat["sxx"][-1], dat["syy"][-1]
    assert exx == pytest.approx(1e-5, rel=1e-6)
    assert eyy == pytest.approx(1 / (1 + 1e-5) - 1, rel=1e-6)
    assert dat["step"][-1] <= 2                        # relaxed at once
    lam, mu = plane_moduli(scene.bond.Kn)
    n_y = scene.rows
    # sigma_yy: exact
    assert syy == pytest.approx(lam * exx + (lam + 2 * mu) * eyy, rel=1e-4)
    # sigma_xx bond by bond: horizontal bonds stretch e_xx d, diagonals (e_xx/4 + 3 e_yy/4) d
    kn = scene.bond.Kn
    force = n_y * kn * D * exx + (n_y - 1) * kn * D * (exx / 4 + 3 * eyy / 4) / 2
    assert sxx == pytest.approx(force / (n_y * math.sqrt(3) / 2 * D * (1 + eyy)), rel=1e-4)
    continuum = (lam + 2 * mu) * exx + lam * eyy
    assert sxx == pytest.approx(continuum, rel=0.02)
    assert abs(sxx / continuum - 1) > 0.005          # the edge term is there (1.4 %)


# ---------------------------------------------------------------- where bonds break first

def first_broken(folder):
    dated = break_steps(folder)
    assert dated, "no bond broke"
    first = min(dated.values())
    return first, np.array([k for k, step in dated.items() if step == first])


def test_competent_layer_breaks_first_under_extension(tmp_path):
    """Layer 3 times stiffer than the matrix, same strengths: its horizontal bonds break
    at a third of the matrix's stretch (Kn Xb fixed, Kn x 3), so the first broken bonds
    all join two particles of the layer (grain 1).  Steps of 5e-6: with 1.5e-5 the
    step in which the layer cracks also carries a crack tip one row into the matrix."""
    scene = Scene("layer-extension", n_x=24, n_steps=12, strain_step=5e-6, bond_dumps=1)
    folder, _ = run(scene, tmp_path)
    model = build_model(scene)
    step, pairs = first_broken(folder)
    # a horizontal layer bond of strength factor g breaks at e = g Xb / (3 d) = 5.8e-5 g:
    # not before step 10 (5e-5, g < 0.864), and of the ~140 such bonds (g uniform in
    # [0.8, 1.2)) one is below 0.864 with probability 1 - 0.84^140 ~ 1; the matrix's
    # need e = 0.8 Xb / d = 1.4e-4
    assert step == 10
    assert np.all(model.grain[pairs - 1] == 1)        # both ends in the layer
    # the summary's measure of the same bonds (scene_study.fracture_summary): all in it
    assert fracture_summary(scene, model, pairs)["fraction_in_layer"] == 1.0


def test_layer_compression_breaks_inclined_bonds_only(tmp_path):
    """Layer-parallel compression, relaxed by relax local: the box shortens along x and
    lengthens along y, so every bond along x is compressed (eps_xx < 0 is continuous across
    the layer's interfaces) and a central spring breaks only in tension: the first bond to
    break (breaks.txt, the command's log in order) is inclined (60 or 120 degrees; once
    cracks open, a bond along x beside one can be pulled), and the walls are in compression
    along x up to that step."""
    scene = Scene("layer-compression", n_x=24, n_steps=30, strain_step=1e-5, bond_dumps=1,
                  relax="local")
    folder, _ = run(scene, tmp_path)
    model = build_model(scene)
    step, pairs = first_broken(folder)
    logged = break_sequence(folder)
    angle = bond_angles(logged[:1], model.lattice.positions)[0]
    assert min(angle, 180.0 - angle) == pytest.approx(60.0, abs=1e-6)
    dat = read_scene_dat(folder / "scene.dat")
    assert np.all(dat["sxx"][1:step + 1] < 0)
    # the log's first breaks are the bonds the dumps find broken at that first step
    assert {tuple(p) for p in logged[:len(pairs)].tolist()} == {tuple(p) for p in pairs.tolist()}


def test_expanding_grain_breaks_its_surroundings_first(tmp_path):
    """One grain grows; the first bonds to break touch the grain or lie within two
    diameters of it, and the walls, held, are pushed (compressive wall stress)."""
    scene = Scene("expanding", n_x=24, n_grains=8, n_expanding=1, n_steps=8,
                  strain_step=1e-4, bond_dumps=1)
    folder, _ = run(scene, tmp_path)
    model = build_model(scene)
    grown = model.lattice.positions[np.isin(model.grain, model.expanding), :2]
    step, pairs = first_broken(folder)
    mids = 0.5 * (model.lattice.positions[pairs[:, 0] - 1, :2]
                  + model.lattice.positions[pairs[:, 1] - 1, :2])
    dist = np.min(np.linalg.norm(mids[:, None, :] - grown[None, :, :], axis=2), axis=1)
    assert np.all(dist <= 2.0 * D)
    dat = read_scene_dat(folder / "scene.dat")
    assert np.all(dat["sxx"][1:] < 0) and np.all(dat["syy"][1:] < 0)
    assert dat["growth"][-1] == pytest.approx((1 + 1e-4) ** 8 - 1, rel=1e-9)


def test_dynamic_polycrystal_breaks_on_grain_boundaries_first(tmp_path):
    """Dynamic loading of a small polycrystal: grain boundaries have half the strength, so
    the first broken bonds join different grains; every break is tensile (central springs)."""
    scene = Scene("polycrystal", n_x=20, n_grains=6, n_steps=10, strain_step=1e-5,
                  mode="dynamic", crossings=20, bond_dumps=1)
    folder, _ = run(scene, tmp_path)
    model = build_model(scene)
    _, pairs = first_broken(folder)
    assert np.all(model.grain[pairs[:, 0] - 1] != model.grain[pairs[:, 1] - 1])
    assert fracture_summary(scene, model, pairs)["intergranular_fraction"] == 1.0
    final = broken_bonds(folder / "bonds.final.txt")
    assert len(final) > 0 and np.all(final[:, 2] == 1)


def test_uniaxial_step_wall_stresses_match_the_plane_moduli(tmp_path):
    """One uniaxial step (x by 1 + e, the y walls held) of an unbreakable homogeneous box:
    sigma_yy = lambda e_xx exactly (the top row's bonds, see the pure-shear test) and
    sigma_xx = (lambda + 2 mu) e_xx up to the edge term of the n_y - 1 diagonal bonds
    (1/(3 n_y) of it in pure shear; here the diagonals carry e/4 against the horizontals' e,
    so the bond-by-bond value is checked to 1e-4 and the continuum to 2 %); their ratio is
    the lattice's plane value lambda / (lambda + 2 mu) = 1/3."""
    scene = Scene("polycrystal", n_x=20, n_steps=1, strain_step=1e-5, stiffness_sd=0.0,
                  strength_min=100.0, strength_max=100.0, deformation="uniaxial")
    folder, _ = run(scene, tmp_path)
    dat = read_scene_dat(folder / "scene.dat")
    exx, eyy, sxx, syy = dat["exx"][-1], dat["eyy"][-1], dat["sxx"][-1], dat["syy"][-1]
    assert exx == pytest.approx(1e-5, rel=1e-6)
    assert abs(eyy) < 1e-12
    lam, mu = plane_moduli(scene.bond.Kn)
    assert syy == pytest.approx(lam * exx, rel=1e-4)
    n_y, kn = scene.rows, scene.bond.Kn
    force = n_y * kn * D * exx + (n_y - 1) * kn * D * (exx / 4) / 2
    assert sxx == pytest.approx(force / (n_y * math.sqrt(3) / 2 * D), rel=1e-4)
    assert sxx == pytest.approx((lam + 2 * mu) * exx, rel=0.02)


def test_uniaxial_is_refused_for_growing_grains():
    with pytest.raises(ValueError, match="deformation = 'uniaxial': growing grains"):
        Scene("expanding", deformation="uniaxial")
