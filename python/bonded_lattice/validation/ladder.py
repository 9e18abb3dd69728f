"""Like for like: the strengths under the papers' own set-up, then one choice at a time
changed to ours (issue 19, point 1).

The papers' set-up (Liu 2013 sections 5.2-5.3, Liu 2017 section 5.1): the stepwise schedule
(platens jump, then the block relaxes), the papers' damping eta (2D sqrt(8 m Kn)/N, 3D
d/V^(1/3) sqrt(8 m Kn)), smooth platens, the papers' block sizes, strength = the peak
stress.  The choices that differ or that the papers leave open, each changed alone:

- the stress area: the centres' span (ours) or the outer cross-section (Liu 2017: "the area
  of the model cross section"); a measurement choice, applied to the same run;
- the loading: constant platen speed (100 elastic-wave crossings to failure) instead of
  the stepwise schedule, at the papers' damping;
- the damping: a quarter of eta (our 2D default) and a tenth, under the stepwise schedule;
- the platens: springs of the bonds' stiffness Kn instead of our 2 Kn (the papers do not state
  theirs), or none: the end layers held and moved as in tension (compression only);
- everything ours: the package's defaults (constant loading,
  :data:`~bonded_lattice.schedules.DEFAULT_LOADING`).

The stepwise schedule costs 30 to 350 times the time steps of constant loading, so the ladder
stops at the sizes listed in :data:`LADDER_SIZES`; the series (section ``series``) carries the
larger sizes under constant loading at the papers' damping.
"""

from __future__ import annotations

import numpy as np

from ..plotting import pyplot, save_png
from .doc import DocContext, paper_pct, pct
from .geometry import section_factor
from .runner import Validation, rock_for
from .section import Section

__all__ = ["LADDER", "LADDER_SIZES", "RUNGS", "change", "rung_errors"]

LADDER_SIZES = {2: [4, 8, 15, 30], 3: [4, 6, 8]}
# above these sizes only the papers' set-up, constant loading and the defaults are run (the
# paper's one per-size strength is Tu of the 1033-particle block, N = 30, Liu 2013 para. 54)
FULL_LADDER_MAX = {2: 15, 3: 8}
CORE_RUNGS = ("paper", "constant", "defaults")
# rung name: (label, RockTest options, the tests it applies to); the platens push only in
# compression (tension moves the end layers)
RUNGS = {
    "paper": ("papers' set-up", {"schedule": "stepwise"}, ("tension", "compression")),
    "constant": ("constant loading", {}, ("tension", "compression")),
    "damping_0.25": ("damping x 0.25", {"schedule": "stepwise", "damping": 0.25},
                     ("tension", "compression")),
    "damping_0.1": ("damping x 0.1", {"schedule": "stepwise", "damping": 0.1},
                    ("tension", "compression")),
    "platens_1": ("platens Kn", {"schedule": "stepwise", "platen_stiffness": 1.0},
                  ("compression",)),
    "layers": ("end layers held", {"schedule": "stepwise", "ends": "layers"}, ("compression",)),
    "defaults": ("ours (defaults)", {"crossings": None, "damping": None},
                 ("tension", "compression")),
}
TESTS = {"tension": "Tu", "compression": "Cu"}


def _folder(dim: int, n: int, test: str, rung: str) -> str:
    """Run folders shared with the other sections: the stepwise runs of ``schedule``
    (``paper_n..``) and the series' runs (``n.._test``, ``.._defaults``)."""
    if rung == "paper":
        return f"{dim}d/paper_n{n}_{test}"
    if rung == "constant":
        return f"{dim}d/n{n}_{test}"
    if rung == "defaults":
        return f"{dim}d/n{n}_{test}_defaults"
    return f"{dim}d/paper_n{n}_{test}_{rung}"


def run_ladder(v: Validation) -> dict:
    data = {}
    for dim in (2, 3):
        rock, rows = rock_for(dim), []
        for n in LADDER_SIZES[dim]:
            for test in TESTS:
                rungs = {}
                for rung, (_, options, tests) in RUNGS.items():
                    if test not in tests:
                        continue
                    if n > FULL_LADDER_MAX[dim] and rung not in CORE_RUNGS:
                        continue
                    rungs[rung] = v.run(_folder(dim, n, test, rung), rock, dim, test, n,
                                        **options)
                rows.append({"n": n, "test": test, "rungs": rungs})
        data[str(dim)] = rows
    return data


