"""The page's first table: every paper result next to ours under the paper's set-up and under
our defaults, with what the like-for-like runs measured about the difference.

Built from the other sections' data in the results file; a row whose data are missing is left
out.  "Papers' set-up" means the stepwise schedule and the papers' damping (section
``like_for_like``); "defaults" the package's constant loading (section ``series``).
"""

from __future__ import annotations

import numpy as np

from .checks import papers_setup_mean
from .doc import pct
from .geometry import section_factor
from .grips import GRIP_VARIANTS, grip_label, grip_means
from .ladder import RUNGS, change, rung_errors
from .papers import PAPER
from .results import section_data

__all__ = ["overview_lines"]

TESTS = {"Tu": "tension", "Cu": "compression"}
RUNG_LABELS = {"outer_area": "outer area", **{k: v[0] for k, v in RUNGS.items()}}
RUNG_ORDER = ("outer_area", "constant", "damping_0.25", "damping_0.1", "platens_1", "layers",
              "defaults")


def overview_lines(results: dict) -> list[str]:
    """The side-by-side table (empty if no section it draws on is in ``results``)."""
    rows: list[tuple[str, str, str, str, str]] = []
    for build in (_unit_rows, _ladder_rows, _platen_rows, _elastic_rows, _energy_rows):
        rows += build(results)
    if not rows:
        return []
    lines = ["## The papers' results side by side", "",
             "Each paper result, ours under the paper's set-up (the stepwise schedule and "
             "the papers' damping) and under our defaults (constant loading), and what the "
             "like-for-like runs (below) measured about the difference.", "",
             "| result | paper | ours, papers' set-up | ours, defaults | the difference, "
             "measured |", "|---|---|---|---|---|"]
    lines += [f"| {' | '.join(r)} |" for r in rows]
    return lines + [""]


def _unit_rows(results: dict) -> list[tuple[str, str, str, str, str]]:
    data = section_data(results, "units")
    if data is None:
        return []
    rows = []
    for dim in ("2", "3"):
        for key, test in TESTS.items():
            ours = data[dim][test]["relative_error"][key]
            paper = PAPER[f"{dim}d.unit.{key}"].value
            rows.append((f"{dim}D single unit, {key}", pct(paper, 3), pct(ours, 3), "",
                         f"{100 * (ours - paper):+.3f} points"))
    return rows


def _mean(values: list[float]) -> float:
    return float(np.mean(values))


def _ladder_rows(results: dict) -> list[tuple[str, str, str, str, str]]:
    ladder, series = section_data(results, "like_for_like"), section_data(results, "series")
    if ladder is None or series is None:
        return []
    rows = []
    for dim in ("2", "3"):
        size = "N" if dim == "2" else "n_y"
        for key, test in TESTS.items():
            lad = [r for r in ladder[dim] if r["test"] == test and r["n"] > 2]
            errs = [rung_errors(r) for r in lad]
            ser = [r for r in series[dim] if r["n"] > 2]
            setup, how = papers_setup_mean(results, dim, key)
            setup_text = f"{pct(setup)} ({how})"
            with_defaults = [r for r in ser if f"{test}_defaults" in r]
            defaults_text = "" if not with_defaults else (
                f"{pct(_mean([r[f'{test}_defaults']['relative_error'][key] for r in with_defaults]))}"
                f" ({size} = {min(r['n'] for r in with_defaults)}-"
                f"{max(r['n'] for r in with_defaults)})")
            paper = PAPER[f"{dim}d.multi.{key}"].value
            rungs = [c for c in RUNG_ORDER if any(c in e for e in errs)]
            moves = ", ".join(f"{RUNG_LABELS[c]} {100 * change(errs, c):+.1f}" for c in rungs)
            grips = section_data(results, "grips")
            cell = (f"; a periodic cell (no grips, no free faces) gives "
                    f"{pct(_mean([r['periodic']['relative_error']['Tu'] for r in grips[dim]]))}"
                    if grips is not None and key == "Tu" else "")
            other = (_grip_text(grips[dim], paper, setup) if grips is not None and key == "Tu"
                     else "")
            rows.append((f"{dim}D multi-unit mean, {key}", pct(paper), setup_text,
                         defaults_text,
                         f"gap {100 * (setup - paper):+.1f} points; one change at a time from "
                         f"the papers' set-up moves ours by: {moves}{cell}{other}"))
        if dim == "2":
            n30 = next((r for r in ladder[dim] if r["n"] == 30 and r["test"] == "tension"), None)
            s30 = next((r for r in series[dim] if r["n"] == 30), None)
            if n30 is not None and s30 is not None:
                ours = rung_errors(n30)["paper"]
                paper = PAPER["2d.n30.Tu"].value
                grips = section_data(results, "grips")
                g30 = next((r for r in grips["2"] if r["n"] == 30), None) if grips else None
                bracket = (f"; a periodic cell (no grips, no free faces) gives "
                           f"{pct(g30['periodic']['relative_error']['Tu'])}: the paper's value "
                           "lies between our held end layers and no grips at all; the paper "
                           "does not say how it pulled its blocks" if g30 else "")
                other = _grip_text(grips["2"], paper, ours, 30) if g30 else ""
                rows.append(("2D Tu, 1033 particles (N = 30)", pct(paper), pct(ours),
                             pct(s30["tension_defaults"]["relative_error"]["Tu"]),
                             f"gap {100 * (ours - paper):+.1f} points{bracket}{other}"))
    return rows


