"""The periodic box of the Mike/Elle scenes in LAMMPS: the bonds across the seam are made
(3 N intact bonds), and an elastic step's stress from the virial pressure tensor is the
lattice's plane moduli, with no edge term; the break-by-break dumps (break_order) give the
same breaks as the plain loop.  Runs of 480-672 particles (< 4 s each)."""

from __future__ import annotations

import subprocess
import sys

import pytest
from bonded_lattice import runner
import numpy as np
from bonded_lattice.scenes import (Scene, break_sequence, break_steps, broken_bonds,
                                   plane_moduli, read_scene_dat, write_scene)


def run(scene: Scene, tmp_path, name: str = "run"):
    info = write_scene(scene, tmp_path / name)
    res = runner.run_deck(info["deck"], tmp_path / name, progress=False)
    assert res.returncode == 0, res.error
    return read_scene_dat(tmp_path / name / "scene.dat")


def elastic(deformation: str) -> Scene:
    """An unbreakable homogeneous box (strength x 100, no stiffness disorder), one step."""
    return Scene("polycrystal", n_x=20, n_steps=1, strain_step=1e-5, stiffness_sd=0.0,
                 strength_min=100.0, strength_max=100.0, deformation=deformation,
                 boundary="periodic")


@pytest.mark.parametrize("deformation", ["pure-shear", "uniaxial"])
def test_periodic_elastic_step_gives_the_plane_moduli(deformation, tmp_path):
    """One strain step of a homogeneous periodic box.

    Every particle has the same neighbourhood, so the affine displacement of change_box
    ... remap is the equilibrium (relaxed at once) and the stress is the bond sum over one
    particle's three bonds over its area sqrt3/2 d^2: sigma_xx = (lambda + 2 mu) e_xx +
    lambda e_yy, sigma_yy = lambda e_xx + (lambda + 2 mu) e_yy with lambda = mu = sqrt3/4 Kn
    (plane_moduli), exactly, with no edge term (the walls' sigma_xx has 1/(3 n_y) = 1.4 %
    here, test_scenes.py).  The deck's sigma is minus LAMMPS' virial pressure (area lx ly):
    this checks its sign and area factor.  Tolerance 1e-4: the geometric nonlinearity of a
    step of e = 1e-5 changes the stresses by a few e relative (2.2e-5 seen for sigma_yy in
    pure shear, the same with walls).  Uniaxial: the box's height is kept (e_yy = 0) and
    sigma_yy / sigma_xx = 1/3, the plane Poisson's ratio.
    """
    scene = elastic(deformation)
    dat = run(scene, tmp_path)
    exx, eyy, sxx, syy = dat["exx"][-1], dat["eyy"][-1], dat["sxx"][-1], dat["syy"][-1]
    assert exx == pytest.approx(1e-5, rel=1e-6)
    if deformation == "uniaxial":
        assert abs(eyy) < 1e-12
    else:
        assert eyy == pytest.approx(1 / (1 + 1e-5) - 1, rel=1e-6)
    assert dat["step"][-1] <= 2                        # relaxed at once
    lam, mu = plane_moduli(scene.bond.Kn)
    assert sxx == pytest.approx((lam + 2 * mu) * exx + lam * eyy, rel=1e-4)
    assert syy == pytest.approx(lam * exx + (lam + 2 * mu) * eyy, rel=1e-4)
    # no stress before the step: the lattice starts at its rest lengths
    assert abs(dat["sxx"][0]) < 1e-9 * abs(sxx) and abs(dat["syy"][0]) < 1e-9 * abs(sxx)


def test_periodic_box_bonds_across_the_seam(tmp_path):
    """The pair style bonds every touching pair, across the periodic faces too: 3 N intact
    bonds at the start (N = 20 x 24 = 480: 1440), where the wall box has the free edges'
    n_y (n_x - 1) + (2 n_x - 1)(n_y - 1) = 1353 (test_scenes.py)."""
    scene = elastic("pure-shear")
    dat = run(scene, tmp_path)
    assert dat["intact"][0] == 3 * scene.n == 1440
    assert dat["intact"][-1] == 1440                   # unbreakable: nothing broke


