"""The energy budget of the 2017 paper's example (section 5.3, Fig. 6) at the resolution of
the failure: the 2166-element quartzite block in tension and compression, with compute
lattice/energy and its per-step log (``breaking.dat``, :mod:`.failure`).

The runs go from the paper's set-up (its stepwise schedule, the damping of its eq. 28, its
time step) to ours one change at a time (:data:`RUNS`); each is read at every step of its
failure window and at the coarser samplings a log would see.  The figures are the analogues
of Fig. 6a-d (:mod:`.energy_plots`).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from ..decks import BREAKING_WINDOW, DeckSpec
from ..experiment import ENERGY_AFTERMATH, build_lattice
from ..io import read_ave_time, read_thermo
from ..schedules import DEFAULT_DT_FRACTION, PAPER_SCHEDULES
from .doc import DocContext
from .energy_plots import energy_curves_png, heat_window_png
from .failure import failure_event, peak_kinetic_fraction, peak_width, window_rows
from .papers import PAPER
from .runner import Validation, curve, rock_for
from .section import Section

__all__ = ["ENERGY", "ENERGY_SIZE", "RUNS"]

ENERGY_SIZE = 12            # the 2017 paper's energy example: 2166 elements, 12 along y
HEATS = ("viscous_heat", "breaking_heat_normal", "breaking_heat_shear", "frictional_heat")
# the paper's time step as a multiple of ours (0.04997 / 0.1 of sqrt(m/Kn))
PAPER_DT_SCALE = PAPER_SCHEDULES[3]["dt_fraction"] / DEFAULT_DT_FRACTION
# the runs: key, test, RockTest options, and the one thing that changed from the row before
# (the tension rows go from the paper's set-up to ours; the damping rows bracket ours)
RUNS = (
    ("tension_stepwise", "tension", {"schedule": "stepwise"}, "the paper's set-up"),
    ("tension_constant_dt1e-8", "tension", {"dt_scale": PAPER_DT_SCALE}, "loading: constant"),
    ("tension_constant", "tension", {}, "time step: ours"),
    ("tension_constant_damping0.5", "tension", {"damping": 0.5}, "damping x 0.5"),
    ("tension_constant_damping2", "tension", {"damping": 2.0}, "damping x 2"),
    ("compression_stepwise", "compression", {"schedule": "stepwise"}, "the paper's set-up"),
    ("compression_constant", "compression", {}, "loading: constant, time step: ours"),
)
# the runs drawn as Fig. 6 (a/c: compression, b/d: tension)
FIGURE_RUNS = {"compression": "compression_stepwise", "tension": "tension_stepwise"}
# the energies' time after the failure's end kept for the figures (s): the kinetic energy
# peaks before the end of the tension failure and has been damped to under 1% of its
# peak 5 us later (Fig. 6b's B2)
AFTER_S = 5.0e-6
CURVE_COLUMNS = ("Time", "c_energy[1]", "c_energy[2]", "c_energy[4]", "c_energy[5]",
                 "c_energy[6]", "c_energy[7]", "c_energy[8]", "c_energy[10]")
# the paper computed its energies once per loading step (section 5.3): 100 steps of 1e-8 s
PAPER_SAMPLE_S = PAPER["3d.schedule.relax_steps"].value * PAPER["3d.schedule.dt_s"].value


def _folder_name(key: str) -> str:
    return f"3d/fig6_n{ENERGY_SIZE}_{key}"


# fractions of the kinetic energy's peak above which its burst is timed
KE_LEVELS = (0.1, 0.01)

# the failure halt's threshold: |stress| below this fraction of the peak
HALT_FRACTION = DeckSpec.__dataclass_fields__["halt_fraction"].default


def old_halt(log: dict, every: int, fraction: float = HALT_FRACTION) -> int | None:
    """The step a deck without the failure's aftermath stopped at: the first thermo row
    (multiple of ``every``) after the peak with |stress| below ``fraction`` of the thermo
    rows' peak so far; None if the log has none."""
    step, stress = log["TimeStep"], abs(log["v_stress"])
    rows = step % every == 0
    peak = 0.0
    for s, x, row in zip(step, stress, rows):
        if not row:
            continue
        peak = max(peak, x)
        if x < fraction * peak:
            return int(s)
    return None