def _grip_text(rows: list[dict], paper: float, ours: float, n: int | None = None) -> str:
    """What the other grips of section 'grips' do to ``ours`` (the held end layers' Tu error)
    against the paper's ``paper``: each grip's shift from the held end layers (mean over the
    section's sizes, or at size ``n``) added to ``ours``, and the grip that brings it closest
    ('' without the variants' data)."""
    if not all("variants" in r for r in rows):
        return ""
    if n is None:
        errors = grip_means(rows)
    else:
        row = next(r for r in rows if r["n"] == n)
        errors = {"held": row["held"]["relative_error"]["Tu"],
                  **{k: row["variants"][k]["relative_error"]["Tu"] for k in GRIP_VARIANTS}}
    shifts = {k: e - errors["held"] for k, e in errors.items()}
    best = min(shifts, key=lambda k: abs(ours + shifts[k] - paper))
    sizes = (f"N = {n}" if n is not None else
             f"{'N' if rows[0]['held']['dim'] == 2 else 'n_y'} = "
             + ", ".join(str(r["n"]) for r in rows))
    moves = ", ".join(f"{grip_label(k)} {100 * shifts[k]:+.1f}" for k in GRIP_VARIANTS)
    text = f"; other grips move ours by ({sizes}, section 'grips'): {moves}"
    if best == "held":
        return text + ("; none brings ours closer to the paper than the held end layers: the "
                       "grips do not explain the gap")
    return (text + f"; the {grip_label(best)} bring ours closest, to "
            f"{pct(ours + shifts[best])} (gap {100 * (ours + shifts[best] - paper):+.1f} points)")


def _elastic_rows(results: dict) -> list[tuple[str, str, str, str, str]]:
    series = section_data(results, "series")
    if series is None:
        return []
    row = next((r for r in series["2"] if r["n"] == 4), None)
    if row is None:
        return []
    el = row["elastic"]
    ours = el["relative_error"]["E"]
    outer = (1 + ours) * section_factor(el) - 1
    strain = section_data(results, "platen_strain")
    s4 = next((r for r in strain["2"] if r["n"] == 4), None) if strain is not None else None
    by_strain = ""
    if s4 is not None:
        e = {f"{k:g}": s4["by_platens"][f"{k:g}"]["E"] for k in strain["stiffnesses"]}
        ours_k = next(iter(e))     # the platens of the elastic test (2 Kn)
        by_strain = ("; with the strain from the end rows' displacement "
                     f"{pct(e[ours_k]['end_rows'])}, from the platens' travel over the outer "
                     "height " + ", ".join(f"{pct(e[k]['platens_faces'])} (platens {k} Kn)"
                                          for k in e)
                     + f", over the centres' span {pct(e[ours_k]['platens_centres'])} (section "
                     "'2D E by the strain's definition')")
    rows = [("2D E, 18 particles (N = 4)", f"about {pct(PAPER['2d.n4.E'].value, 0)}",
             pct(ours), pct(ours),
             f"the outer stress area would give {pct(outer)}: the paper's stresses use the "
             f"centres' span (or an area as close to it){by_strain}")]
    multi = [r["elastic"] for r in series["3"] if r["n"] > 2]
    if multi:
        e = _mean([abs(r["relative_error"]["E"]) for r in multi])
        nu = _mean([abs(r["relative_error"]["nu"]) for r in multi])
        nu_all = _mean([abs(r["nu_all_particles"] / r["target"]["nu"] - 1) for r in multi])
        worst = max(multi, key=lambda r: abs(r["relative_error"]["nu"]))
        rows.append(("3D multi-unit elastic errors, mean magnitude",
                     f"about {100 * PAPER['3d.multi.elastic'].value:.1f}%",
                     f"E {100 * e:.2f}%, nu {100 * nu:.2f}%", "the same (elastic test)",
                     f"nu from mid-height side gauges, largest {pct(worst['relative_error']['nu'])}"
                     f" ({worst['particles']} elements, few particles at mid-height); the "
                     f"all-particle fit gives {100 * nu_all:.2f}%, a free-face deficit falling as "
                     "1/n_y (section 'Block sizes')"))
    return rows