def rung_errors(row: dict) -> dict[str, float]:
    """The strength error of each rung of a ladder row, plus ``outer_area``: the papers'
    set-up measured on the outer cross-section."""
    key = TESTS[row["test"]]
    errs = {rung: run["relative_error"][key] for rung, run in row["rungs"].items()}
    paper = row["rungs"]["paper"]
    errs["outer_area"] = (1 + errs["paper"]) * section_factor(paper) - 1
    return errs


def change(errs: list[dict[str, float]], rung: str) -> float:
    """The mean move of ``rung`` from the papers' set-up, over the rows that have it."""
    return float(np.mean([e[rung] - e["paper"] for e in errs if rung in e]))


def doc_ladder(data: dict, ctx: DocContext) -> list[str]:
    L = ["## Like for like: the papers' set-up, then one choice at a time", "",
         "Strength errors against the formulas.  'Papers' set-up': the stepwise schedule "
         "(the papers' platen steps and relaxation), the papers' damping, smooth platens, "
         "stress over the centres' span.  Each further column changes one choice alone: the "
         "outer cross-section as the stress area (same run), constant loading at the papers' "
         "damping, less damping under the stepwise schedule, platen springs of the bonds' "
         "stiffness Kn instead of 2 Kn, or the end layers held as in tension instead of "
         "platens (compression); the last column is "
         "everything ours, the package's defaults."]
    cols = ["paper", "outer_area", "constant", "damping_0.25", "damping_0.1", "platens_1",
            "layers", "defaults"]
    labels = {"outer_area": "outer area", **{k: RUNGS[k][0] for k in RUNGS}}
    for dim in ("2", "3"):
        rows = data[dim]
        present = [c for c in cols if c == "outer_area" or any(c in r["rungs"] for r in rows)]
        size = "N" if dim == "2" else "n_y"
        L += ["", f"### {dim}D", "",
              f"| {size} | particles | strength | " + " | ".join(labels[c] for c in present)
              + " | time steps, stepwise / constant |",
              "|" + "---|" * (len(present) + 4)]
        for row in rows:
            errs = rung_errors(row)
            r = row["rungs"]
            ratio = r["paper"]["plan"]["steps"] / r["constant"]["plan"]["steps"]
            L.append(f"| {row['n']} | {r['paper']['particles']} | {TESTS[row['test']]} | "
                     + " | ".join(pct(errs.get(c)) for c in present) + f" | {ratio:.0f} |")
        L += ["", _moves(dim, rows, present, labels)]
    _ladder_png(ctx, data)
    L += ["", "![strength under the papers' set-up and one change at a time](img/like_for_like.png)"]
    return L


def _moves(dim: str, rows: list[dict], present: list[str], labels: dict[str, str]) -> str:
    """What each change moves, averaged over the ladder's multi-unit sizes, per strength."""
    parts = []
    for key in ("Tu", "Cu"):
        sel = [rung_errors(r) for r in rows if TESTS[r["test"]] == key and r["n"] > 2]
        if not sel:
            continue
        base = float(np.mean([e["paper"] for e in sel]))
        moves = ", ".join(f"{labels[c]} {100 * change(sel, c):+.2f}"
                          for c in present if c != "paper" and any(c in e for e in sel))
        parts.append(f"{key}: papers' set-up {pct(base)} on average over these multi-unit "
                     f"sizes (the paper's mean over its sizes {paper_pct(f'{dim}d.multi.{key}')}); "
                     f"each change moves it by (percentage points) {moves}")
    return ".  ".join(parts) + "."


def _ladder_png(ctx: DocContext, data: dict) -> None:
    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5), squeeze=False)
    for i, dim in enumerate(("2", "3")):
        for j, test in enumerate(TESTS):
            ax = axes[i][j]
            rows = [r for r in data[dim] if r["test"] == test]
            particles = [r["rungs"]["paper"]["particles"] for r in rows]
            errs = [rung_errors(r) for r in rows]
            for c in ("paper", "outer_area", "constant", "damping_0.25", "damping_0.1",
                      "platens_1", "layers", "defaults"):
                pts = [(p, 100 * e[c]) for p, e in zip(particles, errs) if c in e]
                if pts:
                    ax.semilogx(*zip(*pts), "o-", ms=4, label=c.replace("_", " "))
            ax.axhline(0, color="k", lw=0.8)
            ax.set_title(f"{dim}D {TESTS[test]}", fontsize=10)
            ax.set_xlabel("particles" if dim == "2" else "elements")
            ax.set_ylabel("error against the formula (%)")
            ax.legend(fontsize=7)
    save_png(fig, ctx.img / "like_for_like.png", dpi=110)


LADDER = Section("like_for_like", run_ladder, doc_ladder, slow=True)
