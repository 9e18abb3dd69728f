"""The failure of a strength test at the resolution of a time step, from its per-step log.

A deck with the energy budget writes ``breaking.dat`` (:data:`bonded_lattice.decks.
BREAKING_COLUMNS`): every term of compute lattice/energy, the broken bonds and the stress at
every step of the last :data:`~bonded_lattice.decks.BREAKING_WINDOW` steps of the run, which
hold the failure.  This module finds the failure in it the way Liu et al. (2017, section 5.3)
read their Fig. 6c/d, and the numbers the paper gives for it:

- the failure event (:func:`failure_event`): the burst of breaking heat -- the increases of
  the breaking heat (normal + shear) that follow each other with pauses of at most
  :data:`QUIET_S`; of those bursts the one that releases the most heat.  Its start (the
  paper's C1, D1: "the breaking heat increases from zero") is the burst's first step with
  more heat than before it, its end (C2, D2: "the breaking heat stops increasing") the step
  the burst's last increase lands on; beside it the time from 2% to 98% of the burst's heat;
- the peak kinetic energy over the total energy (the external work: the model starts with
  none, eq. 25) sampled at every step, or every k steps as a coarser log would see it
  (:func:`peak_kinetic_fraction`);
- the rows to draw (:func:`window_rows`): every step around the event, thinned only if the
  event outlasts :data:`WINDOW_ROWS` steps.
"""

from __future__ import annotations

import numpy as np

__all__ = ["HEAT", "QUIET_S", "WINDOW_COLUMNS", "WINDOW_ROWS", "failure_event",
           "peak_kinetic_fraction", "peak_width", "window_rows"]

# the breaking heat of the normal and of the shear springs (compute lattice/energy)
HEAT = ("c_energy[5]", "c_energy[6]")
# the longest pause inside one failure: one loading step of the 2017 paper (100 relaxation
# steps of 1e-8 s), the interval at which it computed its energies.  A pause that long shows
# on its curves as the breaking heat having stopped; the 2166-element tension block's bonds
# break with pauses of at most 15 steps (0.3 us) once the failure has begun
QUIET_S = 1.0e-6
# the columns kept for the figures: elastic, kinetic, viscous, breaking (n, s), frictional
# heat, external work, balance error
WINDOW_COLUMNS = ("c_energy[1]", "c_energy[2]", "c_energy[4]", "c_energy[5]", "c_energy[6]",
                  "c_energy[7]", "c_energy[8]", "c_energy[10]")
# rows of a window kept in the results file: every step of the 2166-element block's tension
# failure under the paper's schedule (about 300 steps of 1e-8 s, with 150 before it and 5 us
# after it: 950 rows); a compression failure (thousands of steps) thinned to this
WINDOW_ROWS = 1000


def _check_dt(dt: float) -> float:
    if not (dt > 0 and np.isfinite(dt)):
        raise ValueError(f"dt = {dt} is out of range: need 0 < dt < inf")
    return float(dt)


def failure_event(log: dict[str, np.ndarray], dt: float, quiet_s: float = QUIET_S) -> dict | None:
    """The failure in the per-step log ``log`` (columns by name, ``TimeStep`` first) of a run
    with time step ``dt`` (s); None if no bond broke in it.

    Returns steps and times (s, step x dt): ``start_step``/``end_step`` (the paper's D1/D2),
    ``duration_s`` (end - start), ``duration_2_98_s`` (2% to 98% of the burst's heat),
    ``heat_J`` (the burst's), ``precursor_fraction`` (heat released before the burst, over
    the final heat), ``peak_stress_step`` (the largest |stress| in the log),
    ``first_pause_s``/``last_pause_s`` (from the first to the second increase, from the last
    but one to the last).
    """
    dt = _check_dt(dt)
    if not quiet_s > 0:
        raise ValueError(f"quiet_s = {quiet_s} is out of range: need quiet_s > 0")
    step = np.asarray(log["TimeStep"], dtype=np.int64)
    heat = np.asarray(log[HEAT[0]], dtype=float) + np.asarray(log[HEAT[1]], dtype=float)
    rises = np.flatnonzero(np.diff(heat) > 0) + 1      # rows whose heat exceeds the row before
    if len(rises) == 0:
        return None
    quiet = quiet_s / dt
    # bursts: runs of rises whose steps are at most `quiet` apart
    cuts = np.flatnonzero(np.diff(step[rises]) > quiet) + 1
    bursts = np.split(rises, cuts)
    released = [heat[b[-1]] - heat[b[0] - 1] for b in bursts]
    burst = bursts[int(np.argmax(released))]
    first, last = int(burst[0]), int(burst[-1])
    before, after = heat[first - 1], heat[last]
    rise = (heat - before) / (after - before)
    span = slice(first - 1, last + 1)
    on = first - 1 + int(np.argmax(rise[span] > 0.02))
    off = first - 1 + int(np.argmax(rise[span] >= 0.98))
    stress = np.abs(np.asarray(log["v_stress"], dtype=float)) if "v_stress" in log else None
    return {
        "start_step": int(step[first]), "end_step": int(step[last]),
        "start_s": float(step[first] * dt), "end_s": float(step[last] * dt),
        "duration_s": float((step[last] - step[first]) * dt),
        "duration_2_98_s": float((step[off] - step[on]) * dt),
        "heat_J": float(after - before),
        "precursor_fraction": float(before / heat[-1]),
        "peak_stress_step": None if stress is None else int(step[int(np.argmax(stress))]),
        "quiet_s": float(quiet_s),
        # the pauses after the first and before the last increase: how much the
        # start-to-end time hangs on single bonds
        "first_pause_s": float((step[burst[1]] - step[first]) * dt) if len(burst) > 1 else 0.0,
        "last_pause_s": float((step[last] - step[burst[-2]]) * dt) if len(burst) > 1 else 0.0,
    }


