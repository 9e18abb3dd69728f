"""The per-step log of a strength test with the energy budget (decks.BREAKING_COLUMNS, written
from a ring buffer after the run) on a small 3D tension test: it reads back, agrees with the
thermo rows, holds the failure and its aftermath, and its failure window is the tension
failure's (validation.failure)."""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.decks import BREAKING_COLUMNS, BREAKING_LOG
from bonded_lattice.experiment import ENERGY_AFTERMATH, peak_work_fraction, run_test
from bonded_lattice.io import read_ave_time
from bonded_lattice.rocks import get_rock
from bonded_lattice.runner import parse_thermo
from bonded_lattice.validation.energy import old_halt
from bonded_lattice.validation.failure import failure_event, peak_kinetic_fraction


@pytest.fixture(scope="module")
def tension(tmp_path_factory):
    """3D quartz, 6 elements along y (255), tension at the default plan (3 s of run)."""
    out = tmp_path_factory.mktemp("tension")
    summary = run_test(get_rock("quartz"), 3, "tension", 6, out, np_=1, progress=False,
                       energy=True)
    thermo = parse_thermo((out / "log.lammps").read_text())[-1]
    return summary, read_ave_time(out / BREAKING_LOG), thermo


def test_every_column_reads_back_and_ends_on_the_thermo_rows(tension):
    summary, log, thermo = tension
    assert list(log) == ["TimeStep", *BREAKING_COLUMNS]
    # the run is shorter than the window: every step from 0 to the last one
    steps = log["TimeStep"]
    assert steps[0] == 0 and np.all(np.diff(steps) == 1) and steps[-1] == thermo["Step"][-1]
    # the last row is the last thermo row; the thermo prints 8 significant digits
    # (rounding: at most 5e-8 relative)
    for column in BREAKING_COLUMNS:
        if column.startswith("c_"):
            assert log[column][-1] == pytest.approx(thermo[column][-1], rel=6e-8, abs=1e-30), column
    # the balance holds at every step, not only at the thermo rows: measured 8.9e-4 at every
    # step against 7.2e-4 at the rows (tests/validation/test_energy_balance.py: < 1e-3 there)
    assert peak_work_fraction(log["c_energy[10]"], log["c_energy[8]"]) < 2e-3


def test_the_run_goes_on_after_the_failure_until_the_kinetic_energy_is_damped(tension):
    summary, log, _ = tension
    dt, every = summary["plan"]["dt"], summary["plan"]["thermo_every"]
    halt = old_halt(log, every)      # where the run stopped before the aftermath
    assert log["TimeStep"][-1] - halt >= ENERGY_AFTERMATH / dt
    peak = peak_kinetic_fraction(log, 1)
    # the old halt came before the kinetic energy's peak (measured: 5 steps before it)
    assert peak["step"] > halt
    # at the end the kinetic energy is damped: measured 5.5e-4 of its peak (the papers' eta
    # alone would leave exp(-2 eta t / m) = e^-100 after 20 us; the rest is the block's
    # elastic energy ringing back)
    assert log["c_energy[2]"][-1] < 1e-2 * peak["kinetic_J"]


def test_the_tension_failure_window(tension):
    summary, log, _ = tension
    event = failure_event(log, summary["plan"]["dt"])
    # no bond breaks before the failure in tension: the whole breaking heat is the burst's
    assert event["precursor_fraction"] == 0.0
    assert event["heat_J"] == pytest.approx(summary["energy"]["breaking_heat_normal"]
                                            + summary["energy"]["breaking_heat_shear"], rel=1e-7)
    # the first broken bond unloads the block: the stress peaks within a step of the first
    # breaking heat (measured: one step after it)
    assert abs(event["peak_stress_step"] - event["start_step"]) <= 1
    # the start-to-end time holds the 2%-98% one; and it agrees with experiment.energy_summary
    # (the same definition without precursors)
    assert event["duration_s"] >= event["duration_2_98_s"] > 0
    assert event["duration_s"] == pytest.approx(summary["energy"]["breaking_duration_full_s"],
                                                rel=1e-9)