def measure_run(folder: Path, test: str, summary: dict) -> dict:
    """The failure (:func:`.failure.failure_event`) and the peak kinetic fraction at every
    step, every paper's loading step (1 us) and every thermo row, from ``folder``."""
    plan = json.loads((folder / "summary.json").read_text())["plan"]
    dt, every = plan["dt"], plan["thermo_every"]
    log = read_ave_time(folder / "breaking.dat")
    event = failure_event(log, dt)
    paper_every = max(1, int(round(PAPER_SAMPLE_S / dt)))
    out = {"summary": summary, "dt": dt, "thermo_every": every, "paper_every": paper_every,
           "relax_steps": plan["relax_steps"], "step_size": plan["step_size"],
           "event": event, "window_rows": int(len(log["TimeStep"])),
           "ke": {name: peak_kinetic_fraction(log, k) for name, k in
                  (("every step", 1), ("every 1 us", paper_every), ("thermo rows", every))}}
    # a sampling once per paper_every steps at any phase: the lowest peak it can read
    phases = [peak_kinetic_fraction({k: v[(log["TimeStep"] - j) % paper_every == 0]
                                     for k, v in log.items()}, 1)["fraction"]
              for j in range(paper_every)]
    out["ke_every_1_us_lowest"] = min(phases)
    halt = old_halt(log, every)
    if halt is not None and test == "tension":
        before = {k: v[log["TimeStep"] <= halt] for k, v in log.items()}
        out["ke"]["thermo rows, old halt"] = peak_kinetic_fraction(before, every)
        out["old_halt_step"] = halt
        # what the run that stopped there measured: its heat had not reached the final value
        out["event_to_old_halt"] = failure_event(before, dt)
    out["elastic_decline_s"] = elastic_decline(folder)
    elastic = log["c_energy[1]"]
    out["ke_over_peak_elastic"] = out["ke"]["every step"]["kinetic_J"] / float(elastic.max())
    out["ke_width_s"] = peak_width(log, "c_energy[2]", dt)
    # how long the kinetic energy stays above a tenth and a hundredth of its peak: the paper
    # gives the compression failure's duration from its Fig. 6a inset of the kinetic energy
    out["ke_above_s"] = {f"{f:g}": peak_width(log, "c_energy[2]", dt, f) for f in KE_LEVELS}
    if event is not None and plan["schedule"] == "stepwise":
        # the ends' separation at the failure's start: both moved step_size per loading step
        loading_steps = math.ceil(event["start_step"] / plan["relax_steps"])
        out["elongation_m"] = 2 * plan["step_size"] * loading_steps
    return out


# fractions of the elastic energy's peak its decline after the failure is timed to
ELASTIC_LEVELS = (0.5, 0.1, 0.05)


def _fall(time, values, levels) -> dict[str, float | None]:
    """Time from the largest of ``values`` to its first row below each fraction of
    ``levels`` of it; None where the rows end first."""
    top = int(values.argmax())
    out: dict[str, float | None] = {}
    for f in levels:
        below = (values[top:] < f * values[top]).nonzero()[0]
        out[f"{f:g}"] = float(time[top + below[0]] - time[top]) if below.size else None
    return out


def elastic_decline(folder: Path) -> dict[str, dict[str, float | None]]:
    """From the thermo rows of ``folder/log.lammps``: the time from the elastic energy's peak
    (the paper's A2) to its first row below each fraction of :data:`ELASTIC_LEVELS` of that
    peak (A3: 'declines to almost zero'), and the same for |stress|."""
    table = read_thermo(folder / "log.lammps")[-1]
    return {"elastic": _fall(table["Time"], table["c_energy[1]"], ELASTIC_LEVELS),
            "stress": _fall(table["Time"], abs(table["v_stress"]), ELASTIC_LEVELS)}


