"""Where a block's tensile deficit comes from: Tu of the tension test (the end layers held
and pulled apart) against Tu of a periodic cell in uniaxial tension (``test="periodic"``: no
ends, no free faces, the lateral faces at zero stress), at the papers' sizes; and Tu under
other grips of the end layers (:data:`bonded_lattice.decks.GRIPS`): clamped (lateral motion
fixed too) and tied by axial springs of 1 to 20 Kn to moving smooth planes.

The papers do not say how they pulled their blocks; the 2013 paper's lattice is "bonded by two
smooth planes" (para. 42).  The periodic cell is the limit of grips that do not concentrate
stress, the held end layers that of infinitely stiff smooth grips; the spring grips are the
compliant planes the platens' analogue in compression would be (section 'The platens decide
the compressive deficit': platens of Kn give the paper's Cu deficit).  In 2D also a uniform
traction on the end layers and the two outermost rows held (:mod:`.grip_ends`, data key
``ends``).
"""

from __future__ import annotations

import numpy as np

from ..plotting import pyplot, save_png
from .doc import DocContext, paper_pct, pct
from .grip_ends import end_grip_lines, run_end_grips
from .papers import paper_value
from .runner import Validation, rock_for
from .section import Section

__all__ = ["GRIPS", "GRIP_VARIANTS", "closest_grips", "grip_label"]

SIZES = {2: [8, 15, 30], 3: [6, 12]}
# the end layers' grips besides the held ones (RockTest options): clamped, and springs of
# these multiples of Kn (20 Kn: the stiffest the time step allows, MAX_PLATEN_STIFFNESS)
SPRING_STIFFNESSES = [1.0, 2.0, 5.0, 20.0]
GRIP_VARIANTS: dict[str, dict] = {
    "clamped": {"grips": "clamped"},
    **{f"springs_{k:g}": {"grips": "springs", "platen_stiffness": k}
       for k in SPRING_STIFFNESSES},
}


def grip_label(key: str) -> str:
    """A variant's name in the text: 'held end layers', 'clamped end layers', 'spring grips
    of 2 Kn'."""
    if key.startswith("springs_"):
        return f"spring grips of {key.split('_', 1)[1]} Kn"
    return f"{key} end layers"


def run_grips(v: Validation) -> dict:
    data = {}
    for dim in (2, 3):
        rock, rows = rock_for(dim), []
        for n in SIZES[dim]:
            rows.append({"n": n,
                         "periodic": v.run(f"{dim}d/grips_n{n}_periodic", rock, dim, "periodic",
                                           n),
                         "held": v.run(f"{dim}d/n{n}_tension", rock, dim, "tension", n),
                         "variants": {key: v.run(f"{dim}d/grips_n{n}_{key}", rock, dim,
                                                 "tension", n, **options)
                                      for key, options in GRIP_VARIANTS.items()}})
        data[str(dim)] = rows
    data["ends"] = run_end_grips(v)
    return data


def _tu(row: dict, key: str) -> float:
    run = row["held"] if key == "held" else row["variants"][key]
    return run["relative_error"]["Tu"]


def grip_means(rows: list[dict]) -> dict[str, float]:
    """Mean Tu error over the sizes per grip ('held' and every variant the rows hold)."""
    keys = ["held"] + [k for k in GRIP_VARIANTS if all(k in r.get("variants", {}) for r in rows)]
    return {k: float(np.mean([_tu(r, k) for r in rows])) for k in keys}


def closest_grips(rows: list[dict], paper: float, n: int | None = None) -> tuple[str, float]:
    """The grip (key of :func:`grip_means`, or 'held') whose Tu error comes closest to the
    paper's ``paper``: the mean over the sizes, or at size ``n``; with that error."""
    if n is None:
        errors = grip_means(rows)
    else:
        row = next(r for r in rows if r["n"] == n)
        errors = {k: _tu(row, k) for k in ["held"] + list(row.get("variants", {}))}
    key = min(errors, key=lambda k: abs(errors[k] - paper))
    return key, errors[key]


def doc_grips(data: dict, ctx: DocContext) -> list[str]:
    L = ["## Where the tensile deficit comes from: grips and free faces", "",
         "Tu of the tension test (the end layers held and pulled apart, constant loading at the "
         "papers' damping) against Tu of a periodic cell pulled uniaxially with its lateral "
         "faces at zero stress: no ends and no free faces, so no grip and no boundary layer.  "
         "The section 'Anisotropy' locates the tension blocks' damage next to the held ends.",
         "",
         "| dim | size | particles, block / cell | held end layers | periodic cell |",
         "|---|---|---|---|---|"]
    for dim in ("2", "3"):
        for r in data[dim]:
            L.append(f"| {dim}D | {'N' if dim == '2' else 'n_y'} = {r['n']} | "
                     f"{r['held']['particles']} / {r['periodic']['particles']} | "
                     f"{pct(r['held']['relative_error']['Tu'])} | "
                     f"{pct(r['periodic']['relative_error']['Tu'])} |")
    for dim in ("2", "3"):
        held = float(np.mean([r["held"]["relative_error"]["Tu"] for r in data[dim]]))
        cell = float(np.mean([r["periodic"]["relative_error"]["Tu"] for r in data[dim]]))
        L += ["", f"{dim}D, mean over these sizes: held end layers {pct(held)}, periodic cell "
              f"{pct(cell)}; the paper's multi-unit mean {paper_pct(f'{dim}d.multi.Tu')}."]
    if all("variants" in r for dim in ("2", "3") for r in data[dim]):
        L += _variant_lines(data, ctx)
    if "ends" in data:
        L += end_grip_lines(data["ends"])
    return L


