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

from ..decks import DeckSpec
from ..experiment import ENERGY_AFTERMATH, build_lattice
from ..io import read_ave_time
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
    ("compression_constant", "compression", {}, "ours"),
)
# the runs drawn as Fig. 6 (a/c: compression, b/d: tension)
FIGURE_RUNS = {"compression": "compression_constant", "tension": "tension_stepwise"}
# the energies' time after the failure's end kept for the figures (s): the kinetic energy
# peaks within 2 us of the end and the papers' damping halves it every 1.6 us
AFTER_S = 6.0e-6
CURVE_COLUMNS = ("Time", "c_energy[1]", "c_energy[2]", "c_energy[4]", "c_energy[5]",
                 "c_energy[6]", "c_energy[7]", "c_energy[8]", "c_energy[10]")
# the paper computed its energies once per loading step (section 5.3): 100 steps of 1e-8 s
PAPER_SAMPLE_S = PAPER["3d.schedule.relax_steps"].value * PAPER["3d.schedule.dt_s"].value


def _folder_name(key: str) -> str:
    return f"3d/fig6_n{ENERGY_SIZE}_{key}"


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
    halt = old_halt(log, every)
    if halt is not None and test == "tension":
        before = {k: v[log["TimeStep"] <= halt] for k, v in log.items()}
        out["ke"]["thermo rows, old halt"] = peak_kinetic_fraction(before, every)
        out["old_halt_step"] = halt
    elastic = log["c_energy[1]"]
    out["ke_over_peak_elastic"] = out["ke"]["every step"]["kinetic_J"] / float(elastic.max())
    out["ke_width_s"] = peak_width(log, "c_energy[2]", dt)
    if event is not None and plan["schedule"] == "stepwise":
        # the ends' separation at the failure's start: both moved step_size per loading step
        loading_steps = math.ceil(event["start_step"] / plan["relax_steps"])
        out["elongation_m"] = 2 * plan["step_size"] * loading_steps
    return out


