"""Python workflow: conversion, deck writing, running, measuring, summary.json."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from bonded_lattice.cli import main
from bonded_lattice.conversion import bond_to_rock, rock_to_bond
from bonded_lattice.decks import DeckSpec, deck_text
from bonded_lattice.experiment import run_test
from bonded_lattice.rocks import get_rock
from helpers.materials import QUARTZ, QUARTZ_2D, WORKED


@pytest.mark.parametrize("dim", [2, 3])
def test_quartz_worked_values(dim):
    b = rock_to_bond(90e9, 0.16, 25e6, 252e6, 1.0, 1e-3, dim)
    # the sheet prints 5 significant digits
    np.testing.assert_allclose([b.Kn, b.Ks, b.Xb, b.Fs0, b.mu_p],
                               [WORKED[dim][k] for k in ("Kn", "Ks", "Xb", "Fs0", "mu_p")],
                               rtol=1e-4)


@pytest.mark.filterwarnings("ignore::UserWarning")  # random rocks may be unable to reach Cu
@pytest.mark.parametrize("dim", [2, 3])
def test_round_trips(dim):
    rng = np.random.default_rng(7)
    nu_max, mu_min = (0.25, 1 / math.sqrt(3)) if dim == 2 else (0.2, 1 / (2 * math.sqrt(2)))
    for _ in range(300):
        E, Tu, Cu = rng.uniform(1e9, 1e11), rng.uniform(1e6, 5e7), rng.uniform(2e7, 5e8)
        nu, mu_i, d = rng.uniform(0, nu_max), rng.uniform(mu_min, 2.0), rng.uniform(1e-4, 1e-2)
        b = rock_to_bond(E, nu, Tu, Cu, mu_i, d, dim)
        r = bond_to_rock(b.Kn, b.Ks, b.Xb, b.Fs0, b.mu_p, d, dim)
        # closed-form inverse: only round-off separates the two directions
        np.testing.assert_allclose([r.E, r.Tu, r.Cu, r.mu_i], [E, Tu, Cu, mu_i], rtol=1e-9)
        assert r.nu == pytest.approx(nu, abs=1e-12)


@pytest.mark.parametrize("args,fragment", [
    ((90e9, 0.3, 25e6, 252e6, 1.0, 1e-3, 2), "nu = 0.3 is out of range for a 2D lattice"),
    ((90e9, 0.22, 25e6, 252e6, 1.0, 1e-3, 3), "nu = 0.22 is out of range for a 3D lattice"),
    ((90e9, 0.16, 25e6, 252e6, 0.5, 1e-3, 2), "mu_i = 0.5 is out of range for a 2D lattice"),
    ((-1.0, 0.16, 25e6, 252e6, 1.0, 1e-3, 2), "E = -1.0 is out of range"),
    ((90e9, 0.16, 0.0, 252e6, 1.0, 1e-3, 2), "Tu = 0.0 is out of range"),
    ((90e9, 0.16, 25e6, -5.0, 1.0, 1e-3, 3), "Cu = -5.0 is out of range"),
    ((90e9, 0.16, 25e6, 252e6, 1.0, 0.0, 2), "d = 0.0 is out of range"),
    ((90e9, 0.16, 25e6, 252e6, 1.0, 1e-3, 4), "dim = 4 is out of range"),
])
def test_invalid_rock_properties_raise(args, fragment):
    with pytest.raises(ValueError, match=fragment.replace("(", r"\(")):
        rock_to_bond(*args)


@pytest.mark.parametrize("args,fragment", [
    ((-1.0, 1.0, 1e-7, 1.0, 0.1, 1e-3, 2), "Kn = -1.0 is out of range"),
    ((1.0, 2.0, 1e-7, 1.0, 0.1, 1e-3, 2), "Ks = 2.0 is out of range"),
    ((1.0, 0.5, 0.0, 1.0, 0.1, 1e-3, 3), "Xb = 0.0 is out of range"),
    ((1.0, 0.5, 1e-7, 1.0, 0.6, 1e-3, 2), "mu_p = 0.6 is out of range for a 2D lattice"),
    ((1.0, 0.5, 1e-7, 1.0, -0.1, 1e-3, 3), "mu_p = -0.1 is out of range"),
])
def test_invalid_bond_parameters_raise(args, fragment):
    with pytest.raises(ValueError, match=fragment):
        bond_to_rock(*args)


def test_deck_spec_rejects_bad_values():
    bond = QUARTZ[2]
    good = dict(test="tension", dim=2, d=1e-3, bond=bond, data_file="x", area=0.03, eta=1.0,
                speed=0.01, steps=10)
    DeckSpec(**good)
    for key, value, fragment in [("test", "shear", "test = 'shear' is not known"),
                                 ("speed", 0.0, "speed = 0.0 is out of range"),
                                 ("steps", 0, "steps = 0 is out of range"),
                                 ("eta", -1.0, "eta = -1.0 is out of range"),
                                 ("shear_frame", "rigid", "shear_frame = 'rigid' is not known")]:
        with pytest.raises(ValueError, match=fragment):
            DeckSpec(**{**good, key: value})
    text = deck_text(DeckSpec(**{**good, "test": "elastic"}))
    # the elastic test makes the bonds unbreakable (Liu et al. 2017): Xb, Fs0 x 100
    assert f"{100 * bond.Xb:.17g}" in text and "lattice/viscous" in text


def test_cli_convert_prints_pair_coeff(capsys):
    assert main(["convert", "--rock", "quartz", "--dim", "3"]) == 0
    out = capsys.readouterr().out
    assert "pair_coeff" in out and "46793831" in out
    assert main(["convert", "--dim", "2", "--bond", *QUARTZ_2D.split()]) == 0
    out = capsys.readouterr().out
    # the worked values carry 5 digits, so E comes back as 9.0000e10 to that precision
    E = float(out.split("E = ")[1].split()[0])
    assert E == pytest.approx(90e9, rel=1e-4)


def test_cli_reports_bad_rock(capsys):
    assert main(["convert", "--rock", "unobtainium"]) == 2
    assert "unknown rock 'unobtainium'" in capsys.readouterr().err


@pytest.mark.mpi
def test_end_to_end_elastic_run_writes_summary(tmp_path):
    summary = run_test(get_rock("quartz"), 2, "elastic", 30, tmp_path, np_=2, progress=False)
    saved = json.loads((tmp_path / "summary.json").read_text())
    assert saved["measured"] == summary["measured"]
    assert set(saved["target"]) == {"E", "nu"}
    assert (tmp_path / "stress_strain.png").stat().st_size > 10_000
    # with the stress over the centre-to-centre width, E of the 30-across block
    # matches the formula (measured +0.03%; the issue asks for 1%); nu from the
    # mid-height gauges too (measured -0.38%), while the all-particle fit carries a
    # free-side deficit that halves as N doubles (-1.8% at N = 30, docs/validation.md)
    assert abs(summary["relative_error"]["E"]) < 0.01
    assert abs(summary["relative_error"]["nu"]) < 0.01
    assert summary["nu_all_particles"] / 0.16 - 1 == pytest.approx(-0.018, abs=0.005)


def test_elastic_run_in_the_corotational_frame(tmp_path):
    """Small-strain E and nu of a 15-across 2D block with shear_frame corotational: the
    uniaxial strain is nearly a pure strain, so only the non-affine rotations near the
    corners and platens enter.  Measured against the fixed frame: E -7.6e-5, nu (mid-height
    gauges) -7.5e-4 relative; both within the issue's 1% of quartz, like the fixed frame."""
    results = {}
    for frame in ("fixed", "corotational"):
        results[frame] = run_test(get_rock("quartz"), 2, "elastic", 15, tmp_path / frame, np_=1,
                                  progress=False, shear_frame=frame)
    assert "shear_frame corotational" in (tmp_path / "corotational" / "in.elastic").read_text()
    assert "shear_frame" not in (tmp_path / "fixed" / "in.elastic").read_text()
    fixed, corot = results["fixed"]["measured"], results["corotational"]["measured"]
    print(f"fixed E {fixed['E']:.6g} nu {fixed['nu']:.6g}; corotational E {corot['E']:.6g} "
          f"nu {corot['nu']:.6g}")
    assert corot["E"] == pytest.approx(fixed["E"], rel=1e-3)
    assert corot["nu"] == pytest.approx(fixed["nu"], rel=3e-3)
    assert abs(results["corotational"]["relative_error"]["E"]) < 0.01
    assert abs(results["corotational"]["relative_error"]["nu"]) < 0.01