def _variant_lines(data: dict, ctx: DocContext) -> list[str]:
    keys = ["held"] + list(GRIP_VARIANTS)
    head = "| dim | size | " + " | ".join(grip_label(k) for k in keys) + " | paper |"
    L = ["", "### Other grips", "",
         "Tu errors of the same blocks pulled through other grips: the end layers clamped (their "
         "lateral motion fixed as well), or tied by an axial spring per particle to two smooth "
         "planes moving apart (free sideways: the 2013 paper's lattice 'bonded by two smooth "
         "planes', with a finite stiffness like its platens'; springs of "
         + ", ".join(f"{k:g}" for k in SPRING_STIFFNESSES) + " Kn).  The stress is the force "
         "the grips apply; the same loading as above.", "", head,
         "|" + "---|" * (head.count("|") - 1)]
    for dim in ("2", "3"):
        for r in data[dim]:
            paper = (paper_pct("2d.n30.Tu") if dim == "2" and r["held"]["particles"]
                     == round(paper_value("2d.n30.particles")) else "")
            L.append(f"| {dim}D | {'N' if dim == '2' else 'n_y'} = {r['n']} | "
                     + " | ".join(pct(_tu(r, k)) for k in keys) + f" | {paper} |")
        means = grip_means(data[dim])
        L.append(f"| {dim}D | mean | " + " | ".join(pct(means[k]) for k in keys)
                 + f" | {paper_pct(f'{dim}d.multi.Tu')} (multi-unit mean) |")
    for dim in ("2", "3"):
        means = grip_means(data[dim])
        paper = paper_value(f"{dim}d.multi.Tu")
        key, err = closest_grips(data[dim], paper)
        springs = [means[f"springs_{k:g}"] for k in SPRING_STIFFNESSES]
        # softer grips weaken the block if Tu rises with the springs' stiffness up to the held
        # (infinitely stiff) end layers
        chain = springs + [means["held"]]
        soft = all(a < b for a, b in zip(chain, chain[1:]))
        L += ["", f"{dim}D: over these sizes the grips closest to the paper's mean "
              f"({pct(paper)}, over all its multi-unit sizes) are the {grip_label(key)}, "
              f"{pct(err)} ({100 * (err - paper):+.1f} points).  "
              + (f"Softer grips weaken the block: springs of {SPRING_STIFFNESSES[0]:g} Kn give "
                 f"{pct(springs[0])}, of {SPRING_STIFFNESSES[-1]:g} Kn {pct(springs[-1])}, held "
                 f"end layers (infinitely stiff) {pct(means['held'])}; clamping gives "
                 f"{pct(means['clamped'])}." if soft else
                 f"Springs of {SPRING_STIFFNESSES[0]:g} Kn give {pct(springs[0])}, clamping "
                 f"{pct(means['clamped'])}.")]
    _png(ctx, data)
    L += ["", "![Tu against the grips' stiffness](img/grips.png)"]
    return L


def _png(ctx: DocContext, data: dict) -> None:
    """Tu error against the grip springs' stiffness per size (dotted: the held end layers;
    square: clamped), with the paper's values, 2D and 3D side by side."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    papers = {"2": [("2d.multi.Tu", "--", "paper, multi-unit mean"),
                    ("2d.n30.Tu", "-.", "paper, 1033 particles")],
              "3": [("3d.multi.Tu", "--", "paper, multi-unit mean")]}
    for ax, dim in zip(axes, ("2", "3")):
        for r in data[dim]:
            ys = [100 * _tu(r, f"springs_{k:g}") for k in SPRING_STIFFNESSES]
            line, = ax.semilogx(SPRING_STIFFNESSES, ys, "o-",
                                label=f"{r['held']['particles']} particles")
            colour = line.get_color()
            ax.axhline(100 * _tu(r, "held"), color=colour, ls=":", lw=1)
            ax.plot([2 * SPRING_STIFFNESSES[-1]], [100 * _tu(r, "clamped")], "s", color=colour)
        for key, style, label in papers[dim]:
            ax.axhline(100 * paper_value(key), color="r", ls=style, lw=1, label=label)
        ax.set(xlabel="grip spring stiffness / Kn (dotted: held; square: clamped)",
               ylabel="Tu error (%)")
        ax.set_title(f"{dim}D", fontsize=10)
        ax.legend(fontsize=7)
    save_png(fig, ctx.img / "grips.png", dpi=110)


GRIPS = Section("grips", run_grips, doc_grips)