def run_energy(v: Validation) -> dict:
    lattice = build_lattice(3, ENERGY_SIZE, 1.0e-3)
    span = lattice.bounds[:, 1] - lattice.bounds[:, 0]
    # eq. 28's V: the elements' volume (N sqrt2 d^3 / 2, the deck's) or the outer box's
    volume = lattice.n * math.sqrt(2) * lattice.d ** 3 / 2
    box = float((span + lattice.d).prod())
    data: dict = {"block": {"elements": lattice.n, "d": lattice.d,
                            "span_m": [float(x) for x in span],
                            "eta_box_over_elements": (volume / box) ** (1 / 3)},
                  "halt_fraction": HALT_FRACTION, "aftermath_s": ENERGY_AFTERMATH,
                  "runs": {}, "changes": {}, "curves": {}}
    for key, test, options, change in RUNS:
        name = _folder_name(key)
        summary = v.run(name, rock_for(3), 3, test, ENERGY_SIZE, energy=True, **options)
        data["runs"][key] = measure_run(v.folder(name), test, summary)
        data["changes"][key] = change
    for test, key in FIGURE_RUNS.items():
        folder, run = v.folder(_folder_name(key)), data["runs"][key]
        log = read_ave_time(folder / "breaking.dat")
        data["curves"][test] = {"key": key, "whole": curve(folder, CURVE_COLUMNS, points=300),
                                "window": window_rows(log, run["event"], run["dt"], AFTER_S)}
    return data


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
         f"{p['3d.energy.elements'].value:.0f}), with `compute lattice/energy` "
         "(`bonded-lattice run --energy`).  The decks log every term of the budget, the "
         "broken bonds and the stress at every time step of the run's last "
         f"{paper['window_rows']} steps (a ring buffer, `fix vector ... nmax`, written after the "
         "run: the failure halt stops the run soon after the failure, so the window holds it "
         "while the file stays bounded) and go on for a while after the failure (the kinetic "
         "energy peaks after the stress has dropped).  The thermo rows give the whole run.", "",
         "### The paper's numbers and ours (the paper's set-up: "
         f"{_setup(paper)})", "",
         "| quantity | the paper | ours | our definition |", "|---|---|---|---|"]
    ev, ke = paper["event"], paper["ke"]
    L.append(f"| peak kinetic energy / total energy, tension | "
             f"{100 * p['3d.energy.tension.peak_kinetic'].value:.1f}% | "
             f"{100 * ke['every step']['fraction']:.1f}% | the largest kinetic energy over the "
             "external work so far (the total energy, eq. 25: the model starts with none) at "
             f"every step; over the final work {100 * ke['every step']['over_final_work']:.1f}% |")
    L.append(f"| bonds break within, start to end (D1 to D2) | "
             f"{_us(p['3d.energy.tension.duration_s'].value)} us | {_us(ev['duration_s'])} us | "
             "the first step whose breaking heat (normal + shear) exceeds the step before's, "
             "to the step of the last increase; increases more than "
             f"{_us(ev['quiet_s'], 0)} us apart (the paper's sampling interval) split "
             "bursts, and the burst with the most heat is the failure |")
    L.append(f"| the same, 2% to 98% of the burst's heat | | {_us(ev['duration_2_98_s'])} us | |")
    for label, width in widths:
        L.append(f"| crack speed, {label} width ({1e3 * width:.2f} mm) / start to end | "
                 f"{p['3d.energy.tension.crack_speed'].value:.0f} m/s (width "
                 f"{100 * p['3d.energy.tension.width_m'].value:.1f} cm) | "
                 f"{width / ev['duration_s']:.0f} m/s | |")
    L.append(f"| the tension model breaks in two at | "
             f"{p['3d.energy.tension.failure_time_s'].value:.4g} s | {ev['start_s']:.4g} s | "
             "the failure's start (D1), from the start of loading |")
    comp = runs["compression_constant"]
    cev = comp["event"]
    L.append(f"| the compression failure takes | about "
             f"{p['3d.energy.compression.failure_duration_s'].value:.0e} s | "
             f"{cev['duration_s']:.2g} s ({cev['duration_2_98_s']:.2g} s from 2% to 98%) | "
             "start to end of the burst as in tension, under our constant loading "
             f"({_setup(comp)}); {100 * cev['precursor_fraction']:.0f}% of the breaking heat "
             "came before it (opening cracks, the paper's A1) |")
    L += ["", "### Like for like: from the paper's set-up to ours, one change at a time", "",
          "| run | change | set-up | KE peak / work: every step | every 1 us | thermo rows "
          "| start to end (us) | 2-98% (us) | speed, y outer / start to end (m/s) | failure "
          "start (s) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for key, run in runs.items():
        if not key.startswith("tension"):
            continue
        e, k = run["event"], run["ke"]
        L.append(f"| {key} | {data['changes'][key]} | {_setup(run)} | "
                 f"{100 * k['every step']['fraction']:.1f}% | "
                 f"{100 * k['every 1 us']['fraction']:.1f}% | "
                 f"{100 * k['thermo rows']['fraction']:.1f}% (every {run['thermo_every']}) | "
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
    L += ["", "Analogues of Fig. 6: (a) compression and (b) tension, the whole run from the "
          "thermo rows, the insets at every step of the failure; (c) compression and (d) "
          "tension, the heat at every step of the failure window, the start and the end "
          "marked.", "",
          "![energy, compression (Fig. 6a)](img/energy_3d_compression.png)",
          "![energy, tension (Fig. 6b)](img/energy_3d_tension.png)",
          "![heat at the failure, compression (Fig. 6c)](img/energy_3d_compression_heat.png)",
          "![heat at the failure, tension (Fig. 6d)](img/energy_3d_tension_heat.png)"]
    return L


def _explanation(data: dict, widths: tuple) -> list[str]:
    """What each change moves, the earlier numbers, and the failure time's two readings."""
    runs, p = data["runs"], PAPER
    paper, const = runs["tension_stepwise"], runs["tension_constant"]
    ke, cke = paper["ke"], const["ke"]
    L = ["", f"Sampling.  At every step the paper's set-up peaks at "
         f"{100 * ke['every step']['fraction']:.1f}% (the paper: "
         f"{100 * p['3d.energy.tension.peak_kinetic'].value:.1f}%); sampled once per loading "
         f"step ({_us(paper['paper_every'] * paper['dt'], 0)} us, how the paper computed its "
         f"energies) {100 * ke['every 1 us']['fraction']:.1f}%, at our thermo rows (every "
         f"{paper['thermo_every']} steps) {100 * ke['thermo rows']['fraction']:.1f}%.  The "
         "kinetic energy's peak lasts about a microsecond, so a coarse log misses it by an "
         "amount that depends on where its rows fall."]
    if "thermo rows, old halt" in ke:
        L.append(f"Before this section the decks stopped at the first thermo row with |stress| "
                 "below 30% of the peak, before the kinetic energy had peaked: read at the thermo "
                 "rows up to that step (step "
                 f"{paper['old_halt_step']}) the same run gives "
                 f"{100 * ke['thermo rows, old halt']['fraction']:.1f}% (and the constant "
                 f"loading {100 * cke['thermo rows, old halt']['fraction']:.1f}%), the earlier "
                 "page's numbers; the halt now waits until the energy has been damped.")
    L.append(f"Total energy.  The model starts with no energy, so the total energy (eq. 25) is "
             "the work done so far; the work hardly grows during the failure (over the final "
             f"work: {100 * ke['every step']['over_final_work']:.1f}%).  Over the largest "
             f"elastic energy the peak is {100 * paper['ke_over_peak_elastic']:.1f}%.")
    d05, d2 = runs["tension_constant_damping0.5"], runs["tension_constant_damping2"]
    L.append("Damping.  The deck's eta is eq. 28 with V the elements' volume (N sqrt2 d^3/2); "
             "the outer box would change it by a few per cent.  Halving eta (constant loading) "
             f"moves the every-step peak from {100 * cke['every step']['fraction']:.1f}% to "
             f"{100 * d05['ke']['every step']['fraction']:.1f}%, doubling it to "
             f"{100 * d2['ke']['every step']['fraction']:.1f}%; the start-to-end time from "
             f"{_us(const['event']['duration_s'])} to {_us(d05['event']['duration_s'])} and "
             f"{_us(d2['event']['duration_s'])} us.")
    L.append(f"Loading and time step.  Constant loading at the paper's time step and at ours "
             f"gives {_us(runs['tension_constant_dt1e-8']['event']['duration_s'])} and "
             f"{_us(const['event']['duration_s'])} us start to end against "
             f"{_us(paper['event']['duration_s'])} us stepwise (the paper: "
             f"{_us(p['3d.energy.tension.duration_s'].value)} us).  The 2%-98% times are "
             "shorter because the first and the last bonds break alone, slowly.")
    L.append(f"Width.  The block spans {1e3 * widths[0][1]:.2f} mm between centres along x "
             f"and {1e3 * (widths[2][1] - data['block']['d']):.2f} mm along y; its outer "
             f"width along y, {ENERGY_SIZE} elements of {1e3 * data['block']['d']:.0f} mm, is "
             "the paper's 1.2 cm; which width the crack crosses depends on where it starts, "
             "so the speeds are given for each.")
    if "elongation_m" in paper:
        step = p["3d.schedule.tension.step_m"].value
        loading_step_s = p["3d.schedule.relax_steps"].value * p["3d.schedule.dt_s"].value
        t_paper = p["3d.energy.tension.failure_time_s"].value
        both = paper["elongation_m"] / (2 * step) * loading_step_s
        one = paper["elongation_m"] / step * loading_step_s
        L.append(f"Failure time.  Our block's ends are {1e6 * paper['elongation_m']:.3f} um "
                 "further apart when it fails.  With both ends moving "
                 f"{step:.2g} m per loading step of {_us(loading_step_s, 0)} us (our reading) "
                 f"that takes {both:.4g} s; with one end moving, {one:.4g} s.  The paper's "
                 f"{t_paper:.4g} s means an elongation of {1e6 * 2 * step * t_paper / loading_step_s:.3f}"
                 f" um (both ends) or {1e6 * step * t_paper / loading_step_s:.3f} um (one end).")
    return L


ENERGY = Section("energy", run_energy, doc_energy)
