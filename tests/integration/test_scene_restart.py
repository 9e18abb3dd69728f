"""A quasi-static scene cut off and resumed from its last restart file (``Scene.restart_every``,
``bonded-lattice scene ... --restart N --run --resume``) against the same scene run whole.

The cut: the deck run with ``-var nsteps 3`` (as a run stopped during step 4 would have
left it, plus step 3's lines, which the resume must drop), restart files every 2 steps, so
the resume starts after step 2. Each run is 1840 particles and 6 strain steps (< 5 s).
"""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest
from bonded_lattice import runner
from bonded_lattice.scene_study import run_scene
from bonded_lattice.scenes import (Scene, break_sequence, read_scene_dat, resume_deck,
                                   write_scene)

STEPS, EVERY, CUT = 6, 2, 3


def scene_of(kind: str, relax: str, boundary: str = "walls", atom_style: str = "sphere") -> Scene:
    extra = {"n_grains": 6, "n_expanding": 1, "strain_step": 2e-4} if kind == "expanding" else {}
    return Scene(kind, n_steps=STEPS, restart_every=EVERY, relax=relax, boundary=boundary,
                 atom_style=atom_style, **extra)


def whole_and_resumed(scene: Scene, tmp_path):
    """The scene run whole and run cut off after step CUT, then resumed (1 rank each)."""
    whole = tmp_path / "whole"
    run_scene(scene, whole, pictures=False)
    cut = tmp_path / "cut"
    info = write_scene(scene, cut)
    res = runner.run_deck(info["deck"], cut, progress=False, extra_args=["-var", "nsteps", str(CUT)])
    assert res.returncode == 0, res.error
    assert (cut / "restart.step").read_text().split() == ["variable", "kdone", "equal", "2"]
    summary = run_scene(scene, cut, pictures=False, resume=True)
    assert summary["resumed_from_step"] == 2
    return whole, cut


@pytest.mark.parametrize("kind, boundary, atom_style", [("layer-extension", "walls", "sphere"),
                                                        ("polycrystal", "periodic", "atomic"),
                                                        ("expanding", "walls", "sphere")])
def test_relax_local_resumed_is_the_whole_run_to_the_bit(tmp_path, kind, boundary, atom_style):
    """relax local keeps nothing between its calls, so a resumed run repeats the whole run
    exactly: the breaks (order, ratios), scene.dat (strains, stresses, counts) and the final
    bond records are the same files (atom_style atomic: the mass per type and the pair
    style's diameter come back from the restart file)."""
    whole, cut = whole_and_resumed(scene_of(kind, "local", boundary, atom_style), tmp_path)
    assert len(break_sequence(whole)) > 5, "the test must break bonds"
    for name in ("breaks.txt", "scene.dat", "bonds.final.txt"):
        assert (cut / name).read_bytes() == (whole / name).read_bytes(), name


def test_relax_direct_resumed_breaks_the_same_bonds(tmp_path):
    """relax direct keeps its factor from one call to the next; the resumed run makes it
    anew, so its Newton steps stop at another point within the tolerance: the same bonds in
    the same order, the same counts and strains to the bit, the stresses to the tolerance
    (ftol = 1e-4 of a bond's breaking force, the scale of the forces the walls sum)."""
    whole, cut = whole_and_resumed(scene_of("layer-extension", "direct"), tmp_path)
    order = break_sequence(whole)
    assert len(order) > 5, "the test must break bonds"
    np.testing.assert_array_equal(break_sequence(cut), order)
    a, b = read_scene_dat(whole / "scene.dat"), read_scene_dat(cut / "scene.dat")
    for column in ("k", "exx", "eyy", "intact", "tension", "shear"):
        np.testing.assert_array_equal(b[column], a[column])
    for column in ("sxx", "syy"):
        np.testing.assert_allclose(b[column], a[column], rtol=1e-4,
                                   atol=1e-4 * np.abs(a[column]).max())


def test_resume_names_what_is_missing_or_wrong(tmp_path):
    scene = scene_of("layer-extension", "local")
    with pytest.raises(ValueError, match=r"restart.scene, restart.step, restart.vars, "
                       r"scene.dat missing.*--restart N"):
        resume_deck(scene, tmp_path)
    # a finished run: nothing to go on with
    run_scene(scene, tmp_path / "done", pictures=False)
    with pytest.raises(ValueError, match=r"holds strain step 6 of 6: the run had finished"):
        resume_deck(scene, tmp_path / "done")
    # restart files are the quasi-static loop's
    with pytest.raises(ValueError, match=r"restart_every = 2 with mode = 'dynamic'"):
        dataclasses.replace(scene, mode="dynamic")
    with pytest.raises(ValueError, match=r"restart_every = -1 is out of range: need >= 0"):
        dataclasses.replace(scene, restart_every=-1)
    with pytest.raises(ValueError, match=r"only a quasi-static scene with restart_every > 0"):
        resume_deck(dataclasses.replace(scene, restart_every=0), tmp_path / "done")


def test_the_command_line_resumes_only_a_run(tmp_path):
    """--resume without --run: the command says what is missing."""
    out = subprocess.run([sys.executable, "-m", "bonded_lattice.cli", "scene", "layer-extension",
                          "--restart", "2", "--resume", "--out", str(tmp_path / "s")],
                         capture_output=True, text=True)
    assert out.returncode != 0
    assert "--resume goes on with a run; add --run" in out.stderr
