"""Sections on blocks of the papers' sizes: the single units and the series of sizes (Liu 2013
Figs. 2, 8; Liu 2017 Figs. 2b, 4)."""

from __future__ import annotations

import numpy as np

from ..plotting import convergence_png
from .doc import DocContext, paper_pct, pct
from .papers import paper_value
from .geometry import section_factor
from ..schedules import DEFAULT_LOADING, default_loading
from .runner import PAPER_DAMPING_LOADING, Validation, rock_for
from .section import Section

__all__ = ["SERIES", "UNITS"]

# 3D compression also at 1000 wave crossings to failure, which section loading_3d shows within
# 0.4 points of the stepwise schedule (100 crossings read Cu 5-8 points high on small blocks),
# up to the size whose slow run still costs minutes
SLOW_3D_CROSSINGS = 1000.0
SLOW_3D_MAX = 20



def run_units(v: Validation) -> dict:
    data = {}
    for dim in (2, 3):
        rock = rock_for(dim)
        unit = {"elastic": v.run(f"{dim}d/unit_elastic", rock, dim, "elastic", 2,
                                 elastic_strain=1e-6)}
        for test in ("tension", "compression"):
            unit[test] = v.run(f"{dim}d/unit_{test}", rock, dim, test, 2, schedule="stepwise")
        data[str(dim)] = unit
    return data


def doc_units(data: dict, ctx: DocContext) -> list[str]:
    L = ["## Single units (Liu 2013 Fig. 2, Liu 2017 Fig. 2b)", "",
         "| | E (strain -1e-6) | nu | Tu | Cu | C_open | papers |", "|---|---|---|---|---|---|---|"]
    for dim in ("2", "3"):
        u = data[dim]
        L.append(f"| {dim}D ({u['elastic']['particles']} particles) | "
                 f"{pct(u['elastic']['relative_error']['E'], 4)} | "
                 f"{pct(u['elastic']['relative_error']['nu'], 4)} | "
                 f"{pct(u['tension']['relative_error']['Tu'], 3)} | "
                 f"{pct(u['compression']['relative_error']['Cu'], 3)} | "
                 f"{pct(u['compression']['relative_error'].get('C_open'))} | "
                 f"Tu {paper_pct(f'{dim}d.unit.Tu', 3)}, Cu {paper_pct(f'{dim}d.unit.Cu')} |")
    plan2, plan3 = data["2"]["compression"]["plan"], data["3"]["compression"]["plan"]
    L += ["", "Strengths with the papers' stepwise schedule (platen steps of "
          f"{data['2']['tension']['plan']['step_size']:.2g} / {plan2['step_size']:.2g} m "
          f"(2D) and {data['3']['tension']['plan']['step_size']:.2g} / "
          f"{plan3['step_size']:.2g} m (3D), with {plan2['relax_steps']} and "
          f"{plan3['relax_steps']} relaxation steps after each).  Cu falls below the formula "
          "because the inclined bonds rotate before they slide; "
          "`tests/validation/test_single_unit.py` checks the units against the exact "
          "finite-strain path.  C_open is the last thermo row before the base bonds open, "
          "one load step early."]
    return L


def run_series(v: Validation) -> dict:
    """Per size: the elastic test, and Tu and Cu with constant loading at the papers'
    damping; also Tu and Cu under our defaults (:data:`~bonded_lattice.schedules.DEFAULT_LOADING`;
    in 3D up to n_y = :data:`SLOW_3D_MAX`, as their compression is slow), and in 3D Cu at
    :data:`SLOW_3D_CROSSINGS` crossings."""
    data = {}
    for dim in (2, 3):
        rock = rock_for(dim)
        rows = []
        for n in v.sizes(dim):
            row = {"n": n}
            for test in ("elastic", "tension", "compression"):
                row[test] = v.run(f"{dim}d/n{n}_{test}", rock, dim, test, n)
            if dim == 2 or n <= SLOW_3D_MAX:
                for test in ("tension", "compression"):
                    row[f"{test}_defaults"] = v.run(f"{dim}d/n{n}_{test}_defaults", rock, dim,
                                                    test, n, crossings=None, damping=None)
            if dim == 3 and n <= SLOW_3D_MAX:
                row["compression_slow"] = v.run(
                    f"3d/n{n}_compression_c{SLOW_3D_CROSSINGS:g}", rock, dim, "compression", n,
                    crossings=SLOW_3D_CROSSINGS)
            rows.append(row)
        data[str(dim)] = rows
    return data