def test_coulomb_envelope_recovers_known_friction():
    from bonded_lattice.analysis import coulomb_envelope

    mu_i, cu = 0.8, 150e6
    q = (math.sqrt(1 + mu_i**2) + mu_i) ** 2
    s3 = np.array([0.0, 5e6, 10e6, 30e6])
    got_cu, got_mu = coulomb_envelope(s3, cu + q * s3)
    assert got_cu == pytest.approx(cu, rel=1e-12) and got_mu == pytest.approx(mu_i, rel=1e-12)
    with pytest.raises(ValueError, match="at least two different confining stresses"):
        coulomb_envelope([1e6, 1e6], [1e8, 2e8])


@pytest.mark.mpi
def test_confined_tests_give_internal_friction(tmp_path):
    from bonded_lattice.analysis import coulomb_envelope

    rock = get_rock("quartz")
    peaks = [run_test(rock, 2, "confined", 15, tmp_path / f"p{p:g}", np_=2, progress=False,
                      confining=p)["measured"]["sigma1"] for p in (0.0, 10e6, 20e6)]
    cu, mu_i = coulomb_envelope([0.0, 10e6, 20e6], peaks)
    # the envelope slope of the lattice follows the conversion's mu_i: measured
    # +3.4% at N = 15 (docs/validation.md); the strength itself carries the
    # multi-unit deficit (-13% at N = 15; papers: about -20%)
    assert mu_i == pytest.approx(rock.mu_i, rel=0.05)
    assert 0.7 * rock.Cu < cu < rock.Cu


