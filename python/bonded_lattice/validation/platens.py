"""What the platens do to a block's compressive strength: Cu against the stiffness of the
platens' springs, and with no platens at all (the end layers held and moved, as in tension).

A block of many units is weaker than its unit in compression (Liu 2013 para. 51, Liu 2017
section 5.2: "boundary effects").  The papers' platens are smooth planes whose contact
stiffness they do not state; ours are springs of 2 Kn (:class:`~bonded_lattice.decks.DeckSpec`
``wall_kn``).  This sweep measures how much of the deficit the platens' stiffness decides.
"""

from __future__ import annotations

import numpy as np

from ..plotting import pyplot, save_png
from .doc import DocContext, paper_pct, pct
from .papers import paper_value
from .runner import Validation, rock_for
from .section import Section

__all__ = ["PLATENS", "STIFFNESSES"]

STIFFNESSES = [1.0, 2.0, 5.0, 10.0]       # multiples of Kn
SIZES = {2: [8, 15, 30], 3: [6, 12]}
# constant loading slow enough to be converged in Cu within a few tenths of a point
# (2D: the series' 100 crossings; 3D: section loading_3d shows 100 crossings read Cu high)
CROSSINGS = {2: 100.0, 3: 1000.0}
# the largest 3D block whose Cu is also run with platens of Kn (the series' slow limit)
KN_MAX_3D = 20


def run_platens(v: Validation) -> dict:
    data = {}
    for dim in (2, 3):
        rock, rows = rock_for(dim), []
        for n in SIZES[dim]:
            runs = {f"{k:g}": v.run(f"{dim}d/platens_n{n}_k{k:g}_c{CROSSINGS[dim]:g}", rock, dim,
                                    "compression", n, crossings=CROSSINGS[dim],
                                    platen_stiffness=k)
                    for k in STIFFNESSES}
            runs["layers"] = v.run(f"{dim}d/platens_n{n}_layers_c{CROSSINGS[dim]:g}", rock, dim,
                                   "compression", n, crossings=CROSSINGS[dim], ends="layers")
            rows.append({"n": n, "runs": runs})
        data[str(dim)] = {"crossings": CROSSINGS[dim], "rows": rows,
                          "elastic": [{"n": n,
                                       "1": v.run(f"{dim}d/platens_n{n}_k1_elastic", rock, dim,
                                                  "elastic", n, platen_stiffness=1.0),
                                       "2": v.run(f"{dim}d/n{n}_elastic", rock, dim, "elastic",
                                                  n)}
                                      for n in v.sizes(dim)]}
        # Cu with platens of Kn at every size the 3D series runs slowly (2D: SIZES already
        # span the papers' sizes whose slow runs cost minutes)
        if dim == 3:
            data["3"]["kn_rows"] = [
                {"n": n, "run": v.run(f"3d/platens_n{n}_k1_c{CROSSINGS[3]:g}", rock, 3,
                                      "compression", n, crossings=CROSSINGS[3],
                                      platen_stiffness=1.0)}
                for n in v.sizes(3) if n <= KN_MAX_3D]
    return data


def elastic_mean(rows: list[dict], key: str, quantity: str = "E") -> float:
    """Mean magnitude of the elastic error of ``quantity`` over the multi-unit sizes of the
    platens section's elastic rows, with platens of ``key`` (``"1"`` or ``"2"``) Kn."""
    return float(np.mean([abs(r[key]["relative_error"][quantity]) for r in rows if r["n"] > 2]))


