"""The pair style warns once, with the lines to use, when LAMMPS' general fix nve (with fix
enforce2d in 2D) or fix viscous moves or damps its particles: fix lattice/nve and fix
lattice/viscous do the same arithmetic in fewer passes.  The deck is one a user writes
from LAMMPS' manual (platens moved by fix move, the rest integrated and damped); the lines
the warning names, put in place of the old ones, must run, measure the steps, and end
where the original deck ends, to the last bit."""

from __future__ import annotations

import re

import pytest
from helpers.decks import run_deck, shaken_block
from helpers.materials import D, WEAK_SHEAR, coeffs

ADVICE = "pair_style lattice/bond: fix nve and fix viscous"


def user_deck(dim: int, integrate: str = "nve", damp: str = "viscous 0.2",
              plane: bool = True, runs: int = 1) -> str:
    """runs: the deck's runs of 300 steps (at the start of a later run fix viscous damps
    with the full-step velocity, fix lattice/viscous with the force of the last step: one
    run for a comparison of the two)."""
    ax = "y" if dim == 2 else "z"
    slab = {"y": "INF INF {lo} {hi} INF INF", "z": "INF INF INF INF {lo} {hi}"}[ax]
    vel = {"y": ("0 -0.5 0", "0 0.5 0"), "z": ("0 0 -0.5", "0 0 0.5")}[ax]
    return shaken_block(dim) + f"""
pair_style      lattice/bond
pair_coeff      * * {coeffs(WEAK_SHEAR[dim])}
neighbor        {0.1 * D} bin
velocity        all create 1e-9 4928 dist gaussian
region          toplayer block {slab.format(lo=f"$(bound(all,{ax}max)-{0.25 * D})", hi="INF")} units box
region          botlayer block {slab.format(lo="INF", hi=f"$(bound(all,{ax}min)+{0.25 * D})")} units box
group           top region toplayer
group           bottom region botlayer
group           inner subtract all top bottom
fix             up top move linear {vel[0]} units box
fix             down bottom move linear {vel[1]} units box
fix             integrate inner {integrate}
fix             damp inner {damp}
{"fix             plane all enforce2d" if dim == 2 and plane else ""}
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
{("run             300" + chr(10)) * runs}write_dump      all custom final.dump id x y z vx vy vz modify sort id format float %.17g
"""


def advice_lines(output: str) -> list[str]:
    """The warning's lines in quotes (the warning comes once per simulation)."""
    warnings = [line for line in output.splitlines() if ADVICE in line]
    assert len(warnings) == 1, warnings
    return re.findall(r"'(fix [^']+)'", warnings[0])


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("np_", [1, 2])
def test_the_advised_lines_measure_the_steps_and_keep_the_bits(tmp_path, dim, np_):
    written = run_deck(user_deck(dim), tmp_path / "written", np=np_)
    assert written.returncode == 0, written.output[-3000:]
    lines = advice_lines(written.output)
    assert lines == ["fix integrate inner lattice/nve", "fix damp inner lattice/viscous"]
    warning = next(line for line in written.output.splitlines() if ADVICE in line)
    assert ("so fix plane has nothing left to do" in warning) == (dim == 2)
    assert "with the same gamma" in warning
    # the user follows the warning: the advised styles, the same gamma, fix enforce2d gone
    advised = run_deck(user_deck(dim, "lattice/nve", "lattice/viscous 0.2", plane=False),
                       tmp_path / "advised", np=np_)
    assert advised.returncode == 0, advised.output[-3000:]
    assert ADVICE not in advised.output
    assert "measures the steps of group inner" in advised.output
    a, b = ((tmp_path / run / "final.dump").read_text() for run in ("advised", "written"))
    assert a == b


def test_only_the_general_fixes_are_named_once(tmp_path):
    """fix lattice/nve with fix viscous, two runs: the warning names fix viscous alone,
    once."""
    res = run_deck(user_deck(3, integrate="lattice/nve", runs=2), tmp_path)
    assert res.returncode == 0, res.output[-3000:]
    assert advice_lines(res.output) == ["fix damp inner lattice/viscous"]
