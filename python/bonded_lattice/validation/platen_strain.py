"""2D Young's modulus by the strain's definition (Liu 2013 para. 43, 45): the elastic test's
axial strain as the all-particle fit (ours, :mod:`bonded_lattice.analysis`), from the end
rows' displacement, and from the platens' travel over the block's height, for platens of 2 Kn
(ours) and of Kn (the stiffness that gives the paper's compressive deficit, section 'The
platens decide the compressive deficit').

The paper computes its strains "on the basis of the displacement of the particles" and finds
the 18-particle block's E "about 3% lower"; the platens' travel adds the platen springs'
compliance, which weighs most on the smallest block.  Every E is in the plane-strain convention
of the formulas (:func:`bonded_lattice.analysis.plane_strain_from_in_plane`), with the
Poisson's ratio of the mid-height gauges over the same axial strain.
"""

from __future__ import annotations

import json
from pathlib import Path

from ..analysis import ELASTIC_WINDOW, plane_strain_from_in_plane, poisson_ratio, youngs_modulus
from ..experiment import build_lattice, end_particles
from ..io import read_thermo
from ..io.dump import read_atom_dump
from .doc import DocContext, paper_pct, pct
from .papers import paper_value
from .runner import Validation, rock_for
from .section import Section

__all__ = ["DEFINITIONS", "PLATEN_STRAIN", "platen_moduli", "series_modulus"]

SIZES = [4, 8, 15, 30]
STIFFNESSES = [2.0, 1.0]   # the platens' springs, multiples of Kn (ours first)
# the strain definitions: key -> its description in the text
DEFINITIONS = {
    "fit": "all-particle fit (ours)",
    "end_rows": "end rows' displacement over the centres' span",
    "platens_faces": "platens' travel over the block's outer height",
    "platens_centres": "platens' travel over the centres' span",
}


def series_modulus(e2: float, height: float, area: float, contacts: int, kn: float) -> float:
    """In-plane modulus from the platens' travel over the centres' span ``height``: the block
    (``e2 x area / height``) in series with two platens of ``contacts`` springs of ``kn``."""
    return 1.0 / (1.0 / e2 + 2.0 * area / (contacts * kn * height))


def platen_moduli(folder: Path, speed: float, d: float, area: float, contacts: int,
                  kn: float) -> dict[str, float]:
    """E (Pa, plane strain) of the 2D elastic run in ``folder`` per strain definition
    (:data:`DEFINITIONS`), and ``series``: :func:`series_modulus` of the all-particle fit
    (the platens' travel over the centres' span the series springs predict).

    The platens move in at ``speed`` each from touching the end rows (travel: the deck's
    ``Time`` column x speed); the end rows' strain comes from ``dump.initial`` and
    ``dump.final`` (the last thermo row) and scales the fit's slope; each definition's
    Poisson's ratio is the gauges' lateral strain over its axial strain.
    """
    t = read_thermo(folder / "log.lammps")[-1]
    names, x0 = read_atom_dump(folder / "dump.initial")
    _, x1 = read_atom_dump(folder / "dump.final")
    y0, y1 = x0[:, names.index("y")], x1[:, names.index("y")]
    height = float(y0.max() - y0.min())
    top, bottom = y0 >= y0.max() - 0.1 * d, y0 <= y0.min() + 0.1 * d
    end_strain = float(((y1 - y0)[top].mean() - (y1 - y0)[bottom].mean()) / height)
    stress, fit = t["v_stress"], t["v_strain"]
    e2 = youngs_modulus(fit, stress, ELASTIC_WINDOW)
    nu2 = poisson_ratio(fit, t["v_gauge"], stress, ELASTIC_WINDOW)
    out = {"fit": plane_strain_from_in_plane(e2, nu2)[0]}
    ratio = float(fit[-1]) / end_strain       # fit strain / end-row strain
    out["end_rows"] = plane_strain_from_in_plane(e2 * ratio, nu2 * ratio)[0]
    travel = -2.0 * speed * t["Time"]
    for key, length in (("platens_centres", height), ("platens_faces", height + d)):
        e2_travel = youngs_modulus(travel / length, stress, ELASTIC_WINDOW)
        out[key] = plane_strain_from_in_plane(e2_travel, nu2 * e2_travel / e2)[0]
    e2_series = series_modulus(e2, height, area, contacts, kn)
    out["series"] = plane_strain_from_in_plane(e2_series, nu2 * e2_series / e2)[0]
    return out