def multi_mean(rows: list[dict], key: str, test: str, factor: bool = False) -> float:
    """Mean relative error of ``key`` over the multi-unit sizes; with ``factor`` on the
    outer cross-section."""
    vals = [(1 + r[test]["relative_error"][key]) * (section_factor(r[test]) if factor else 1)
            - 1 for r in rows if r["n"] > 2]
    return float(np.mean(vals))


def _series_table(dim: str, rows: list[dict]) -> list[str]:
    slow = dim == "3"
    head = ("| " + ("N" if dim == "2" else "n_y") + " | particles | E | E, outer area | "
            "nu (gauges) | nu (all-particle fit) | Tu | Cu | Tu, outer area | Cu, outer area | "
            "Tu, defaults | Cu, defaults | "
            + (f"Cu, {SLOW_3D_CROSSINGS:g} crossings | " if slow else "")
            + "C_open | run time (s) |")
    L = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        el, te, co = r["elastic"], r["tension"], r["compression"]
        secs = sum(r[k]["wall_time_s"] for k in r if k != "n")
        nu_all = el["nu_all_particles"] / el["target"]["nu"] - 1
        outer = [(1 + run["relative_error"][k]) * section_factor(run) - 1
                 for run, k in ((el, "E"), (te, "Tu"), (co, "Cu"))]
        cells = [str(r["n"]), str(el["particles"]), pct(el["relative_error"]["E"]),
                 pct(outer[0]), pct(el["relative_error"]["nu"]), pct(nu_all),
                 pct(te["relative_error"]["Tu"]), pct(co["relative_error"]["Cu"]),
                 pct(outer[1]), pct(outer[2])]
        for test, key in (("tension", "Tu"), ("compression", "Cu")):
            run = r.get(f"{test}_defaults")
            cells.append(pct(run["relative_error"][key]) if run else "")
        if slow:
            run = r.get("compression_slow")
            cells.append(pct(run["relative_error"]["Cu"]) if run else "")
        cells += [pct(co["relative_error"].get("C_open")), f"{secs:.0f}"]
        L.append("| " + " | ".join(cells) + " |")
    return L


