"""How slow constant loading must be in 3D compression: Cu against the number of elastic-wave
crossings to failure, at the papers' damping and at a quarter of it, next to the papers'
stepwise schedule (issue 19: the 3D constant schedule was tuned in 2D only).

The stepwise schedule reads the platen force after each relaxation, with the block at rest;
constant loading reads it while the block moves, and comes to the same Cu only once the loading
is slow enough (measured here, not assumed).
"""

from __future__ import annotations

from ..plotting import pyplot, save_png
from ..schedules import default_loading
from .doc import DocContext, pct
from .runner import Validation, rock_for
from .section import Section

__all__ = ["LOADING_3D"]

SIZES = [4, 6, 10]
CROSSINGS = [100.0, 300.0, 1000.0, 3000.0]
DAMPINGS = [1.0, 0.25]
# a constant loading within this of the stepwise Cu (points of the formula's Cu) is called
# quasi-static: the sampling of the peak and the scatter between nearly equal runs are of
# this order (docs/speed_error.md, the strengths' tolerance 0.5%)
QUASI_STATIC = 0.005


def _folder(n: int, crossings: float, damping: float) -> str:
    return f"3d/rate_n{n}_compression_c{crossings:g}_d{damping:g}"


def run_loading(v: Validation) -> dict:
    rock, rows = rock_for(3), []
    for n in SIZES:
        row = {"n": n, "stepwise": v.run(f"3d/paper_n{n}_compression", rock, 3, "compression",
                                         n, schedule="stepwise"), "constant": []}
        for damping in DAMPINGS:
            for c in CROSSINGS:
                run = v.run(_folder(n, c, damping), rock, 3, "compression", n, crossings=c,
                            damping=damping)
                row["constant"].append({"crossings": c, "damping": damping, "run": run})
        rows.append(row)
    return {"rows": rows}


def doc_loading(data: dict, ctx: DocContext) -> list[str]:
    rows = data["rows"]
    head = "| n_y | elements | stepwise (papers') | " + " | ".join(
        f"{c:g} crossings, eta x {d:g}" for d in DAMPINGS for c in CROSSINGS) + " |"
    L = ["## 3D compression: how slow constant loading must be", "",
         "Cu errors of 3D blocks under constant loading at 100 to 3000 elastic-wave crossings to "
         "failure, at the papers' damping and at a quarter of it, next to the papers' stepwise "
         "schedule (papers' damping).", "", head, "|" + "---|" * (head.count("|") - 1)]
    for row in rows:
        cells = [str(row["n"]), str(row["stepwise"]["particles"]),
                 pct(row["stepwise"]["relative_error"]["Cu"])]
        by = {(r["damping"], r["crossings"]): r["run"] for r in row["constant"]}
        cells += [pct(by[d, c]["relative_error"]["Cu"]) for d in DAMPINGS for c in CROSSINGS]
        L.append("| " + " | ".join(cells) + " |")
    gaps = [(row["n"], {d: by_gap(row, d) for d in DAMPINGS}) for row in rows]
    L += ["", "Constant loading minus stepwise at the slowest loading (percentage points): " +
          "; ".join(f"n_y = {n}: " + ", ".join(f"eta x {d:g} {100 * g:+.2f}" for d, g in gs.items())
                    for n, gs in gaps) + "."]
    L += ["", default_text(rows)]
    _png(ctx, rows)
    L += ["", "![Cu against loading speed, 3D](img/loading_rate_3d.png)"]
    return L


def default_text(rows: list[dict]) -> str:
    """What these runs say about the package's 3D compression default."""
    default = default_loading(3, "compression")
    c0, f0 = default["crossings"], default["damping"]
    name = f"Our 3D compression default ({c0:g} crossings, eta x {f0:g}, docs/speed_error.md)"
    if c0 not in CROSSINGS or f0 not in DAMPINGS:
        return f"{name} is not one of these settings."
    off = {c: [_offset(row, c, f0) for row in rows] for c in CROSSINGS}
    worst = max(abs(x) for x in off[c0])
    text = (f"{name} reads Cu {_span(off[c0])} points off the stepwise schedule on these "
            "blocks" +
            (": at that speed the compression test is not yet quasi-static." if worst > QUASI_STATIC
             else f", within {100 * QUASI_STATIC:g} point of it: quasi-static."))
    slower = [c for c in CROSSINGS if c > c0]
    if slower:
        text += ("  At the same damping " + ", ".join(
            f"{c:g} crossings come within {100 * max(abs(x) for x in off[c]):.1f}"
            for c in slower) + " points.")
    faster = [c for c in CROSSINGS if c < c0]
    if faster:
        text += ("  Faster: " + ", ".join(f"{c:g} crossings {_span(off[c])}" for c in faster) +
                 " points.")
    return text + ("  A quarter of the damping converges, as the loading slows, to a different "
                   "strength on the larger blocks: the damping takes part in how the block "
                   "fails, so the papers' eta belongs to the papers' set-up.")


def _span(values: list[float]) -> str:
    """The range of offsets in points, one number when it rounds to one."""
    lo, hi = f"{100 * min(values):+.1f}", f"{100 * max(values):+.1f}"
    return lo if lo == hi else f"{lo} to {hi}"


def _offset(row: dict, crossings: float, damping: float) -> float:
    """Cu error at ``crossings`` and ``damping`` minus the stepwise one."""
    run = next(r["run"] for r in row["constant"]
               if r["crossings"] == crossings and r["damping"] == damping)
    return run["relative_error"]["Cu"] - row["stepwise"]["relative_error"]["Cu"]


def by_gap(row: dict, damping: float) -> float:
    """Cu error at the slowest constant loading of ``damping`` minus the stepwise one."""
    return _offset(row, max(CROSSINGS), damping)


def _png(ctx: DocContext, rows: list[dict]) -> None:
    plt = pyplot()
    fig, axes = plt.subplots(1, len(rows), figsize=(3.6 * len(rows), 3.4), squeeze=False)
    for ax, row in zip(axes[0], rows):
        for damping, style in zip(DAMPINGS, ("o-", "s--")):
            pts = sorted((r["crossings"], 100 * r["run"]["relative_error"]["Cu"])
                         for r in row["constant"] if r["damping"] == damping)
            ax.semilogx(*zip(*pts), style, label=f"constant, eta x {damping:g}")
        ax.axhline(100 * row["stepwise"]["relative_error"]["Cu"], color="r", ls=":",
                   label="stepwise (papers')")
        ax.set_title(f"n_y = {row['n']} ({row['stepwise']['particles']} elements)", fontsize=9)
        ax.set_xlabel("wave crossings to failure")
        ax.set_ylabel("Cu error (%)")
        ax.legend(fontsize=7)
    save_png(fig, ctx.img / "loading_rate_3d.png", dpi=110)


LOADING_3D = Section("loading_3d", run_loading, doc_loading, slow=True)