def peak_kinetic_fraction(log: dict[str, np.ndarray], every: int = 1) -> dict:
    """The largest kinetic energy over the external work so far, at the steps of ``log``
    that are multiples of ``every`` (1: every step; the 2017 paper's loading step: 100; our
    thermo interval), once the work exceeds 1% of its final value.

    Returns ``fraction`` (kinetic / work at that step), ``over_final_work`` (the same kinetic
    energy over the work at the end of the log), ``step`` and ``kinetic_J``.
    """
    if every < 1:
        raise ValueError(f"every = {every} is out of range: need every >= 1")
    step = np.asarray(log["TimeStep"], dtype=np.int64)
    kinetic = np.asarray(log["c_energy[2]"], dtype=float)
    work = np.abs(np.asarray(log["c_energy[8]"], dtype=float))
    rows = (step % every == 0) & (work > 0.01 * work[-1])
    if not rows.any():
        raise ValueError(f"no step of the log is a multiple of every = {every} with work")
    k = np.flatnonzero(rows)[int(np.argmax(kinetic[rows] / work[rows]))]
    return {"fraction": float(kinetic[k] / work[k]),
            "over_final_work": float(kinetic[k] / work[-1]),
            "step": int(step[k]), "kinetic_J": float(kinetic[k])}


def peak_width(log: dict[str, np.ndarray], column: str, dt: float,
               fraction: float = 0.5) -> float:
    """Time (s) the largest value of ``column`` stays above ``fraction`` of itself: the
    steps around its maximum with at least that much, end to end (by default the full
    width at half maximum).  A ValueError unless 0 < fraction < 1."""
    dt = _check_dt(dt)
    if not 0.0 < fraction < 1.0:
        raise ValueError(f"fraction = {fraction!r}: need 0 < fraction < 1")
    values = np.asarray(log[column], dtype=float)
    top = int(np.argmax(values))
    above = values >= fraction * values[top]
    lo = top
    while lo > 0 and above[lo - 1]:
        lo -= 1
    hi = top
    while hi < len(values) - 1 and above[hi + 1]:
        hi += 1
    step = np.asarray(log["TimeStep"])
    return float((step[hi] - step[lo]) * dt)


def window_rows(log: dict[str, np.ndarray], event: dict, dt: float, after_s: float,
                rows: int = WINDOW_ROWS) -> dict[str, list[float]]:
    """The columns :data:`WINDOW_COLUMNS` (and ``time_s``) of ``log`` from half the event's
    duration (at least 50 steps) before its start to ``after_s`` after its end, at every
    step, or every k-th step (the last kept) if that is more than ``rows`` steps; values
    rounded to 6 significant digits."""
    dt = _check_dt(dt)
    step = np.asarray(log["TimeStep"], dtype=np.int64)
    length = event["end_step"] - event["start_step"]
    lo = event["start_step"] - max(50, length // 2)
    hi = event["end_step"] + int(round(after_s / dt))
    keep = np.flatnonzero((step >= lo) & (step <= hi))
    stride = max(1, int(np.ceil(len(keep) / rows)))
    keep = np.unique(np.r_[keep[::stride], keep[-1]])
    out = {"time_s": [float(f"{x:.8g}") for x in step[keep] * dt], "stride": stride}
    for c in WINDOW_COLUMNS:
        if c in log:
            out[c] = [float(f"{x:.6g}") for x in np.asarray(log[c], dtype=float)[keep]]
    return out