def doc_series(data: dict, ctx: DocContext) -> list[str]:
    L = ["## Block sizes (Liu 2013 Figs. 6, 8; Liu 2017 Fig. 4)", "",
         "Elastic test to strain -1e-4 with unbreakable bonds (Xb and Fs0 x 100, as in "
         "Liu 2017); strength tests with constant loading (platens at a speed that takes "
         f"{PAPER_DAMPING_LOADING['crossings']:g} elastic-wave crossings to reach the failure "
         f"strain) at the papers' damping.  The 'defaults' columns are the package's defaults "
         f"({_defaults_text()}; in 3D up to n_y = {SLOW_3D_MAX}); in 3D Cu is also measured at "
         f"{SLOW_3D_CROSSINGS:g} crossings at the papers' damping, slow enough to be converged "
         "(section '3D compression: how slow constant loading must be').  Stress "
         "is the platen force over the area between the outermost particles' centres; the "
         "'outer area' columns divide by the outer cross-section instead (the centres' span "
         "plus a diameter across each lateral direction)."]
    for dim, label in (("2", "2D quartz"), ("3", "3D quartzite")):
        rows = data[dim]
        L += ["", f"### {label}", ""] + _series_table(dim, rows) + [""]
        means = {(k, f): multi_mean(rows, k, t, f) for k, t in (("Tu", "tension"),
                                                               ("Cu", "compression"))
                 for f in (False, True)}
        L.append(f"Mean over the multi-unit sizes here: Tu {pct(means['Tu', False])} "
                 f"(outer area {pct(means['Tu', True])}; paper {paper_pct(f'{dim}d.multi.Tu')}),"
                 f" Cu {pct(means['Cu', False])} (outer area {pct(means['Cu', True])}; paper "
                 f"{paper_pct(f'{dim}d.multi.Cu')}).  " + _defaults_means(dim, rows))
        if dim == "2":
            n4 = next((r for r in rows if r["n"] == 4), None)
            if n4 is not None:
                el = n4["elastic"]
                outer = (1 + el["relative_error"]["E"]) * section_factor(el) - 1
                L += ["", f"The paper's only per-size elastic number, E of the 18-particle block "
                      f"{paper_pct('2d.n4.E', 0)} (Liu 2013, para. 45), decides the stress area: "
                      f"we get {pct(el['relative_error']['E'])} with the centres' area and "
                      f"{pct(outer)} with the outer one."]
        sizes = [r for r in rows if r["n"] > 2]
        e_max = max(abs(r["elastic"]["relative_error"]["E"]) for r in sizes)
        L += ["", f"E is within {100 * e_max:.2f}% of the formula at every multi-unit size.  The "
              "all-particle lateral fit of Poisson's ratio carries a free-face deficit that "
              "falls as 1/N (fit below); the mid-height gauges measure the interior.",
              "", _free_face_fit(dim, sizes)]
        convergence_png(ctx.img / f"convergence_{dim}d.png", int(dim), rows,
                        {k: paper_value(f"{dim}d.multi.{k}") for k in ("Tu", "Cu")})
        L += ["", f"![E, nu, Tu and Cu against particle count, {dim}D](img/convergence_{dim}d.png)"]
    return L


def _defaults_means(dim: str, rows: list[dict]) -> str:
    """The defaults columns' means over the multi-unit sizes that have them."""
    parts = []
    for key, test in (("Tu", "tension"), ("Cu", "compression")):
        sel = [r for r in rows if r["n"] > 2 and f"{test}_defaults" in r]
        if sel:
            mean = float(np.mean([r[f"{test}_defaults"]["relative_error"][key] for r in sel]))
            size = "N" if dim == "2" else "n_y"
            parts.append(f"{key} {pct(mean)} ({size} = {sel[0]['n']}-{sel[-1]['n']})")
    return f"Under the package's defaults: {', '.join(parts)}." if parts else ""


def _defaults_text() -> str:
    """The strength tests' defaults in words, from
    :func:`~bonded_lattice.schedules.default_loading`."""
    parts = []
    for dim, values in DEFAULT_LOADING.items():   # the damping is per dimension only
        crossings = ", ".join(f"{default_loading(dim, t)['crossings']:g} crossings in {t}"
                              for t in ("tension", "compression"))
        parts.append(f"{dim}D {crossings} at eta x {values['damping']:g}")
    return "; ".join(parts)


def _free_face_fit(dim: str, rows: list[dict]) -> str:
    n = np.array([r["n"] for r in rows], dtype=float)
    err = np.array([r["elastic"]["nu_all_particles"] / r["elastic"]["target"]["nu"] - 1
                    for r in rows])
    c = float(np.sum(err / n) / np.sum(1 / n**2))     # least squares of err = c / n
    resid = float(np.max(np.abs(err - c / n)))
    size = "N" if dim == "2" else "n_y"
    return (f"All-particle fit of nu: error = {100 * c:.0f}/{size} % (least squares over "
            f"the multi-unit sizes; largest deviation from it {pct(resid)}).")


UNITS = Section("units", run_units, doc_units)
SERIES = Section("series", run_series, doc_series)