def _platen_rows(results: dict) -> list[tuple[str, str, str, str, str]]:
    data = section_data(results, "platens")
    if data is None:
        return []
    rows = []
    for dim in ("2", "3"):
        runs = [r["runs"] for r in data[dim]["rows"]]
        kn = _mean([r["1"]["relative_error"]["Cu"] for r in runs])
        ours = _mean([r["2"]["relative_error"]["Cu"] for r in runs])
        held = _mean([r["layers"]["relative_error"]["Cu"] for r in runs])
        sizes = ", ".join(str(r["n"]) for r in data[dim]["rows"])
        rows.append((f"{dim}D multi-unit Cu and the platens ({'N' if dim == '2' else 'n_y'} "
                     f"= {sizes})", pct(PAPER[f'{dim}d.multi.Cu'].value),
                     f"{pct(kn)} with platen springs of Kn", f"{pct(ours)} (platens 2 Kn)",
                     f"the platens' stiffness sets the deficit: held end layers instead of "
                     f"platens give {pct(held)}; the papers do not state their platens' "
                     "stiffness (section 'The platens decide the compressive deficit')"))
    return rows


def _share(x: float) -> str:
    return f"{100 * x:.1f}%"


def _energy_rows(results: dict) -> list[tuple[str, str, str, str, str]]:
    data = section_data(results, "energy")
    if data is None:
        return []
    runs = data["runs"]
    paper_run, ours = runs.get("tension_stepwise"), runs.get("tension_constant")
    rows = []
    if paper_run is not None and ours is not None:
        key = "3d.energy.tension"
        width = data["block"]["span_m"][1] + data["block"]["d"]
        rows += [
            ("3D tension: peak kinetic energy / work", _share(PAPER[f"{key}.peak_kinetic"].value),
             _share(paper_run["ke"]["every step"]["fraction"]),
             _share(ours["ke"]["every step"]["fraction"]),
             f"at every step; read at thermo rows every {paper_run['thermo_every']} steps the "
             f"same run gives {_share(paper_run['ke']['thermo rows']['fraction'])} (the earlier "
             "page's number): sampling"),
            ("3D tension: bonds break within, start to end",
             f"{1e6 * PAPER[f'{key}.duration_s'].value:.2f} us",
             f"{1e6 * paper_run['event']['duration_s']:.2f} us",
             f"{1e6 * ours['event']['duration_s']:.2f} us",
             f"2%-98%: {1e6 * paper_run['event']['duration_2_98_s']:.2f} us (the earlier page's "
             "definition, on heat cut short by the old halt)"),
            ("3D tension: crack speed", f"{PAPER[f'{key}.crack_speed'].value:.0f} m/s",
             f"{width / paper_run['event']['duration_s']:.0f} m/s",
             f"{width / ours['event']['duration_s']:.0f} m/s",
             f"over the outer width along y, {1e3 * width:.1f} mm (the paper's 1.2 cm)"),
            ("3D tension: the model breaks in two at",
             f"{PAPER[f'{key}.failure_time_s'].value:.4g} s",
             f"{paper_run['event']['start_s']:.4g} s", "",
             "the paper's time needs a failure strain above the rock's Tu/E with both ends "
             "moving, or far below it with one (section 'Energy budget'): not explained"),
        ]
    comp, comp_paper = runs.get("compression_constant"), runs.get("compression_stepwise")
    if comp is not None:
        paper_text = "" if comp_paper is None else f"{comp_paper['event']['duration_s']:.2g} s"
        rows.append(("3D compression: the failure takes",
                     f"about {PAPER['3d.energy.compression.failure_duration_s'].value:.0e} s",
                     paper_text, "",
                     "start to end of the breaking-heat burst; under constant loading at "
                     f"the papers' damping {comp['event']['duration_s']:.2g} s; "
                     + (f"the elastic energy falls to half its peak in "
                        f"{comp_paper['elastic_decline_s']['elastic']['0.5']:.2g} s "
                        if comp_paper and "elastic_decline_s" in comp_paper
                        and comp_paper['elastic_decline_s']['elastic']['0.5'] else "")
                     + "(section 'Energy budget'): the paper's time lies between the two readings; "
                     "not explained"))
    return rows