def test_cli_boundary_option(tmp_path):
    """--boundary periodic writes the periodic deck; a bad value is refused, naming the
    valid ones (argparse's choices)."""
    out = tmp_path / "cli"
    res = subprocess.run([sys.executable, "-m", "bonded_lattice.cli", "scene", "polycrystal",
                          "--n", "20", "--boundary", "periodic", "--out", str(out)],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    deck = (out / "in.polycrystal.quasistatic").read_text()
    assert "boundary        p p p" in deck and "setforce" not in deck
    bad = subprocess.run([sys.executable, "-m", "bonded_lattice.cli", "scene", "polycrystal",
                          "--boundary", "open", "--out", str(out)], capture_output=True,
                         text=True)
    assert bad.returncode == 2
    assert "invalid choice: 'open'" in bad.stderr and "'walls', 'periodic'" in bad.stderr


def test_break_order_gives_the_same_breaks_in_order(tmp_path):
    """A small periodic polycrystal (672 particles, 16 steps of 1e-5) with and without
    break_order: the maxbreak-1 loop relaxes, breaks the worst bond and relaxes again like
    break one, so the final broken bonds are the same set; the first 30 come in one dump
    each, in the order the plain run's breaks.txt logs, and their strain steps (from the bond
    dumps of every step) never decrease."""
    base = dict(kind="polycrystal", n_x=24, n_grains=8, n_steps=16, strain_step=1e-5,
                bond_dumps=1, boundary="periodic")
    run(Scene(**base), tmp_path, "plain")
    run(Scene(**base, break_order=30), tmp_path, "ordered")
    final = {name: {tuple(p) for p in broken_bonds(tmp_path / name / "bonds.final.txt")
                    [:, :2].astype(int).tolist()} for name in ("plain", "ordered")}
    assert len(final["plain"]) > 30 and final["plain"] == final["ordered"]
    sequence = break_sequence(tmp_path / "ordered", source="dumps")
    assert len(sequence) == 30
    # the command's own log of the plain run (breaks.txt) has them in the same order
    np.testing.assert_array_equal(sequence, break_sequence(tmp_path / "plain", source="log")[:30])
    dated = break_steps(tmp_path / "plain")
    steps = [dated[tuple(p)] for p in sequence.tolist()]
    assert np.all(np.diff(steps) >= 0)


def test_relax_local_and_direct_in_a_periodic_box_break_in_the_converged_order(tmp_path):
    """relax local (ghosts that are images of local particles, the corner ghosts passing
    forces on) and relax direct (springs across the seam by the ghosts' vectors, a factor
    of the torus) in a periodic box at their default tolerance, on 1 and 2 ranks, against
    LAMMPS' FIRE minimiser at 1e-5 of Kn Xb, a tolerance at which its order of breaks no
    longer changes (docs/lattice_quasistatic.rst, "Accuracy"): the same bonds in the same
    order."""
    base = dict(kind="polycrystal", n_x=20, n_grains=6, n_steps=10, strain_step=1e-5,
                boundary="periodic")
    orders = {}
    for name, relax, ftol, np_ in (("fire", "fire", 1e-5, 1), ("local", "local", None, 1),
                                   ("local2", "local", None, 2), ("direct", "direct", None, 1),
                                   ("direct2", "direct", None, 2)):
        info = write_scene(Scene(**base, relax=relax, ftol=ftol), tmp_path / name)
        res = runner.run_deck(info["deck"], tmp_path / name, np_=np_, progress=False)
        assert res.returncode == 0, res.error
        orders[name] = break_sequence(tmp_path / name, source="log")
    assert len(orders["fire"]) > 10, "the test must break bonds"
    np.testing.assert_array_equal(orders["local"], orders["fire"])
    np.testing.assert_array_equal(orders["local2"], orders["fire"])
    np.testing.assert_array_equal(orders["direct"], orders["fire"])
    np.testing.assert_array_equal(orders["direct2"], orders["fire"])
