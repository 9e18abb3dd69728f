"""The failure window of a per-step log (bonded_lattice.validation.failure) on logs built by
hand, where every number it finds is known."""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.decks import BREAKING_COLUMNS, DeckSpec, deck_text
from bonded_lattice.validation.energy import old_halt
from bonded_lattice.validation.failure import (failure_event, peak_kinetic_fraction,
                                               peak_width, window_rows)

DT = 1e-8


def log_of(heat: np.ndarray, **columns: np.ndarray) -> dict[str, np.ndarray]:
    """A per-step log from step 0 with the breaking heat split 3:1 into normal and shear."""
    n = len(heat)
    log = {"TimeStep": np.arange(n, dtype=float), "c_energy[5]": 0.75 * heat,
           "c_energy[6]": 0.25 * heat}
    for c in BREAKING_COLUMNS[2:]:
        log[c] = columns.get(c, np.zeros(n))
    return log


def test_the_burst_with_the_most_heat_is_the_failure():
    # a precursor of 1 J at step 100, then quiet, then 10 J released over steps 1000-1100
    # (0.1 J a step); quiet for 1 us = 100 steps between the two: two bursts
    heat = np.zeros(2000)
    heat[100:] = 1.0
    heat[1000:1101] += np.linspace(0.1, 10.0, 101)
    heat[1101:] = 11.0
    e = failure_event(log_of(heat), DT)
    assert (e["start_step"], e["end_step"]) == (1000, 1100)
    assert e["duration_s"] == pytest.approx(100 * DT, rel=1e-12)
    assert e["heat_J"] == pytest.approx(10.0, rel=1e-12)
    assert e["precursor_fraction"] == pytest.approx(1.0 / 11.0, rel=1e-12)
    # 2% of the burst's 10 J: the first row above 0.2 J of rise is step 1002 (0.3 J); 98%:
    # the first row with at least 9.8 J is step 1097 (9.8 J, rounding aside: 9.8 = 0.1 x 98)
    assert e["duration_2_98_s"] == pytest.approx((1097 - 1002) * DT, abs=1.01 * DT)


def test_pauses_up_to_the_quiet_time_do_not_split_a_burst():
    # two bursts of 5 J, 60 steps (0.6 us) apart: one failure with the default 1 us, two
    # with 0.5 us (the first, released first, wins a tie of equal heat)
    heat = np.zeros(1000)
    heat[200:] = 5.0
    heat[260:] = 10.0
    one = failure_event(log_of(heat), DT)
    assert (one["start_step"], one["end_step"]) == (200, 260)
    # its start-to-end time is the single pause between its two increases
    assert one["first_pause_s"] == one["last_pause_s"] == pytest.approx(60 * DT, rel=1e-12)
    two = failure_event(log_of(heat), DT, quiet_s=0.5e-6)
    assert (two["start_step"], two["end_step"]) == (200, 200)
    assert failure_event(log_of(np.zeros(10)), DT) is None
    with pytest.raises(ValueError, match="dt = 0"):
        failure_event(log_of(heat), 0.0)


def test_peak_kinetic_fraction_at_every_step_and_sampled():
    # kinetic energy peaking at step 55 (6 J) on a work of 20 J; sampled every 10 steps the
    # largest is at step 50 or 60 (5 J): the sampling misses 1 J of the peak
    n = 200
    kinetic = np.maximum(0.0, 6.0 - np.abs(np.arange(n) - 55) * 0.1)
    work = np.full(n, 20.0)
    work[-1] = 24.0
    log = log_of(np.zeros(n), **{"c_energy[2]": kinetic, "c_energy[8]": work})
    every = peak_kinetic_fraction(log, 1)
    assert every["step"] == 55 and every["fraction"] == pytest.approx(0.3, rel=1e-12)
    assert every["over_final_work"] == pytest.approx(0.25, rel=1e-12)
    assert peak_kinetic_fraction(log, 10)["fraction"] == pytest.approx(5.5 / 20, rel=1e-12)
    with pytest.raises(ValueError, match="every = 0"):
        peak_kinetic_fraction(log, 0)
    # the triangle 6 - 0.1 |k - 55| is at least 3 J from step 25 to step 85: 60 steps
    assert peak_width(log, "c_energy[2]", DT) == pytest.approx(60 * DT, rel=1e-12)


def test_window_rows_every_step_or_thinned():
    heat = np.zeros(5000)
    heat[1000:1101] = np.linspace(0.1, 10.0, 101)
    heat[1101:] = 10.0
    log = log_of(heat)
    e = failure_event(log, DT)
    # 50 steps before the start (half the duration is 50), 2 us = 200 steps after the end
    w = window_rows(log, e, DT, after_s=2e-6)
    assert w["stride"] == 1 and len(w["time_s"]) == 50 + 101 + 200
    assert w["time_s"][0] == pytest.approx(950 * DT) and w["time_s"][-1] == pytest.approx(1300 * DT)
    thin = window_rows(log, e, DT, after_s=2e-6, rows=100)
    assert thin["stride"] == 4 and thin["time_s"][-1] == pytest.approx(1300 * DT)


def test_old_halt_is_the_first_thermo_row_below_the_fraction_of_the_peak():
    # stress rising to 10 at step 40 and dropping to 2 at step 45; thermo every 10 steps:
    # the rows see 10 at step 40 and 2 (< 0.3 x 10) first at step 50
    stress = np.r_[np.linspace(0, 10, 41), np.full(4, 8.0), np.full(20, 2.0)]
    log = log_of(np.zeros(len(stress)), **{"v_stress": stress})
    assert old_halt(log, 10) == 50


def test_the_deck_writes_its_ring_buffer_to_the_log():
    from bonded_lattice.conversion import rock_to_bond
    from bonded_lattice.rocks import get_rock

    r = get_rock("quartz")
    bond = rock_to_bond(r.E, r.nu, r.Tu, r.Cu, r.mu_i, 1e-3, 3)
    spec = DeckSpec(test="tension", dim=3, d=1e-3, bond=bond, data_file="data.lattice",
                    area=1e-4, eta=1.0, speed=0.01, steps=1000, energy=True, halt_delay=250,
                    thermo_every=100)
    text = deck_text(spec)
    assert f"nmax 20000" in text and "jump            SELF breakrow_next" in text
    # one failed row, then 250 steps = 3 more rows of 100: four failed rows stop the run
    assert "v_failedrows >= 4" in text
    with pytest.raises(ValueError, match="halt_delay = -1"):
        DeckSpec(test="tension", dim=3, d=1e-3, bond=bond, data_file="x", area=1e-4, eta=1.0,
                 speed=0.01, steps=10, halt_delay=-1)


def test_peak_width_at_a_fraction_of_the_peak():
    # a triangle of height 1 over steps 0..200, peak at 100: above a fraction f of the peak
    # from step 100 f to 200 - 100 f, i.e. 200 (1 - f) steps; each edge step sits exactly on
    # the level, so round-off may drop it: a step at each end
    steps = np.arange(201)
    log = {"TimeStep": steps, "c_energy[2]": 1.0 - np.abs(steps - 100) / 100.0}
    dt = 1e-8
    for f in (0.5, 0.1, 0.01):
        assert peak_width(log, "c_energy[2]", dt, f) == pytest.approx(200 * (1 - f) * dt,
                                                                       abs=2.01 * dt)
    with pytest.raises(ValueError, match="fraction = 1.0"):
        peak_width(log, "c_energy[2]", dt, 1.0)
