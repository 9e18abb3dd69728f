"""The scenes' quasi-static relaxation in the deck: relax direct by default, its threads, and
the choices that are refused."""

from __future__ import annotations

import re

import pytest
from bonded_lattice.scene_deck import deck_text
from bonded_lattice.scenes import DEFAULT_FTOL, RELAXATIONS, Scene


def quasistatic_line(scene: Scene) -> str:
    lines = [line for line in deck_text(scene).splitlines()
             if line.startswith("lattice/quasistatic")]
    assert len(lines) == 1, lines
    return lines[0]


def test_relax_direct_is_the_default_with_its_tolerance():
    scene = Scene("layer-extension", n_x=8)
    assert scene.relax == "direct" and "direct" in RELAXATIONS
    line = quasistatic_line(scene)
    assert " relax direct quiet yes " in line and "threads" not in line
    # ftol = 1e-4 of a bond's breaking force Kn Xb, written with 6 significant digits
    ftol = float(re.search(r"ftol (\S+)", line).group(1))
    assert ftol == pytest.approx(DEFAULT_FTOL["direct"] * scene.bond.Kn * scene.bond.Xb, rel=1e-5)


def test_threads_go_to_relax_direct():
    line = quasistatic_line(Scene("polycrystal", n_x=8, threads=2))
    assert " relax direct quiet yes threads 2 " in line


@pytest.mark.parametrize("kwargs, message", [
    ({"threads": 0}, r"threads = 0 is out of range: need >= 1"),
    ({"threads": 2, "relax": "local"}, r"threads = 2 with relax = 'local'"),
    ({"relax": "exact"}, r"relax = 'exact' is not known: use one of local, direct, fire"),
])
def test_bad_relaxation_choices_name_the_value(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Scene("layer-extension", n_x=8, **kwargs)
