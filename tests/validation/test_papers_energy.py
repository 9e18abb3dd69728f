"""The 2017 paper's energy figures (Liu et al. 2017, section 5.3) under the paper's own set-up:
the 2166-element quartzite block pulled with its stepwise schedule, read at every step.

Opt-in (``pytest -m slow``): the stepwise run takes about 10 minutes on 2 ranks.  The numbers
and their explanation are in docs/validation.md ("Energy budget at the resolution of the
failure").
"""

from __future__ import annotations

import pytest
from bonded_lattice.experiment import run_test
from bonded_lattice.io import read_ave_time
from bonded_lattice.rocks import get_rock
from bonded_lattice.validation.failure import failure_event, peak_kinetic_fraction
from bonded_lattice.validation.papers import paper_value

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def stepwise_tension(tmp_path_factory):
    out = tmp_path_factory.mktemp("energy_stepwise")
    summary = run_test(get_rock("quartz"), 3, "tension", 12, out, np_=2, progress=False,
                       energy=True, schedule="stepwise", crossings=100.0, damping=1.0)
    return summary, read_ave_time(out / "breaking.dat")


def test_peak_kinetic_energy_is_the_papers_share_of_the_work(stepwise_tension):
    summary, log = stepwise_tension
    assert summary["particles"] == paper_value("3d.energy.elements")
    # the paper: 16.2%.  Tolerance 0.5 points: its eq. 28 leaves the volume V open, and the
    # two readings (the elements' volume, ours, and the outer box: 0.966 eta) move the peak by
    # 0.3 points (it goes as eta^-0.56, measured), plus the paper's rounding
    peak = peak_kinetic_fraction(log, 1)["fraction"]
    assert abs(peak - paper_value("3d.energy.tension.peak_kinetic")) < 0.005, peak


def test_the_bonds_break_within_the_papers_time(stepwise_tension):
    summary, log = stepwise_tension
    event = failure_event(log, summary["plan"]["dt"])
    # the paper: 2.83 us from the first to the last increase of the breaking heat (Fig. 6d).
    # Tolerance 0.35 us: that time ends at the last bond to break, which came 0.31 us after
    # the one before it in our run (a single bond's timing, not the crack's)
    assert abs(event["duration_s"] - paper_value("3d.energy.tension.duration_s")) < 0.35e-6, \
        event
