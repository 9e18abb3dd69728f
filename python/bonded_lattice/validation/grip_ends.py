"""Two more grips of the 2D tension blocks the 2013 paper's words allow (its lattice "bonded by
two smooth planes", para. 42, pulled apart; it does not say how the planes hold the lattice):

- ``traction``: force-controlled ends, every particle of each end layer pulled by the same
  axial force, ramped at a constant rate (a uniform traction, free sideways;
  :func:`bonded_lattice.deck.grips.traction_grips`).  The rate is the rock's E times the held
  end layers' strain rate, so that the traction reaches Tu after as many wave crossings as
  the displacement loading.  Under a force ramp the block's strength is the traction at the
  last moment of equilibrium: the deck's stress is the traction while the end layers separate
  at most :data:`~bonded_lattice.deck.grips.RUNAWAY` times the quasi-static rate and 0 from
  the thermo row where they run away, so that its peak (Tu as for the other grips, total force
  over the centres' span) is the traction at the last row of equilibrium and the failure halt
  stops the run there;
- ``wide``: held as the default grips, but the two outermost rows at each end.

Part of section 'grips' (:mod:`.grips`): rows of N, the held end layers' Tu (the series' runs)
beside these two, and where the traction grips' first bonds broke (from ``dump.final``).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..deck.grips import RUNAWAY, TRACTION_LOG
from ..io.ave_time import read_ave_time
from ..io.dump import read_atom_dump
from .doc import paper_pct, pct
from .papers import paper_value
from .runner import Validation, rock_for

__all__ = ["END_GRIPS", "END_SIZES", "broken_at_ends", "end_force", "end_grip_lines",
           "end_grip_means",
           "run_end_grips"]

# 2D sizes N (particles across): 18 to 4106 particles
END_SIZES = [4, 8, 15, 30, 60]
END_GRIPS = ("traction", "wide")


def broken_at_ends(folder: Path, rows: float = 1.5) -> dict[str, int]:
    """Particles of ``folder/dump.final`` with a broken bond: all of them, and those whose
    initial centres (``dump.initial``) lie within ``rows`` close-packed row spacings
    (sqrt(3)/2 d, d from the data's x spacing) of either end of the block; and the particles
    of the top end layer (centres within 0.6 d of the top, as the grips take them); and the
    broken ones at the ends within 3 d of a side face (the end layers' corners)."""
    names, final = read_atom_dump(folder / "dump.final")
    _, initial = read_atom_dump(folder / "dump.initial")
    col = {n: i for i, n in enumerate(names)}
    order0, order = np.argsort(initial[:, col["id"]]), np.argsort(final[:, col["id"]])
    y0 = initial[order0, col["y"]]
    broken = (final[order, col["c_ntension"]] + final[order, col["c_nshear"]]) > 0
    x0 = np.unique(np.round(initial[:, col["x"]], 12))
    d = float(np.min(np.diff(x0))) * 2.0      # rows alternate, offset by d / 2
    band = rows * math.sqrt(3.0) / 2.0 * d
    ends = (y0 <= y0.min() + band) | (y0 >= y0.max() - band)
    x = initial[order0, col["x"]]
    sides = (x <= x.min() + 3.0 * d) | (x >= x.max() - 3.0 * d)
    return {"broken_particles": int(broken.sum()), "broken_at_ends": int((broken & ends).sum()),
            "broken_at_corners": int((broken & ends & sides).sum()),
            "end_particles": int((y0 >= y0.max() - 0.6 * d).sum())}


def _peak_runaway(folder: Path) -> float:
    """The largest separation rate of the end layers over the quasi-static one in a traction
    run's log (:data:`~bonded_lattice.deck.grips.TRACTION_LOG`)."""
    log = read_ave_time(folder / TRACTION_LOG)
    return float(np.max(log["v_runaway"]))


def _steady_runaway(folder: Path) -> float:
    """The largest deviation of the separation rate from the quasi-static one over the rows
    between a tenth and nine tenths of the run before the halt (the block in equilibrium)."""
    rate = read_ave_time(folder / TRACTION_LOG)["v_runaway"]
    k = len(rate)
    return float(np.max(np.abs(rate[k // 10: 9 * k // 10] - 1.0)))


def run_end_grips(v: Validation) -> list[dict]:
    """Per size of :data:`END_SIZES`: the held end layers' run (the series' folder) and the
    traction and wide grips' runs (constant loading at the papers' damping)."""
    rock, rows = rock_for(2), []
    for n in END_SIZES:
        row = {"n": n, "held": v.run(f"2d/n{n}_tension", rock, 2, "tension", n)}
        for key in END_GRIPS:
            name = f"2d/grips_n{n}_{key}"
            row[key] = v.run(name, rock, 2, "tension", n, grips=key)
        folder = v.folder(f"2d/grips_n{n}_traction")
        row["traction_failure"] = {**broken_at_ends(folder),
                                   "peak_runaway": _peak_runaway(folder),
                                   "steady_deviation": _steady_runaway(folder)}
        row["held_failure"] = broken_at_ends(v.folder(f"2d/n{n}_tension"))
        rows.append(row)
    return rows


def _tu(row: dict, key: str) -> float:
    return row[key]["relative_error"]["Tu"]


def end_force(row: dict) -> float:
    """The traction grips' force per end-layer particle at the failure, over the rock's Tu
    times d: the measured Tu times the loaded width over the end layer's particles."""
    run = row["traction"]
    return ((1.0 + run["relative_error"]["Tu"]) * run["plan"]["area"]
            / (row["traction_failure"]["end_particles"] * run["plan"]["d"]))


def end_grip_means(rows: list[dict]) -> dict[str, float]:
    """Mean Tu error over the rows' sizes, per grip (held, traction, wide)."""
    return {k: float(np.mean([_tu(r, k) for r in rows])) for k in ("held",) + END_GRIPS}


def _trend(rows: list[dict], key: str) -> float:
    """Slope of the Tu error against log10 N (points per decade; negative: the deficit grows
    with N)."""
    ns = np.log10([r["n"] for r in rows])
    return float(np.polyfit(ns, [100 * _tu(r, key) for r in rows], 1)[0])


def end_grip_lines(rows: list[dict]) -> list[str]:
    """The subsection on the traction and wide grips (Markdown lines)."""
    keys = ("held",) + END_GRIPS
    names = {"held": "held end layers", "traction": "uniform traction",
             "wide": "two rows held"}
    n30 = round(paper_value("2d.n30.particles"))
    L = ["", "### Force-controlled and wider grips (2D)", "",
         "Two more readings of the paper's 'lattice bonded by two smooth planes': a uniform "
         "traction (every particle of each end layer pulled by the same axial force, ramped at "
         "the rock's E times the held end layers' strain rate, so that it reaches Tu after as "
         "many wave crossings; free sideways), and the two outermost rows at each end held (as "
         "the held end layers hold one).  Under a force ramp the strength is the traction at "
         "the last moment of equilibrium: the block starts at the quasi-static strain rate and "
         "its end layers separate at that rate until it fails; the traction's Tu is the "
         "traction at the last thermo row before they separate "
         f"{RUNAWAY:g} times as fast (the run stops there; the stress is the total force over "
         "the centres' span, as for the other grips).", "",
         "| N | particles | " + " | ".join(names[k] for k in keys) + " | paper |",
         "|---|---|" + "---|" * (len(keys) + 1)]
    for r in rows:
        paper = paper_pct("2d.n30.Tu") if r["held"]["particles"] == n30 else ""
        L.append(f"| {r['n']} | {r['held']['particles']} | "
                 + " | ".join(pct(_tu(r, k)) for k in keys) + f" | {paper} |")
    means = end_grip_means(rows)
    L.append(f"| mean | | " + " | ".join(pct(means[k]) for k in keys)
             + f" | {paper_pct('2d.multi.Tu')} (multi-unit mean) |")
    slopes = {k: _trend(rows, k) for k in keys}
    paper_falls = paper_value("2d.n30.Tu") > paper_value("2d.multi.Tu")
    sizes = f"N = {rows[0]['n']} to {rows[-1]['n']}"
    L += ["", f"Trend with size ({sizes}, the Tu error's least-squares slope against log10 N, "
          "points per decade; positive: the deficit falls as the block grows): "
          + ", ".join(f"{names[k]} {slopes[k]:+.2f}" for k in keys)
          + ".  The paper's deficit at " + f"{n30} particles ({paper_pct('2d.n30.Tu')}) is "
          + ("smaller" if paper_falls else "larger")
          + f" than its multi-unit mean ({paper_pct('2d.multi.Tu')}): it "
          + ("falls" if paper_falls else "grows") + " with size; "
          + (", ".join(names[k] for k in keys if (slopes[k] > 0) == paper_falls) or "none")
          + " of ours " + ("does" if sum((slopes[k] > 0) == paper_falls for k in keys) == 1
                           else "do") + " the same."]
    fail = [r["traction_failure"] for r in rows]
    all_ends = all(f["broken_particles"] == f["broken_at_corners"] for f in fail)
    forces = [end_force(r) for r in rows]
    same = (max(forces) - min(forces)) < 0.05 * float(np.mean(forces))
    L += ["", "Where the traction grips' blocks fail: particles with a broken bond when the "
          "run stopped (all / within one and a half rows of an end / of those, within 3 d of "
          "a side face) "
          + ", ".join(f"N = {r['n']}: {f['broken_particles']} / {f['broken_at_ends']} / "
                      f"{f['broken_at_corners']}" for r, f in zip(rows, fail))
          + "; the held end layers' blocks at their halt "
          + ", ".join(f"{r['held_failure']['broken_particles']} / "
                      f"{r['held_failure']['broken_at_ends']} / "
                      f"{r['held_failure']['broken_at_corners']}" for r in rows) + ".  "
          + ("Every broken bond of the traction runs lies at the end layers' corners: the "
             "uniform traction pulls the outermost particles of the end rows, held by the "
             "fewest bonds, as hard as the others, and their bonds break first; the runaway is "
             "these particles coming loose, not a crack through the block." if all_ends else
             "Not every broken bond of the traction runs lies at the end layers' corners.")
          + "  The force each end particle carries at the failure (Tu times the loaded width "
          "over the end layer's particles) is " + ", ".join(f"{x:.3f}" for x in forces)
          + " times the rock's Tu times d (N as above)"
          + (": nearly the same at every size (within 5%), so that the traction's Tu follows "
             "the end layer's particles per loaded width, (N - 1) d / N, and its deficit grows "
             "with N." if same else ".")
          + f"  Before the failure the end layers' separation rate stays within "
          f"{100 * max(f['steady_deviation'] for f in fail):.1f}% of the quasi-static one "
          f"(rows between a tenth and nine tenths of each run); at the halt it is "
          f"{min(f['peak_runaway'] for f in fail):.3g} to {max(f['peak_runaway'] for f in fail):.3g} "
          "times that rate."]
    return L