def run_energy(v: Validation) -> dict:
    lattice = build_lattice(3, ENERGY_SIZE, 1.0e-3)
    span = lattice.bounds[:, 1] - lattice.bounds[:, 0]
    # eq. 28's V: the elements' volume (N sqrt2 d^3 / 2, the deck's) or the outer box's
    volume = lattice.n * math.sqrt(2) * lattice.d ** 3 / 2
    box = float((span + lattice.d).prod())
    data: dict = {"block": {"elements": lattice.n, "d": lattice.d,
                            "span_m": [float(x) for x in span],
                            "eta_box_over_elements": (volume / box) ** (1 / 3)},
                  "rock_failure_strain": rock_for(3).Tu / rock_for(3).E,
                  "halt_fraction": HALT_FRACTION, "aftermath_s": ENERGY_AFTERMATH,
                  "window_steps": BREAKING_WINDOW,
                  "runs": {}, "changes": {}, "curves": {}}
    for key, test, options, change in RUNS:
        name = _folder_name(key)
        summary = v.run(name, rock_for(3), 3, test, ENERGY_SIZE, energy=True, **options)
        data["runs"][key] = measure_run(v.folder(name), test, summary)
        data["changes"][key] = change
    for test, key in FIGURE_RUNS.items():
        folder, run = v.folder(_folder_name(key)), data["runs"][key]
        log = read_ave_time(folder / "breaking.dat")
        data["curves"][test] = {"key": key, "whole": curve(folder, CURVE_COLUMNS, points=200),
                                "window": window_rows(log, run["event"], run["dt"], AFTER_S)}
    return data


def _decline_text(run: dict) -> str:
    """The elastic energy's and the stress's fall after their peaks, in words."""
    def fall(name: str) -> str:
        return ", ".join(f"to {float(f):g} of its peak in " + ("(not within the run)" if t is None
                                                              else f"{t:.2g} s")
                         for f, t in run["elastic_decline_s"][name].items())
    return f"the elastic energy falls {fall('elastic')}; the stress {fall('stress')}"


def _us(x: float | None, digits: int = 2) -> str:
    return "" if x is None else f"{1e6 * x:.{digits}f}"


def _setup(run: dict) -> str:
    s, plan = run["summary"], run["summary"]["plan"]
    loading = (f"stepwise {plan['step_size']:.3g} m / {plan['relax_steps']} steps"
               if plan["schedule"] == "stepwise" else "constant")
    return f"{loading}, eta {plan['eta']:.3g} N s/m, dt {plan['dt']:.3g} s"