def test_dump_trajectory_gives_the_same_elastic_constants(tmp_path):
    # E and nu measured a second way: particle displacements of the middle half of
    # the block read from the trajectory with MDAnalysis, stress from the platens
    s = run_test(get_rock("quartz"), 2, "elastic", 15, tmp_path, np_=1, progress=False,
                 dump_every=1)
    from_dump = s["measured_from_dump"]
    assert (tmp_path / "dump.lammpstrj").stat().st_size > 0
    # the in-deck fit uses all particles for the axial strain, the dump fit the
    # middle half: both see the homogeneous elastic field of the block
    assert from_dump["E"] == pytest.approx(s["measured"]["E"], rel=5e-3)
    assert from_dump["E"] == pytest.approx(90e9, rel=0.01)
    # the dump's lateral fit covers the whole width of the middle half, free faces
    # included: between the all-particle fit (-3.6% at N = 15) and the gauges
    # (-0.8%); measured -2.3%
    assert s["nu_all_particles"] < from_dump["nu"] < s["measured"]["nu"]


def test_elastic_fit_ignores_the_curve_after_micro_cracks_open():
    # a compression curve that is linear (E = 90 GPa) up to C_open at 30% of the
    # peak, drops, and climbs back through the fitting window at larger strains
    from bonded_lattice.analysis import youngs_modulus

    strain = np.linspace(0, 4e-3, 801)
    stress = 90e9 * strain
    knee = strain > 0.6e-3                       # 54 MPa, about 27% of the 200 MPa peak
    stress[knee] = 0.8 * 54e6 + 50e9 * (strain[knee] - 0.6e-3)
    stress = np.minimum(stress, 200e6)
    assert youngs_modulus(strain, stress) == pytest.approx(90e9, rel=1e-9)