def run_platen_strain(v: Validation) -> dict:
    rock, rows = rock_for(2), []
    for n in SIZES:
        row: dict = {"n": n, "by_platens": {}}
        for k in STIFFNESSES:
            name = f"2d/n{n}_elastic" if k == 2.0 else f"2d/platen_strain_n{n}_k{k:g}"
            run = v.run(name, rock, 2, "elastic", n, platen_stiffness=k)
            lattice = build_lattice(2, n, run["plan"]["d"])
            kn = k * json.loads((v.folder(name) / "summary.json").read_text())["bond"]["Kn"]
            moduli = platen_moduli(v.folder(name), run["plan"]["speed"], run["plan"]["d"],
                                   run["plan"]["area"], end_particles(lattice), kn)
            row["particles"] = run["particles"]
            row["by_platens"][f"{k:g}"] = {"E": {key: e / rock.E - 1 for key, e in
                                                 moduli.items()},
                                           "measured_E": run["relative_error"]["E"]}
        rows.append(row)
    return {"2": rows, "stiffnesses": STIFFNESSES}


def doc_platen_strain(data: dict, ctx: DocContext) -> list[str]:
    ks = [f"{k:g}" for k in data["stiffnesses"]]
    head = ("| N | particles | " + " | ".join(
        f"{DEFINITIONS[key]}{'' if key in ('fit', 'end_rows') else f', platens {k} Kn'}"
        for k in ks for key in DEFINITIONS if k == ks[0] or key.startswith("platens"))
        + f" | series springs, platens {ks[0]} Kn |")
    L = ["## 2D E by the strain's definition", "",
         "E errors of the elastic test (compression to a strain of 1e-4 between smooth platens, "
         "constant loading at the papers' damping) with the axial strain taken four ways: the "
         "least-squares fit of all particles' displacements (ours), the end rows' mean "
         "displacement, and the platens' travel over the block's outer height (centres' span "
         "plus one diameter) or over the centres' span.  The platens' travel includes their "
         "springs' compliance; the last column is the block's fitted modulus in series with "
         "the two platens' springs, each end's contacts in parallel.  The paper reads its "
         "strains from the particles' displacement (Liu 2013 para. 43) and finds the "
         f"18-particle block's E about {paper_pct('2d.n4.E', 0)}, the largest error of its "
         "sizes (para. 45).", "", head,
         "|" + "---|" * (head.count("|") - 1)]
    for r in data["2"]:
        cells = [str(r["n"]), str(r["particles"])]
        for k in ks:
            e = r["by_platens"][k]["E"]
            cells += [pct(e[key]) for key in DEFINITIONS
                      if k == ks[0] or key.startswith("platens")]
        cells.append(pct(r["by_platens"][ks[0]]["E"]["series"]))
        L.append("| " + " | ".join(cells) + " |")
    n4 = next((r for r in data["2"] if r["n"] == 4), None)
    if n4 is not None:
        k, key, err = _closest(n4, paper_value("2d.n4.E"), ks[0])
        worst = max(data["2"], key=lambda r: abs(r["by_platens"][k]["E"][key]))
        L += ["", f"18 particles: the definition closest to the paper's about "
              f"{paper_pct('2d.n4.E', 0)} is the {DEFINITIONS[key]} with platens of {k} Kn, "
              f"{pct(err)}; by that definition the largest error is at N = {worst['n']} "
              f"({pct(worst['by_platens'][k]['E'][key])})"
              + (", as in the paper." if worst["n"] == n4["n"] else
                 ", while the paper's is at 18 particles.")
              + "  The series springs reproduce the platens' travel over the centres' span "
              f"within {100 * max(abs(r['by_platens'][ks[0]]['E']['series'] - r['by_platens'][ks[0]]['E']['platens_centres']) for r in data['2']):.1f} points."]
    return L


def _closest(row: dict, paper: float, first: str) -> tuple[str, str, float]:
    """(platen stiffness, definition, E error) of ``row`` closest to ``paper``; the
    particles' strains of the runs with platens ``first`` only (the table's)."""
    cands = [(k, key, e) for k, by in row["by_platens"].items()
             for key, e in by["E"].items()
             if key.startswith("platens") or (key in DEFINITIONS and k == first)]
    return min(cands, key=lambda c: abs(c[2] - paper))


PLATEN_STRAIN = Section("platen_strain", run_platen_strain, doc_platen_strain)