def doc_energy(data: dict, ctx: DocContext) -> list[str]:
    runs, block, p = data["runs"], data["block"], PAPER
    x_span, y_span = block["span_m"][0], block["span_m"][1]
    widths = (("x centres", x_span), ("x outer", x_span + block["d"]),
              ("y outer", y_span + block["d"]))
    paper = runs["tension_stepwise"]
    L = ["## Energy budget at the resolution of the failure (Liu 2017, section 5.3 and Fig. 6)",
         "",
         f"3D quartzite, {block['elements']} elements ({ENERGY_SIZE} along y; the paper's "
         f"model has {p['3d.energy.elements'].value:.0f}), with `compute lattice/energy` "
         "(`bonded-lattice run --energy`).  The strength decks log every term of the budget, "
         "the broken bonds and the stress at every time step of the run's last "
         f"{data['window_steps']} steps (`breaking.dat`: a ring buffer, `fix vector ... nmax`, "
         "written after the run; the failure halt ends the run soon after the failure, so the "
         "window holds it, and the file stays small however long the loading was) and run on "
         f"for {_us(data['aftermath_s'], 0)} us after the halt's condition (|stress| below "
         f"{100 * data['halt_fraction']:.0f}% of its peak) is first met, so that the kinetic "
         "energy's peak and decay are in the log.  The thermo rows give the whole run.", "",
         f"### The paper's numbers and ours (tension: the paper's set-up, {_setup(paper)})", "",
         "| quantity | the paper | ours | our definition |", "|---|---|---|---|"]
    ev, ke = paper["event"], paper["ke"]
    L.append(f"| peak kinetic energy / total energy, tension | "
             f"{100 * p['3d.energy.tension.peak_kinetic'].value:.1f}% | "
             f"{100 * ke['every step']['fraction']:.1f}% | the largest kinetic energy over the "
             "external work so far (the total energy of eq. 25: the model starts with none) at "
             f"every step; over the final work {100 * ke['every step']['over_final_work']:.1f}% |")
    L.append(f"| bonds break within, start to end (D1 to D2) | "
             f"{_us(p['3d.energy.tension.duration_s'].value)} us | {_us(ev['duration_s'])} us | "
             "from the first step whose breaking heat (normal + shear) exceeds the step "
             "before's to the step of the last increase; increases more than "
             f"{_us(ev['quiet_s'], 0)} us apart (the paper's sampling interval) split "
             "bursts, and the burst with the most heat is the failure |")
    L.append(f"| the same, 2% to 98% of the burst's heat | | {_us(ev['duration_2_98_s'])} us | "
             "the earlier page's definition |")
    for label, width in widths:
        L.append(f"| crack speed, {label} width ({1e3 * width:.2f} mm) / start to end | "
                 f"{p['3d.energy.tension.crack_speed'].value:.0f} m/s (width "
                 f"{100 * p['3d.energy.tension.width_m'].value:.1f} cm) | "
                 f"{width / ev['duration_s']:.0f} m/s | |")
    for test, key in (("tension", "tension_stepwise"), ("compression", "compression_constant")):
        e = runs[key]["summary"]["energy"]
        heats = " / ".join(f"{100 * e[h] / e['external_work']:.1f}" for h in HEATS)
        said = (f"frictional heat {p['3d.energy.tension.frictional_heat'].value:.0f}"
                if test == "tension" else "")
        L.append(f"| heat at the end, {test}: viscous / breaking normal / breaking shear / "
                 f"frictional, % of the work | {said} | {heats} | compute lattice/energy's "
                 "tallies (elements 4-7) over its work (element 8) |")
    L.append(f"| the tension model breaks in two at | "
             f"{p['3d.energy.tension.failure_time_s'].value:.4g} s | {ev['start_s']:.4g} s | "
             "the failure's start (D1), from the start of loading |")
    for key in ("compression_stepwise", "compression_constant"):
        comp = runs.get(key)
        if comp is None:
            continue
        cev = comp["event"]
        above = comp.get("ke_above_s", {})
        ke_text = "; the kinetic energy stays above " + ", ".join(
            f"{float(f):g} of its peak for {t:.2g} s" for f, t in above.items()) if above else ""
        L.append(f"| the compression failure takes ({_setup(comp)}) | about "
                 f"{p['3d.energy.compression.failure_duration_s'].value:.0e} s | "
                 f"{cev['duration_s']:.2g} s ({cev['duration_2_98_s']:.2g} s from 2% to 98%"
                 f"{ke_text}) | start to end of the burst as in tension (the paper reads its "
                 "duration off the kinetic energy of the Fig. 6a inset without a definition); "
                 f"{100 * cev['precursor_fraction']:.0f}% of the breaking heat came before it "
                 "(the opening cracks of the paper's A1) |")
    for key in ("compression_stepwise", "compression_constant"):
        comp = runs.get(key)
        if comp is None or "elastic_decline_s" not in comp:
            continue
        L.append(f"| the compression failure, A2 to A3 ({_setup(comp)}) | about "
                 f"{p['3d.energy.compression.failure_duration_s'].value:.0e} s | "
                 f"{_decline_text(comp)} | the paper: the model fails at A2 and its elastic "
                 "energy 'declines to almost zero at A3'; the times from the elastic energy's "
                 "(the stress's) peak to its first thermo row below a fraction of it, while the "
                 f"run lasts ({_us(data['aftermath_s'], 0)} us past the failure halt's "
                 "condition) |")
    L += ["", "### Like for like: from the paper's set-up to ours, one change at a time", "",
          "| run | change from the row above | set-up | KE peak / work, every step | every 1 "
          "us | thermo rows | thermo rows to the old halt | start to end (us) | 2-98% (us) | "
          "y outer width / start to end (m/s) | failure start (s) |",
          "|---|---|---|---|---|---|---|---|---|---|---|"]
    for key, run in runs.items():
        if not key.startswith("tension"):
            continue
        e, k = run["event"], run["ke"]
        old = k.get("thermo rows, old halt")
        old_text = "" if old is None else f"{100 * old['fraction']:.1f}%"
        L.append(f"| {key} | {data['changes'][key]} | {_setup(run)} | "
                 f"{100 * k['every step']['fraction']:.1f}% | "
                 f"{100 * k['every 1 us']['fraction']:.1f}% | "
                 f"{100 * k['thermo rows']['fraction']:.1f}% (every {run['thermo_every']}) | "
                 f"{old_text} | "
                 f"{_us(e['duration_s'])} | {_us(e['duration_2_98_s'])} | "
                 f"{widths[2][1] / e['duration_s']:.0f} | {e['start_s']:.4g} |")
    L += _explanation(data, widths)
    for test in ("compression", "tension"):
        c = data["curves"][test]
        run = runs[c["key"]]
        title = f"3D quartzite, {block['elements']} elements, {test} ({_setup(run)})"
        energy_curves_png(ctx.img / f"energy_3d_{test}.png", c["whole"], c["window"], title,
                          inset_kinetic_only=test == "compression")
        marks = ("C1", "C2") if test == "compression" else ("D1", "D2")
        heat_window_png(ctx.img / f"energy_3d_{test}_heat.png", c["window"], run["event"],
                        marks, title)
    L += ["", "Analogues of Fig. 6: (a) compression (our constant loading) and (b) tension "
          "(the paper's set-up), the whole run from the thermo rows, the insets from the "
          "per-step log (in compression the kinetic energy alone, as in the paper); (c) "
          "compression and (d) tension, the heat in the failure window, the failure's start "
          "and end marked.", "",
          "![energy, compression (Fig. 6a)](img/energy_3d_compression.png)",
          "![energy, tension (Fig. 6b)](img/energy_3d_tension.png)",
          "![heat at the failure, compression (Fig. 6c)](img/energy_3d_compression_heat.png)",
          "![heat at the failure, tension (Fig. 6d)](img/energy_3d_tension_heat.png)"]
    return L


