"""The papers' stepwise schedule against our constant loading at one size per dimension:
strength and cost."""

from __future__ import annotations

from .doc import DocContext, pct
from .runner import Validation, rock_for
from .section import Section

__all__ = ["SCHEDULE"]

SCHEDULE_SIZE = {2: 15, 3: 6}


def run_schedule(v: Validation) -> dict:
    data = {}
    for dim in (2, 3):
        n, rock = SCHEDULE_SIZE[dim], rock_for(dim)
        data[str(dim)] = {
            test: {"stepwise": v.run(f"{dim}d/paper_n{n}_{test}", rock, dim, test, n,
                                     schedule="stepwise"),
                   "constant": v.run(f"{dim}d/n{n}_{test}", rock, dim, test, n)}
            for test in ("tension", "compression")}
    return data


def doc_schedule(data: dict, ctx: DocContext) -> list[str]:
    L = ["## The papers' stepwise schedule against constant loading", "",
         "| dim | test | particles | schedule | strength error | time steps | run time (s) |",
         "|---|---|---|---|---|---|---|"]
    ratios = []
    for dim, tests in data.items():
        for test, runs in tests.items():
            key = "Tu" if test == "tension" else "Cu"
            for name, r in runs.items():
                L.append(f"| {dim}D | {test} | {r['particles']} | {name} | "
                         f"{pct(r['relative_error'][key])} | {r['plan']['steps']} | "
                         f"{r['wall_time_s']:.0f} |")
            ratios.append(runs["stepwise"]["plan"]["steps"] / runs["constant"]["plan"]["steps"])
    L += ["", "Both at the papers' damping; time steps are the planned maximum (strength runs "
          "stop after failure).  The stepwise schedule plans "
          f"{min(ratios):.0f} to {max(ratios):.0f} times more time steps."]
    return L


SCHEDULE = Section("schedule", run_schedule, doc_schedule, slow=True)
