"""The critical time step: reported at the start of each run, a warning above the
safety fraction, and an unstable run stopped with a message that names the step and
an atom instead of running on into NaN."""

from __future__ import annotations

import math
import re

import pytest
from bonded_lattice.conversion import critical_time_step
from helpers.decks import block_2d_deck, lattice_block, run_deck
from helpers.materials import D, QUARTZ, QUARTZ_2D, QUARTZ_3D, QUARTZ_MASS

MASS = QUARTZ_MASS[2]                  # quartz, 2D, per metre of thickness
KN, KS = QUARTZ[2].Kn, QUARTZ[2].Ks
DECK = block_2d_deck("-2 14 -2 12", "0 10 0 8", coeffs=QUARTZ_2D) + """
# a small random vibration, far below breaking, no damping
variable        vx atom 0.01*normal(0,1,8411)
variable        vy atom 0.01*normal(0,1,2203)
velocity        all set v_vx v_vy NULL units box
fix             nve all lattice/nve
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


# 3D, fcc, atom_style atomic with one mass: fix lattice/nve on all atoms takes the
# one-stream loop over x, v and f; its step test must stop a run far above the
# critical time step as the per-atom loops do (four times the Gershgorin bound,
# which is 0.6-0.9 of the exact limit)
D3_MASS = 2650.0 * math.pi / 6.0 * D**3          # quartz sphere
D3_KN, D3_KS = QUARTZ[3].Kn, QUARTZ[3].Ks
DECK_3D = f"""
units           si
atom_style      atomic
newton          on
{lattice_block(3, "-3 8 -3 8 -3 8", "0 5 0 5 0 5")}create_atoms    1 region block
mass            1 {D3_MASS}
pair_style      lattice/bond diameter {D}
pair_coeff      1 1 {QUARTZ_3D}
variable        vx atom 0.01*normal(0,1,8411)
variable        vy atom 0.01*normal(0,1,2203)
variable        vz atom 0.01*normal(0,1,5113)
velocity        all set v_vx v_vy v_vz units box
fix             nve all lattice/nve
thermo          100
timestep        ${{dt}}
run             2000
"""


def test_3d_one_mass_stream_stops_an_unstable_run(tmp_path):
    # Gershgorin bound of an interior fcc particle (12 bonds)
    dt_crit = critical_time_step(D3_MASS, D3_KN, D3_KS, 3)
    result = run_deck(DECK_3D, tmp_path, args=["-var", "dt", repr(4.0 * dt_crit)])
    assert "measures the steps" in result.output
    assert result.returncode != 0
    message = re.search(r"atom (\d+) moved ([0-9.eE+-]+) in one time step at step (\d+)",
                        result.output)
    assert message, result.output[-2000:]
    assert 0 < int(message.group(3)) < 2000
    assert float(message.group(2)) > 0.1 * 0.5 * D