def _explanation(data: dict, widths: tuple) -> list[str]:
    """What each change moves, the earlier page's numbers, and the failure time's two
    readings of the schedule."""
    runs, p, block = data["runs"], PAPER, data["block"]
    paper, const, dt1 = runs["tension_stepwise"], runs["tension_constant"], runs[
        "tension_constant_dt1e-8"]
    ke, ev = paper["ke"], paper["event"]
    peak_paper = p["3d.energy.tension.peak_kinetic"].value
    L = ["", f"**Sampling.**  At every step the paper's set-up peaks at "
         f"{100 * ke['every step']['fraction']:.1f}% (the paper: {100 * peak_paper:.1f}%).  "
         f"The kinetic energy stays above half its peak for {_us(paper['ke_width_s'])} us; "
         f"sampled once per loading step ({_us(paper['paper_every'] * paper['dt'], 0)} us, "
         f"as the paper computed its energies) the peak reads "
         f"{100 * ke['every 1 us']['fraction']:.1f}% at the ends of the relaxation periods "
         f"(at least {100 * paper['ke_every_1_us_lowest']:.1f}% whichever step of the period "
         f"is sampled), at our thermo rows (every "
         f"{paper['thermo_every']} steps, {_us(paper['thermo_every'] * paper['dt'])} us) "
         f"{100 * ke['thermo rows']['fraction']:.1f}%.  A log coarser than the peak's width "
         "misses it by as much as its rows happen to fall off it: the earlier page's stepwise "
         "number was read at these thermo rows."]
    old, old_event = ke.get("thermo rows, old halt"), paper.get("event_to_old_halt")
    if old is not None and old_event is not None:
        L += ["", f"**The earlier page's numbers.**  Before, the decks stopped at the first "
              f"thermo row with |stress| below {100 * data['halt_fraction']:.0f}% of its peak: "
              f"here step {paper['old_halt_step']}; the failure started at step "
              f"{ev['start_step']}, the kinetic energy peaked at step "
              f"{ke['every step']['step']} and the last bond of the failure broke at step "
              f"{ev['end_step']}.  Read at the thermo rows up to that step this run gives "
              f"{100 * old['fraction']:.1f}% (the constant loading "
              f"{100 * const['ke']['thermo rows, old halt']['fraction']:.1f}%, at every step "
              f"{100 * const['ke']['every step']['fraction']:.1f}%).  The breaking time was "
              f"the 2%-98% time of the heat up to the halt: {_us(old_event['duration_2_98_s'])}"
              f" us from this log cut there, {_us(ev['duration_2_98_s'])} us with the whole "
              "failure.  The paper reads Fig. 6d from start to end: "
              f"{_us(ev['duration_s'])} us here (the paper: "
              f"{_us(p['3d.energy.tension.duration_s'].value)} us), a time that hangs on "
              f"single bonds: the last one broke {_us(ev['last_pause_s'])} us after the one "
              f"before it."]
    ratio = math.log(runs["tension_constant_damping0.5"]["ke"]["every step"]["fraction"]
                     / runs["tension_constant_damping2"]["ke"]["every step"]["fraction"])
    slope = ratio / math.log(4.0)       # -d ln(peak) / d ln(eta), from eta x 0.5 to x 2
    box = block["eta_box_over_elements"]
    d05, d2 = runs["tension_constant_damping0.5"], runs["tension_constant_damping2"]
    L += ["", f"**Total energy.**  The model starts with no energy, so the total energy (eq. "
          "25) is the work done so far; the work hardly grows during the failure (the peak "
          f"over the final work: {100 * ke['every step']['over_final_work']:.1f}%).  Over the "
          f"largest elastic energy the peak is {100 * paper['ke_over_peak_elastic']:.1f}%.", "",
          "**Damping.**  The deck's eta is eq. 28 with V the elements' volume (N sqrt2 d^3 / 2)"
          f"; with V the outer box, eta would be {box:.3f} times it.  Under constant loading, "
          f"halving eta moves the every-step peak from "
          f"{100 * const['ke']['every step']['fraction']:.1f}% to "
          f"{100 * d05['ke']['every step']['fraction']:.1f}% and doubling it to "
          f"{100 * d2['ke']['every step']['fraction']:.1f}% (the peak goes as eta^-"
          f"{slope:.2f}); the start-to-end time from {_us(const['event']['duration_s'])} us "
          f"to {_us(d05['event']['duration_s'])} and {_us(d2['event']['duration_s'])} us.  "
          f"The outer box's eta would raise the paper's set-up's peak to about "
          f"{100 * ke['every step']['fraction'] * box ** -slope:.1f}%; the paper's "
          f"{100 * peak_paper:.1f}% needs eta x "
          f"{(peak_paper / ke['every step']['fraction']) ** (-1 / slope):.3f}.",
          "", f"**Loading and time step.**  From the paper's set-up, constant loading (at the "
          f"paper's time step) moves the every-step peak from "
          f"{100 * ke['every step']['fraction']:.1f}% to "
          f"{100 * dt1['ke']['every step']['fraction']:.1f}% and the start-to-end time from "
          f"{_us(ev['duration_s'])} to {_us(dt1['event']['duration_s'])} us; our time step "
          f"then gives {100 * const['ke']['every step']['fraction']:.1f}% and "
          f"{_us(const['event']['duration_s'])} us.", "",
          f"**Width.**  The block spans {1e3 * widths[0][1]:.2f} mm between centres along x and "
          f"{1e3 * (widths[2][1] - block['d']):.2f} mm along y; its outer width along y, "
          f"{ENERGY_SIZE} elements of {1e3 * block['d']:.0f} mm, is the paper's "
          f"{100 * p['3d.energy.tension.width_m'].value:.1f} cm.  The speeds are a width over "
          "the start-to-end time, as the paper takes them; which width the crack crosses "
          "depends on where it starts."]
    if "elongation_m" in paper:
        step = p["3d.schedule.tension.step_m"].value
        loading_step_s = p["3d.schedule.relax_steps"].value * p["3d.schedule.dt_s"].value
        t_paper = p["3d.energy.tension.failure_time_s"].value
        both = paper["elongation_m"] / (2 * step) * loading_step_s
        one = paper["elongation_m"] / step * loading_step_s
        height = block["span_m"][2]
        e_both = 2 * step * t_paper / loading_step_s
        e_one = step * t_paper / loading_step_s
        L += ["", f"**Failure time.**  Our block's ends are {1e6 * paper['elongation_m']:.3f} um"
              f" further apart when it starts to fail (a strain of "
              f"{paper['elongation_m'] / height:.3g} over the {1e3 * height:.2f} mm between the "
              "end layers' centres).  With both ends moving "
              f"{step:.2g} m per loading step of {_us(loading_step_s, 0)} us (the deck's "
              f"reading) that takes {both:.4g} s; with one end moving, {one:.4g} s.  Neither is "
              f"the paper's {t_paper:.4g} s, which means an elongation of {1e6 * e_both:.3f} um "
              f"(both ends, a strain of {e_both / height:.3g}) or {1e6 * e_one:.3f} um (one end, "
              f"{e_one / height:.3g}); the rock's Tu/E is {data['rock_failure_strain']:.3g}, and "
              "the multi-unit blocks fail below it."]
    return L


# slow: the paper's stepwise schedule takes the tension block about 850000 steps (20 min on
# one rank); the constant-loading runs take about a minute each
ENERGY = Section("energy", run_energy, doc_energy, slow=True)
