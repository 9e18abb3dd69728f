"""The stress-strain curve of a compressive strength test with its features found from the run
(:mod:`.curve_features`): the 1033-particle 2D block (Liu 2013, para. 49, 51 and Fig. 7a) and
the 2166-element 3D block (Liu 2017, section 5.2 and Fig. 5).

Each section makes its own run with dense thermo output (a row every few time steps, so that
drops lasting a wave crossing have tens of rows) that goes on until the stress has fallen to
a twentieth of its peak, and, in 2D, reads the series' run of the same block (thermo about
1500 rows over the planned run) to show what the coarser rows resolve.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..conversion import c_open
from ..io import read_atom_dump, read_atom_frame, read_thermo
from ..plotting import pyplot, save_png
from ..analysis import C_OPEN_FRACTION
from .curve_features import (C_FRACTION, DROP_FRACTION, OPENED_FRACTION, curve_features,
                             keep_rows)
from .doc import DocContext
from .papers import PAPER
from .runner import Validation, rock_for
from .section import Section

__all__ = ["COMPRESSION_CURVE", "COMPRESSION_CURVE_3D", "CURVES"]

# per dimension: block size, thermo interval (time steps), the series' run to compare with
CURVES = {2: {"n": 30, "thermo_every": 5, "coarse": "2d/n30_compression"},
          3: {"n": 12, "thermo_every": 4, "coarse": None}}
# a trajectory frame every this many thermo rows: where the first bonds break
DUMP_ROWS = 20
HALT_FRACTION = 0.05
COLUMNS = ("v_strain", "v_stress", "c_bonds[1]", "c_bonds[2]", "c_bonds[3]")

# the papers' words on each feature (Liu 2013, paras. 49, 51; Liu 2017, section 5.2)
PAPER_WORDS = {
    2: {"O-A": "O-A: the stress increases linearly from the origin (para. 49)",
        "before_A": "A2, A3: the stress drops a bit prior to A: some boundary bonds break "
                    "earlier (para. 51)",
        "A": "A: tensile micro-cracks form and the stress declines a bit (C_open, para. 49)",
        "opening": "A-B: the stress increases almost linearly, at a lower rate than O-A "
                   "(para. 49)",
        "before_B": "(not described)",
        "B": "B: the whole lattice fails at the compressive strength Cu (para. 49)",
        "C": "C: the stress drops dramatically to almost zero (para. 49)"},
    3: {"O-A": "the stress increases linearly from the origin to A1",
        "before_A": "A3: the stress drops a bit: some boundary bonds fail before the stress "
                    "reaches C_open",
        "A": "A1: the microscopic opening cracks form and the stress decreases",
        "opening": "the stress climbs up with increasing strain",
        "before_B": "a drop of stress also can be found before A2",
        "B": "A2: the compressive strength Cu; the model then fails in sliding mode",
        "C": "(not named in the text on Fig. 5)"},
}
PAPER_NAMES = {2: {"A": "A", "B": "B", "C": "C", "before_A": "A2, A3"},
               3: {"A": "A1", "B": "A2", "C": "C", "before_A": "A3"}}


def _feature_rows(f: dict) -> list[int]:
    """The rows to keep whole in the thinned curve: the features' and every row of the two
    zooms of :func:`curve_png` (from the first break to the end of the opening, and from the
    first drop before the peak to the peak)."""
    rows = [f["B"]["row"], f["opened"]["row"]]
    for key in ("first_break", "C"):
        if f[key] is not None:
            rows.append(f[key]["row"])
    for dr in f["drops"]:
        rows += [dr["top"]["row"], dr["bottom"]["row"]]
    for a, b in _zooms(f).values():
        rows += list(range(max(a, 0), b + 1))
    return rows


def _zooms(f: dict) -> dict[str, tuple[int, int]]:
    """Row ranges of the zooms: the opening (from before the first break to after the end of
    the opening) and the peak (from before the first drop before it to a little after it)."""
    first = f["first_break"]["row"] if f["first_break"] is not None else f["B"]["row"]
    opened = f["opened"]["row"]
    pre_b = min([dr["top"]["row"] for dr in f["before_B"]] + [f["B"]["row"]])
    span_a, span_b = opened - first, f["B"]["row"] - pre_b
    return {"opening": (max(0, first - span_a // 3), opened + span_a // 5),
            "peak": (max(0, pre_b - max(span_b // 2, 40)), f["B"]["row"] + 40)}


def crossing_rows(run: dict, thermo_every: int, rock) -> int:
    """Thermo rows in one elastic-wave crossing of the (square) block: its width over
    sqrt(E / rho), in time steps dt of the run's plan, over ``thermo_every``."""
    crossing = run["lateral_width_m"] / math.sqrt(rock.E / rock.rho)
    return int(math.ceil(crossing / (run["plan"]["dt"] * thermo_every)))


