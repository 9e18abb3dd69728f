"""Loading schedules: walls that follow a variable, the papers' stepwise loading, halting."""

from __future__ import annotations

import pytest
from bonded_lattice.experiment import PAPER_SCHEDULES, run_test
from bonded_lattice.rocks import get_rock
from helpers.decks import atoms_at, opening, run_deck

ONE_PARTICLE = opening(3, box="-1 1 -1 1 -1 1") + atoms_at([(0, 0, 0)]) + """\
set atom 1 diameter 0.2 density 1000
pair_style lattice/bond
pair_coeff * * 1.0e3 0 1.0e-3 1.0 0.1
fix nve all nve
timestep 1.0e-3
"""


def test_wall_follows_an_equal_style_variable(lmp_instance):
    # the papers' stepwise loading: the wall jumps by 1 mm every 10 steps
    lmp_instance.commands_string(ONE_PARTICLE + """
variable w equal -0.5+1.0e-3*ceil(step/10)
fix floor all lattice/wall zlo v_w 1.0e4 0 0
""")
    for steps, jumps in [(1, 1), (9, 1), (10, 2), (25, 3)]:
        lmp_instance.command(f"run {steps}")
        total = lmp_instance.get_thermo("step")
        assert lmp_instance.numpy.extract_fix("floor", 0, 1, 3) == pytest.approx(
            -0.5 + 1.0e-3 * (-(-int(total) // 10)), abs=1e-15), (steps, jumps)


@pytest.mark.parametrize("line,fragment", [
    ("fix w all lattice/wall zlo v_nothere 1e4 0 0", "position variable nothere does not exist"),
    ("variable a atom x\nfix w all lattice/wall zlo v_a 1e4 0 0", "is not equal-style"),
    ("variable w equal 0\nfix w all lattice/wall zlo v_w 1e4 0 0 vel 1",
     "a variable position v_w excludes vel and servo"),
])
def test_variable_wall_errors_name_the_problem(tmp_path, line, fragment):
    result = run_deck(ONE_PARTICLE + line + "\nrun 1\n", tmp_path)
    assert result.returncode != 0
    assert fragment in result.output


def test_paper_schedule_single_unit_compression(tmp_path):
    # the 2013 paper's stepwise schedule (1.9e-9 m per platen, 400 relaxation steps)
    # on the three-particle unit: Cu -0.98% in the paper (MatDEM), -0.88% for the
    # exact finite-strain path (tests/validation/test_single_unit.py); measured -0.92%
    s = run_test(get_rock("quartz"), 2, "compression", 2, tmp_path, np_=1, progress=False,
                 schedule="paper")
    assert s["plan"]["relax_steps"] == PAPER_SCHEDULES[2]["relax_steps"] == 400
    assert s["plan"]["step_size"] == pytest.approx(1.9e-9)
    assert -0.015 < s["relative_error"]["Cu"] < -0.005
    # micro-cracks open at C_open = Tu (0.75/nu - 1) = 92.19 MPa (measured -1.34%:
    # the last row before the base bond broke, one load step earlier)
    assert s["relative_error"]["C_open"] == pytest.approx(0.0, abs=0.02)
    assert s["relative_error"]["E"] == pytest.approx(0.0, abs=1e-3)


def test_stepwise_and_constant_tension_agree(tmp_path):
    # 68 particles; a coarser stepwise schedule than the paper's to keep the test short
    rock = get_rock("quartz")
    step = run_test(rock, 2, "tension", 8, tmp_path / "step", np_=1, progress=False,
                    schedule="paper", step_size=1.9e-9, relax_steps=100)
    const = run_test(rock, 2, "tension", 8, tmp_path / "const", np_=1, progress=False)
    deck = (tmp_path / "step" / "in.tension").read_text()
    assert "ceil((step-v_s0)/100)" in deck and "fix             ptop top move variable" in deck
    assert step["measured"]["Tu"] == pytest.approx(const["measured"]["Tu"], rel=0.02)
    # both stop by themselves once the block has broken (fix halt)
    for run in ("step", "const"):
        assert "Fix halt condition" in (tmp_path / run / "log.lammps").read_text()
