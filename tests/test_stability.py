"""The critical time step: reported at the start of each run, a warning above the
safety fraction, and an unstable run stopped with a message that names the step and
an atom instead of running on into NaN."""

from __future__ import annotations

import math
import re

import pytest
from bonded_lattice.conversion import critical_time_step
from conftest import block_2d_deck, run_deck

D = 1.0e-3
MASS = 2.295e-3                        # quartz, 2D, per metre of thickness
KN, KS = 6.5874e10, 2.3715e10
DECK = block_2d_deck("-2 14 -2 12", "0 10 0 8", coeffs=f"{KN} {KS} 1.9011e-7 3.6905e4 0.23915") + """
# a small random vibration, far below breaking, no damping
variable        vx atom 0.01*normal(0,1,8411)
variable        vy atom 0.01*normal(0,1,2203)
velocity        all set v_vx v_vy NULL units box
fix             nve all nve
thermo_style    custom step ke pe
thermo          100
timestep        ${dt}
run             ${steps}
"""
# the report in the log: "critical time step X (...); the time step Y is Z of it"
REPORT = re.compile(r"critical time step ([0-9.eE+-]+) .*the time step ([0-9.eE+-]+) is "
                    r"([0-9.]+) of it")
# Gershgorin bound of an interior particle with 6 bonds (conversion.critical_time_step)
DT_CRIT = critical_time_step(MASS, KN, KS, 2)


def run(tmp_path, dt, steps):
    return run_deck(DECK, tmp_path, args=["-var", "dt", repr(dt), "-var", "steps", str(steps)])


def test_critical_time_step_is_reported_and_a_recommended_run_is_stable(tmp_path):
    result = run(tmp_path, 0.2 * DT_CRIT, 3000)
    assert result.returncode == 0, result.output[-2000:]
    match = REPORT.search(result.output)
    assert match, result.output[-2000:]
    reported, dt, fraction = (float(v) for v in match.groups())
    # the block has interior particles with all 6 bonds: the same bound as the formula
    assert reported == pytest.approx(DT_CRIT, rel=1e-5)
    assert fraction == pytest.approx(0.2, abs=1e-3)
    assert "WARNING" not in result.output
    # stable: the kinetic energy stays of the order of its start (no growth)
    ke = result.thermo[0]["KinEng"]
    assert all(math.isfinite(v) for v in ke)
    assert max(ke) < 2.0 * ke[0]


def test_time_step_above_the_safety_fraction_warns(tmp_path):
    result = run(tmp_path, 0.7 * DT_CRIT, 10)
    assert result.returncode == 0, result.output[-2000:]
    assert "WARNING: Time step" in result.output and "above the safety fraction 0.5" in result.output
    assert f"at most {0.5 * DT_CRIT:.6g}" in result.output


@pytest.mark.parametrize("integrator", ["nve", "lattice/nve"])
def test_twice_the_critical_time_step_is_stopped_with_step_and_atom(tmp_path, integrator):
    # fix lattice/nve on all atoms measures the steps while it moves the atoms
    # (the store's own pass is skipped): the test of their length must stay
    deck = DECK.replace("fix             nve all nve", f"fix             nve all {integrator}")
    result = run_deck(deck, tmp_path, args=["-var", "dt", repr(2.0 * DT_CRIT), "-var", "steps",
                                            "2000"])
    assert result.returncode != 0
    message = re.search(r"atom (\d+) moved ([0-9.eE+-]+) in one time step at step (\d+)",
                        result.output)
    assert message, result.output[-2000:]
    step = int(message.group(3))
    assert 0 < step < 2000           # caught during the run, long before its end
    assert float(message.group(2)) > 0.1 * 0.5 * D
    assert "the integration is unstable" in result.output
    assert "nan" not in result.output.lower().split("error")[0][-3000:]