def _features(table: dict, lag: int) -> dict:
    return curve_features(-table["v_strain"], -table["v_stress"], table["c_bonds[2]"],
                          table["c_bonds[3]"], float(table["c_bonds[1]"][0]), lag)


def run_curve(v: Validation, dim: int) -> dict:
    """The dense run, its features and thinned curve; in 2D also the series' run's features."""
    spec = CURVES[dim]
    rock = rock_for(dim)
    name = f"{dim}d/curve_n{spec['n']}_compression"
    run = v.run(name, rock, dim, "compression", spec["n"], thermo_every=spec["thermo_every"],
                halt_fraction=HALT_FRACTION, dump_every=DUMP_ROWS * spec["thermo_every"])
    table = read_thermo(v.folder(name) / "log.lammps")[-1]
    lag = crossing_rows(run, spec["thermo_every"], rock)
    f = _features(table, lag)
    keep = keep_rows(len(table["v_strain"]), _feature_rows(f))
    curve = {"row": [int(i) for i in keep]}
    for c in COLUMNS:
        curve[c] = [float(f"{x:.7g}") for x in table[c][keep]]
    E_line = rock.E / (1.0 - rock.nu**2) if dim == 2 else rock.E
    data = {"dim": dim, "n": spec["n"], "folder": name, "run": run,
            "thermo_every": spec["thermo_every"], "rows": len(table["v_strain"]),
            "halt_fraction": HALT_FRACTION, "lag_rows": lag, "features": f, "curve": curve,
            "fractions": {"drop": DROP_FRACTION, "open": C_OPEN_FRACTION,
                          "opened": OPENED_FRACTION, "c": C_FRACTION},
            "target": {"Cu": rock.Cu, "C_open": c_open(rock.Tu, rock.nu, dim),
                       "E_line": E_line}}
    data["sites"] = first_sites(v.folder(name), table, f, DUMP_ROWS * spec["thermo_every"],
                                dim, run["plan"]["d"])
    coarse = spec["coarse"]
    if coarse is not None and (v.folder(coarse) / "log.lammps").exists():
        ct = read_thermo(v.folder(coarse) / "log.lammps")[-1]
        steps = ct["Step"]
        every = int(steps[1] - steps[0])
        cf = _features(ct, crossing_rows(run, every, rock))
        data["coarse"] = {"folder": coarse, "rows": len(steps),
                          "thermo_every": every,
                          "before_A": cf["before_A"], "A": cf["A"], "opening": len(cf["opening"]),
                          "first_break": cf["first_break"], "B": cf["B"]}
    return data


def break_sites(folder: Path, step: int, dim: int, d: float) -> dict:
    """Where the bonds broken in tension by time step ``step`` are: the particles that lost
    one, and how many of them lie in the block's outer layer (centre within 0.6 d of a face in
    the initial configuration) and in that of its free side faces (across the load), from the
    frame of ``dump.lammpstrj`` at ``step``."""
    names0, initial = read_atom_dump(folder / "dump.initial")
    names, frame = read_atom_frame(folder / "dump.lammpstrj", step)
    axes = ("x", "y") if dim == 2 else ("x", "y", "z")
    pos = np.column_stack([initial[:, names0.index(a)] for a in axes])
    face = [(pos[:, k] < pos[:, k].min() + 0.6 * d) | (pos[:, k] > pos[:, k].max() - 0.6 * d)
            for k in range(len(axes))]
    outer, sides = np.logical_or.reduce(face), np.logical_or.reduce(face[:-1])
    lost = frame[:, names.index("c_ntension")]
    damaged = lost > 0
    return {"step": int(step), "bonds": int(round(lost.sum() / 2)),
            "particles": int(damaged.sum()), "outer": int((damaged & outer).sum()),
            "sides": int((damaged & sides).sum()), "outer_share_of_block": float(outer.mean()),
            "sides_share_of_block": float(sides.mean())}