def doc_platens(data: dict, ctx: DocContext) -> list[str]:
    keys = [f"{k:g}" for k in STIFFNESSES] + ["layers"]
    head = ("| dim | size | particles | " + " | ".join(f"platens {k} Kn" for k in keys[:-1])
            + " | end layers held |")
    L = ["## The platens decide the compressive deficit", "",
         "Cu errors of blocks compressed by smooth platens whose springs have 1 to 10 times the "
         "bonds' stiffness Kn (ours: 2 Kn), and by the end layers held and moved as in tension "
         "(no platens); constant loading at the papers' damping (2D "
         f"{data['2']['crossings']:g}, 3D {data['3']['crossings']:g} wave crossings to failure).",
         "", head, "|" + "---|" * (head.count("|") - 1)]
    for dim in ("2", "3"):
        for row in data[dim]["rows"]:
            r = row["runs"]
            L.append(f"| {dim}D | {'N' if dim == '2' else 'n_y'} = {row['n']} | "
                     f"{r['layers']['particles']} | "
                     + " | ".join(pct(r[k]["relative_error"]["Cu"]) for k in keys) + " |")
    for dim in ("2", "3"):
        rows = data[dim]["rows"]
        at = {k: float(np.mean([r["runs"][k]["relative_error"]["Cu"] for r in rows]))
              for k in keys}
        L += ["", f"{dim}D, mean over these sizes: platens of Kn {pct(at['1'])}, of 2 Kn "
              f"{pct(at['2'])}, held end layers {pct(at['layers'])}; the paper's multi-unit "
              f"mean {paper_pct(f'{dim}d.multi.Cu')}."]
    _png(ctx, data, keys)
    L += ["", "![Cu against the platens' stiffness](img/platens.png)"]
    kn = data["3"].get("kn_rows")
    if kn:
        mean = float(np.mean([r["run"]["relative_error"]["Cu"] for r in kn]))
        L += ["", "3D Cu with platens of Kn at every size up to n_y = "
              f"{kn[-1]['n']}: " + ", ".join(f"n_y = {r['n']} {pct(r['run']['relative_error']['Cu'])}"
                                            for r in kn)
              + f"; mean {pct(mean)} (the paper's multi-unit mean "
              f"{paper_pct('3d.multi.Cu')})."]
    if all("elastic" in data[dim] for dim in ("2", "3")):
        L += _elastic_lines(data)
    return L


def _elastic_lines(data: dict) -> list[str]:
    """E and nu of the elastic test (strain -1e-4, constant loading at the papers' damping)
    with platens of Kn and of 2 Kn."""
    L = ["", "### The elastic test with platens of Kn", "",
         "E and nu (mid-height gauges) of the elastic test with platen springs of Kn and of "
         "2 Kn (ours; the series' runs).", "",
         "| dim | size | particles | E, Kn | E, 2 Kn | nu, Kn | nu, 2 Kn |",
         "|---|---|---|---|---|---|---|"]
    for dim in ("2", "3"):
        for r in data[dim]["elastic"]:
            L.append(f"| {dim}D | {'N' if dim == '2' else 'n_y'} = {r['n']} | "
                     f"{r['1']['particles']} | " + " | ".join(
                         pct(r[k]["relative_error"][q]) for q in ("E", "nu") for k in ("1", "2"))
                     + " |")
    for dim in ("2", "3"):
        rows = data[dim]["elastic"]
        L += ["", f"{dim}D, mean magnitude over the multi-unit sizes: E {100 * elastic_mean(rows, '1'):.2f}% "
              f"with platens of Kn, {100 * elastic_mean(rows, '2'):.2f}% with 2 Kn; nu "
              f"{100 * elastic_mean(rows, '1', 'nu'):.2f}% and {100 * elastic_mean(rows, '2', 'nu'):.2f}%."]
    return L


def _png(ctx: DocContext, data: dict, keys: list[str]) -> None:
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    for ax, dim in zip(axes, ("2", "3")):
        for row in data[dim]["rows"]:
            r = row["runs"]
            line, = ax.semilogx(STIFFNESSES, [100 * r[k]["relative_error"]["Cu"]
                                              for k in keys[:-1]], "o-",
                                label=f"{r['layers']['particles']} particles")
            ax.axhline(100 * r["layers"]["relative_error"]["Cu"], color=line.get_color(),
                       ls=":", lw=1)
        ax.axhline(100 * paper_value(f"{dim}d.multi.Cu"), color="r", ls="--", lw=1,
                   label="paper, multi-unit mean")
        ax.set_xlabel("platen spring stiffness / Kn (dotted: end layers held)")
        ax.set_ylabel("Cu error (%)")
        ax.set_title(f"{dim}D", fontsize=10)
        ax.legend(fontsize=7)
    save_png(fig, ctx.img / "platens.png", dpi=110)


PLATENS = Section("platens", run_platens, doc_platens)