def first_sites(folder: Path, table: dict, f: dict, every: int, dim: int, d: float) -> dict:
    """:func:`break_sites` at the first frame with bonds broken in tension and at the last
    frame before A's top (frames every ``every`` time steps from step 0)."""
    steps = table["Step"]
    out = {}
    if f["first_break"] is not None:
        first = int(steps[f["first_break"]["row"]])
        out["first"] = break_sites(folder, every * -(-first // every), dim, d)
    if f["A"] is not None:
        top = int(steps[f["A"]["top"]["row"]])
        if "first" in out and every * (top // every) > out["first"]["step"]:
            out["before_A"] = break_sites(folder, every * (top // every), dim, d)
    return out


def _pt(p: dict | None, cu: float) -> list[str]:
    if p is None:
        return ["", "", ""]
    return [f"{1e3 * p['strain']:.4f}", f"{p['stress'] / 1e6:.2f}", f"{p['stress'] / cu:.3f}"]


def _drop_cells(dr: dict, cu: float) -> list[str]:
    return _pt(dr["top"], cu) + [f"{dr['size'] / 1e6:.2f}", f"{dr['tension']} / {dr['shear']}"]


def _drop_rows(drops: list[dict], label: str, words: str, cu: float) -> list[str]:
    """Table rows of a list of drops, the paper's words on the first; 'none found' if empty."""
    if not drops:
        return [f"| {label} | none found | | | | | {words} |"]
    return [f"| {label} ({k + 1}) | " + " | ".join(_drop_cells(dr, cu))
            + f" | {words if k == 0 else ''} |" for k, dr in enumerate(drops)]


def feature_table(data: dict) -> list[str]:
    """The features' strain, stress, stress / Cu of the formula, drop and bonds, and what the
    paper says of each."""
    f, dim, cu = data["features"], data["dim"], data["target"]["Cu"]
    words, names = PAPER_WORDS[dim], PAPER_NAMES[dim]
    L = ["| feature | strain (1e-3) | stress (MPa) | stress / Cu | drop (MPa) | bonds broken "
         "(tension / shear) | the paper |", "|---|---|---|---|---|---|---|"]
    e_ratio = f["E_OA"] / data["target"]["E_line"] if f["E_OA"] else None
    L.append(f"| O-A: slope {f['E_OA'] / 1e9:.2f} GPa ({e_ratio:.4f} of the formula's) | | | "
             f"| | | {words['O-A']} |")
    fb = f["first_break"]
    if fb is not None:
        L.append("| first broken bonds | " + " | ".join(_pt(fb, cu)) + f" | | "
                 f"{f['first_break_bonds']} | |")
    fr = data["fractions"]
    L += _drop_rows(f["before_A"], f"drop before {names['A']}", words["before_A"], cu)
    if f["A"] is not None:
        L.append(f"| {names['A']} (top of the first drop once {100 * fr['open']:g}% of the "
                 "bonds are broken in tension) | " + " | ".join(_drop_cells(f["A"], cu))
                 + f" | {words['A']} |")
    op = f["opening"]
    if op:
        big = max(op, key=lambda dr: dr["size"])
        L.append(f"| largest of the {len(op)} drops while the block opens | "
                 + " | ".join(_drop_cells(big, cu)) + " | |")
    L.append(f"| end of the opening ({100 * fr['opened']:g}% of the tension breaks) | "
             + " | ".join(_pt(f["opened"], cu)) + f" | | | {words['opening']} |")
    L += _drop_rows(f["before_B"], f"drop before {names['B']}", words["before_B"], cu)
    L.append(f"| {names['B']} (peak) | " + " | ".join(_pt(f["B"], cu)) + f" | | | {words['B']} |")
    L.append(f"| {names['C']} (end of the drop: within {fr['c']:g} of the fall from the "
             "peak to the lowest stress) | " + " | ".join(_pt(f["C"], cu))
             + f" | | | {words['C']} |")
    return L


def curve_png(path, data: dict, title: str) -> None:
    """The thinned curve with its features marked: the whole curve, and zooms on the opening
    (with the broken-bond counts) and on the peak."""
    plt = pyplot()
    c, f, dim = data["curve"], data["features"], data["dim"]
    names = PAPER_NAMES[dim]
    eps = -1e3 * np.asarray(c["v_strain"])
    sig = -np.asarray(c["v_stress"]) / 1e6
    bt, bs = np.asarray(c["c_bonds[2]"]), np.asarray(c["c_bonds[3]"])
    rows = np.asarray(c["row"])
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))

    def mark(ax, p, label, colour, text=True):
        if p is None:
            return
        x, y = 1e3 * p["strain"], p["stress"] / 1e6
        ax.plot(x, y, "o", color=colour, ms=5)
        if text:
            below = label == names["before_A"]
            ax.annotate(label, (x, y), textcoords="offset points",
                        xytext=(-40, 4) if below else (4, 6), fontsize=8, color=colour)

    points = [(f["A"]["top"] if f["A"] else None, names["A"], "tab:red"),
              (f["B"], names["B"], "tab:purple"), (f["C"], names["C"], "tab:brown")]
    pre_a = [(dr["top"], names["before_A"], "tab:orange") for dr in f["before_A"]]
    pre_b = [(dr["top"], f"drop before {names['B']}", "tab:green") for dr in f["before_B"]]
    ax = axes[0]
    ax.plot(eps, sig, lw=1)
    ax.plot([0, eps.max()], [0, data["target"]["E_line"] * eps.max() / 1e9], "k:", lw=0.8,
            label="formula's E")
    ax.axhline(data["target"]["Cu"] / 1e6, color="r", ls=":", lw=0.8, label="Cu (formula)")
    for p, label, colour in points + pre_a[:1] + pre_b[:1]:
        mark(ax, p, label, colour)
    # zooms: from before the first break to after the opening; around the drops before the peak
    
    ax.set_ylim(0, 1.1 * max(sig.max(), data["target"]["Cu"] / 1e6))
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    # zoom on the opening
    zooms = _zooms(f)
    for ax, what in ((axes[1], "opening"), (axes[2], "peak")):
        a, b = zooms[what]
        m = (rows >= a) & (rows <= b)
        ax.plot(eps[m], sig[m], ".-", lw=0.8, ms=2)
        labelled = set()
        for p, label, colour in points + pre_a + pre_b:
            if p is not None and a <= p["row"] <= b:
                mark(ax, p, label, colour, text=label not in labelled)
                labelled.add(label)
        for dr in f["drops"]:
            if a <= dr["top"]["row"] <= b and dr["tension"] + dr["shear"] > 0:
                fall = m & (rows >= dr["top"]["row"]) & (rows <= dr["bottom"]["row"])
                ax.plot(eps[fall], sig[fall], "r-", lw=1.6)
        twin = ax.twinx()
        twin.plot(eps[m], (bt if what == "opening" else bs)[m], color="0.5", lw=0.8, ls="--")
        twin.set_ylabel(f"bonds broken in {'tension' if what == 'opening' else 'shear'} "
                        "(dashed)", fontsize=8)
        ax.set_title(f"{what}: falls with broken bonds in red", fontsize=9)
    for ax in axes:
        ax.set_xlabel("compressive strain (1e-3)")
        ax.set_ylabel("compressive stress (MPa)")
    save_png(fig, path)


def doc_curve(data: dict, ctx: DocContext) -> list[str]:
    dim, f, run = data["dim"], data["features"], data["run"]
    paper = "Liu 2013, para. 49, 51 and Fig. 7a" if dim == 2 else "Liu 2017, Fig. 5"
    size = PAPER["2d.n30.particles"] if dim == 2 else PAPER["3d.n12.elements"]
    label = "2D" if dim == 2 else "3D"
    img = f"compression_curve_{dim}d.png"
    L = [f"## The compressive stress-strain curve, {label} ({paper})", "",
         f"The {run['particles']}-{'particle' if dim == 2 else 'element'} block "
         f"({'N' if dim == 2 else 'n_y'} = {data['n']}; the paper's: {size.value:g}) in "
         "compression, constant loading at the papers' damping, a thermo row every "
         f"{data['thermo_every']} time steps ({data['rows']} rows), run until the stress "
         f"fell below {data['halt_fraction']:g} of its peak or the planned steps ended.  The "
         "features are found from the curve and the broken-bond counts "
         "(`bonded_lattice.validation.curve_features`): a drop is a fall of the stress by at "
         f"least {f['drop_min'] / 1e6:.2f} MPa ({data['fractions']['drop']:g} of the peak, "
         "above the loading's ringing) with bonds broken from one wave crossing "
         f"({data['lag_rows']} rows) before "
         "its top (but after the trough before it) to its bottom; stress / Cu is over the "
         "formula's Cu; the O-A slope is over the formula's E"
         + (", in 2D the in-plane modulus of plane strain E / (1 - nu^2), the slope a 2D "
            "test measures" if dim == 2 else "") + ".", ""]
    L += feature_table(data)
    a = f["A"]
    if a is not None:
        L += ["", f"{PAPER_NAMES[dim]['A']} at {a['top']['stress'] / 1e6:.2f} MPa is "
              f"{a['top']['stress'] / data['target']['C_open']:.3f} of the formula's C_open "
              f"({data['target']['C_open'] / 1e6:.1f} MPa; the run's C_open, the last row "
              f"before {100 * data['fractions']['open']:g}% of the bonds are broken in "
              "tension: "
              f"{run['measured'].get('C_open', 0) / 1e6:.2f} MPa)."]
    sites = data.get("sites", {})
    for key, what in (("first", "At the first trajectory frame with bonds broken in tension"),
                      ("before_A", f"At the last frame before {PAPER_NAMES[dim]['A']}")):
        st = sites.get(key)
        if st is not None:
            L += ["", f"{what} (time step {st['step']}): {st['bonds']} bonds, "
                  f"{st['particles']} particles lost one, {st['outer']} of them in the outer "
                  f"layer of the block (which holds {100 * st['outer_share_of_block']:.0f}% of "
                  f"its particles), {st['sides']} in that of its free side faces "
                  f"({100 * st['sides_share_of_block']:.0f}%)."]
    co = data.get("coarse")
    if co is not None:
        ca = co["A"]
        L += ["", f"The series' run of the same block (`{co['folder']}`, a row every "
              f"{co['thermo_every']} steps, {co['rows']} rows) shows "
              f"{len(co['before_A'])} drop(s) before A and {co['opening']} while the block "
              "opens" + (f", A at {ca['top']['stress'] / 1e6:.2f} MPa" if ca else "")
              + f", against {len(f['before_A'])} and {len(f['opening'])} here: its rows are "
              + ("too sparse to resolve the small drops." if len(co["before_A"]) <
                 len(f["before_A"]) else "dense enough for them.")]
    curve_png(ctx.img / img, data, f"{label}, {run['particles']} "
              f"{'particles' if dim == 2 else 'elements'}, compression")
    L += ["", f"![The compressive stress-strain curve, {label}, with its features](img/{img})"]
    return L


def run_curve_2d(v: Validation) -> dict:
    return run_curve(v, 2)


def run_curve_3d(v: Validation) -> dict:
    return run_curve(v, 3)


COMPRESSION_CURVE = Section("compression_curve", run_curve_2d, doc_curve)
COMPRESSION_CURVE_3D = Section("compression_curve_3d", run_curve_3d, doc_curve)
