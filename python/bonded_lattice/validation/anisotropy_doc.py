"""The text, tables and figure of the section ``anisotropy``
(:mod:`bonded_lattice.validation.anisotropy`), made from its data alone."""

from __future__ import annotations

from pathlib import Path

from .doc import DocContext, pct
from .papers import PAPER

__all__ = ["anisotropy_doc", "anisotropy_png"]

PROPS = ("E", "nu", "Tu", "Cu")
FIGURE = "anisotropy.png"


def _pts(x: float, digits: int = 1) -> str:
    """A difference of two relative errors, in percentage points."""
    return f"{100 * x:+.{digits}f} points"


def _below(x: float) -> str:
    """A difference of two relative errors as 'N.N points below/above'."""
    return f"{100 * abs(x):.1f} points {'below' if x < 0 else 'above'}"


def _mpa(r: dict, test: str) -> str:
    """The stress at which a row's ``test`` run broke its first bond, in MPa."""
    return f"{r['runs'][test]['first_break_stress'] / 1e6:.0f} MPa"


def _deg(x: float) -> str:
    return f"{x:g}°"


def _cells(r: dict, extra: dict[str, str] | None = None) -> str:
    """A row's table cells from its particles on: particles, platen contacts / end band,
    the four errors (``extra``: a cell after the one named), damage near the ends."""
    e, near, extra = r["relative_error"], r["damage_near_ends"], extra or {}
    cells = [str(r["particles"]), f"{r['end_contacts']} / {r['end_band_particles']}"]
    for p in PROPS:
        cells.append(pct(e[p], 2 if p in ("E", "nu") else 1))
        if p in extra:
            cells.append(extra[p])
    cells.append(f"{_frac(near['Tu'])} / {_frac(near['Cu'])}")
    return " | ".join(cells) + " |"


def _row_2d(r: dict) -> str:
    return (f"| {_deg(r['orientation_deg'])} | {_deg(r['lattice_direction_deg'])} | "
            + _cells(r, {"Tu": pct(r["affine_Tu_error"], 1)}))


def _frac(x: float | None) -> str:
    return "" if x is None else f"{100 * x:.0f}%"


def _table_2d(data: dict) -> list[str]:
    L = ["| θ | load in the paper's frame | particles | platen contacts / end band | E | nu "
         "| Tu | Tu, unbounded lattice | Cu | damage within 2 d of the ends (Tu / Cu) |",
         "|---|---|---|---|---|---|---|---|---|---|"]
    for n in data["sizes_2d"]:
        block = data["two_d"][str(n)]
        L.append(f"| **N = {n}** | | | | | | | | | |")
        L += [_row_2d(r) for r in block["rows"]]
        L.append(_row_2d(block["mirror"]).replace(f"| {_deg(data['mirror_2d'])} |",
                                                  f"| {_deg(data['mirror_2d'])} (mirror of "
                                                  f"{_deg(data['mirror_of'])}) |", 1))
        L.append(_row_2d(block["papers_platens"]).replace("| 0° |", "| 0°, papers' platens |",
                                                          1))
    return L


def _table_3d(data: dict) -> list[str]:
    t = data["three_d"]
    names = {0.0: "layers across the load (the paper's)", 90.0: "rows along the load"}
    L = ["| orientation | elements | platen contacts / end band | E | nu | Tu | Cu "
         "| damage within 2 d of the ends (Tu / Cu) |", "|---|---|---|---|---|---|---|---|"]
    labelled = [(r, f"{_deg(r['orientation_deg'])}: {names[r['orientation_deg']]}")
                for r in t["rows"]] + [(t["papers_platens"], "0°, papers' platens")]
    return L + [f"| {label} | " + _cells(r) for r, label in labelled]


def _range(block: dict, prop: str, digits: int = 1) -> str:
    s = block["spread"][prop]
    return (f"{pct(s['min'], digits)} (at {_deg(s['min_at_deg'])}) to {pct(s['max'], digits)} "
            f"(at {_deg(s['max_at_deg'])})")


def _stepped(block: dict, prop: str) -> tuple[float, float]:
    """Smallest and largest error at the angles strictly between 0 and 30 degrees."""
    errs = [r["relative_error"][prop] for r in block["rows"]
            if 0.0 < r["orientation_deg"] < 30.0]
    return min(errs), max(errs)


def _curve_at(curve: dict, angle: float) -> float:
    """The unbounded lattice's Tu error at ``angle`` (one of the curve's angles)."""
    return curve["error"][curve["angle_deg"].index(angle)]


def _neighbour_step(block: dict, prop: str) -> float:
    """The largest change of ``prop``'s error between neighbouring stepped angles."""
    errs = [r["relative_error"][prop] for r in block["rows"]
            if 0.0 < r["orientation_deg"] < 30.0]
    return max(abs(b - a) for a, b in zip(errs, errs[1:]))


def _repeats(small: dict, large: dict, sizes: list[int]) -> str:
    """Which properties the mirror angle repeats (its difference no larger than the largest
    change between neighbouring stepped angles), per size."""
    out = []
    for n, block in zip((sizes[0], sizes[-1]), (small, large)):
        same = [p for p in PROPS
                if abs(block["mirror_difference"][p]) <= _neighbour_step(block, p)]
        other = [p for p in PROPS if p not in same]
        text = f"At N = {n} the mirror angle repeats {', '.join(same) or 'none'}"
        if other:
            text += f" but not {', '.join(other)}, which then depends on how the block is cut"
        out.append(text + ".")
    return " ".join(out)


def anisotropy_doc(data: dict, ctx: DocContext) -> list[str]:
    """The section's Markdown; draws docs/img/anisotropy.png."""
    anisotropy_png(ctx.img / FIGURE, data)
    sizes = data["sizes_2d"]
    small, large = (data["two_d"][str(n)] for n in (sizes[0], sizes[-1]))
    at = {r["orientation_deg"]: r for r in small["rows"]}
    at_large = {r["orientation_deg"]: r for r in large["rows"]}
    zero, along = at[0.0], at[30.0]
    stepped = [r for r in small["rows"] if 0.0 < r["orientation_deg"] < 30.0]
    paper = PAPER["2d.anisotropy.direction_deg"]
    angles = data["angles_2d"]
    lo_e, hi_e = _stepped(small, "E")
    lo_e2, hi_e2 = _stepped(large, "E")
    lo_t, hi_t = _stepped(small, "Tu")
    lo_t2, hi_t2 = _stepped(large, "Tu")
    lo_c, hi_c = _stepped(small, "Cu")
    curve = data["affine_Tu_error_curve"]
    lower_e = small["spread"]["E"]["below_papers"]
    lower_t = small["spread"]["Tu"]["below_papers"]
    others = len(angles) - 1
    md, pm = small["mirror_difference"], small["platens_minus_layers"]
    md2 = large["mirror_difference"]
    t3 = data["three_d"]
    r0, r90 = t3["rows"]
    L = ["## Anisotropy: E, nu, Tu and Cu against the lattice's orientation (Liu 2013 para. 55)",
         "",
         f"The 2013 paper validates its formulas with the load at {paper.value:g}° to the "
         "close-packed rows (by the unit's symmetry also at 30° and 150°) and reports that "
         "\"E and Tu are a bit lower along other directions\" (para. 55).  Here the papers' "
         f"2D block of N = {sizes[0]} and {sizes[-1]} particles across is cut from the lattice "
         f"turned by θ = {_deg(angles[0])} to {_deg(angles[-1])} in steps of "
         f"{_deg(angles[1] - angles[0])} (counter-clockwise about the lower-left particle, "
         "`orientation`), in the same rectangle; the load stays along y.  In the paper's "
         "lattice frame the load is then at 90° − θ: θ = 0 is the paper's 90° (and, the "
         "lattice repeating every 60°, its 30° and 150°), θ = 30° puts one bond family along "
         "the load (the paper's horizontal direction, which has no formula).  The lattice's "
         "mirror planes at 0 and 30° make 0-30° every direction; "
         f"θ = {_deg(data['mirror_2d'])}, the mirror image of {_deg(data['mirror_of'])} cut "
         "differently, checks that.  "
         f"N = {sizes[0]} ({zero['particles']} particles at 0°) keeps the runs cheap and is "
         "past the smallest blocks' regime (its E at 0° is "
         f"{pct(zero['relative_error']['E'])} off the formula and its Tu "
         f"{pct(zero['relative_error']['Tu'], 1)}, against "
         f"{pct(at_large[0.0]['relative_error']['E'])} and "
         f"{pct(at_large[0.0]['relative_error']['Tu'], 1)} at N = {sizes[-1]}); "
         f"N = {sizes[-1]} repeats the sweep to tell edge effects (which shrink with size) "
         "from the lattice's own anisotropy.",
         "",
         "**The blocks.** Only at 0 and 30° are the sides and ends lattice lines (at 30° the "
         "ends are zigzags of particles at 0 and d/2 from the end).  In between every side is "
         f"stepped and the block holds fewer particles ({min(r['particles'] for r in stepped)}"
         f"-{max(r['particles'] for r in stepped)} at N = {sizes[0]}).  A flat platen would "
         f"touch {min(r['end_contacts'] for r in stepped)}-"
         f"{max(r['end_contacts'] for r in stepped)} of the "
         f"{min(r['end_band_particles'] for r in stepped)}-"
         f"{max(r['end_band_particles'] for r in stepped)} particles within 0.6 d of the two "
         "ends, the lowest of each step, and load the block through them; so every run here "
         "holds the end bands (`ends=\"layers\"`, chosen automatically for stepped ends): "
         "their axial motion prescribed, free sideways, pushed together in compression as "
         "tension pulls them apart.  The stress is the end bands' force over the width "
         "between the outermost centres (`Lattice.loaded_area`, as everywhere), "
         f"{zero['loaded_area_d']:.2f} d at 0° and {min(r['loaded_area_d'] for r in stepped):.2f}"
         f"-{max(r['loaded_area_d'] for r in stepped):.2f} d when turned.  The papers' "
         "platens at 0° are run too (last row of each size).",
         "",
         f"![anisotropy](img/{FIGURE})", ""]
    L += _table_2d(data)
    L += ["",
          "Errors are against the formulas (measured minus formula, relative); \"Tu, unbounded "
          "lattice\": the stress at which the most stretched bond of an unbounded, affinely "
          "deformed lattice reaches Xb (bonds at θ, θ + 60° and θ + 120°; "
          "`anisotropy.affine_tu_2d`); the last column: of the particles that lost bonds, "
          "those within 2 d of an end.",
          "",
          f"- **E and nu.**  Over 0-30° E runs from {_range(small, 'E')} at N = {sizes[0]} "
          f"and from {_range(large, 'E')} at N = {sizes[-1]}.  A hexagonal lattice is "
          "elastically isotropic, and the numbers say the dependence is the blocks' edges: "
          f"at the stepped angles the deficit ({pct(lo_e)} to {pct(hi_e)}) shrinks to "
          f"{pct(lo_e2)} to {pct(hi_e2)} when N doubles; at 30° the side columns are straight "
          "chains along the load, so the width between the outer centres leaves out half a "
          f"column spacing on each side, √3/2 d over the width = "
          f"{pct(small['side_columns_over_width'])} at N = {sizes[0]} and "
          f"{pct(large['side_columns_over_width'])} at N = {sizes[-1]}, against E "
          f"{pct(along['relative_error']['E'])} and {pct(at_large[30.0]['relative_error']['E'])}."
          f"  nu runs from {_range(small, 'nu')} ({_range(large, 'nu')} at N = {sizes[-1]}).",
          f"- **Tu.**  {pct(zero['relative_error']['Tu'], 1)} at 0° and "
          f"{pct(along['relative_error']['Tu'], 1)} at 30°, against "
          f"{pct(curve['error'][0], 1)} and {pct(curve['error'][-1], 1)} for an unbounded "
          "lattice (with a bond along the load, that bond stretches by the full axial strain "
          "and breaks first).  The zones within 2 d of the ends hold "
          f"{_frac(4.0 / zero['height_d'])} of the block's height; of the damage of the "
          f"N = {sizes[0]} tension runs they hold {_frac(zero['damage_near_ends']['Tu'])} at "
          f"0°, {_frac(min(r['damage_near_ends']['Tu'] for r in stepped))}-"
          f"{_frac(max(r['damage_near_ends']['Tu'] for r in stepped))} at the stepped angles "
          f"and {_frac(along['damage_near_ends']['Tu'])} at 30°: the blocks break next to a "
          "held end, where they meet the end band, except at 30°.  At 0° that boundary is a "
          "lattice line and the block comes "
          f"{_below(zero['relative_error']['Tu'] - curve['error'][0])} the unbounded lattice "
          f"(30°: {_below(along['relative_error']['Tu'] - curve['error'][-1])}); "
          f"at the stepped angles they break at {pct(lo_t, 0)} to {pct(hi_t, 0)} "
          f"({pct(lo_t2, 0)} to {pct(hi_t2, 0)} at N = {sizes[-1]}: no better), against "
          f"{pct(_curve_at(curve, 5.0), 0)} to {pct(_curve_at(curve, 25.0), 0)} for the "
          "unbounded lattice: the steps load the few bonds that cross each of them, a local "
          "concentration that does not shrink with the block.  These numbers measure the "
          "stepped grips, not the lattice, whose own Tu at those angles is the unbounded "
          "value.",
          f"- **Cu.**  {pct(zero['relative_error']['Cu'], 1)} at 0° with held ends and "
          f"{pct(small['papers_platens']['relative_error']['Cu'], 1)} with the papers' "
          "platens: the platens, not the lattice, make most of that block's Cu deficit (also "
          f"at N = {sizes[-1]}: {pct(at_large[0.0]['relative_error']['Cu'], 1)} and "
          f"{pct(large['papers_platens']['relative_error']['Cu'], 1)}); "
          f"{pct(along['relative_error']['Cu'], 0)} at 30°, where a uniform compression "
          "stretches no bond (a bond at 60° to the load changes length by (nu cos² 30° − "
          "sin² 30°) times the axial shortening, negative for nu < 1/3), so the first bond "
          f"breaks only at {_mpa(along, 'compression')} against {_mpa(zero, 'compression')} "
          "at 0°, where the bonds across the load open (C_open); at the stepped angles "
          f"{pct(lo_c, 0)} to {pct(hi_c, 0)}, from {pct(stepped[0]['relative_error']['Cu'], 0)}"
          f" at {_deg(stepped[0]['orientation_deg'])} to "
          f"{pct(stepped[-1]['relative_error']['Cu'], 0)} at "
          f"{_deg(stepped[-1]['orientation_deg'])}.",
          f"- **The paper's statement.**  Against θ = 0, E is lower at {lower_e} of the "
          f"{others} other angles and Tu at {lower_t} of {others} (N = {sizes[0]}).  For Tu "
          "this agrees with the paper and with the unbounded lattice (lower at "
          f"{sum(e < curve['error'][0] for e in curve['error'][1:])} of the "
          f"{len(curve['error']) - 1} other whole degrees up to 30°, at most "
          f"{_below(min(curve['error']) - curve['error'][0])} the papers' orientation), but the "
          "blocks' Tu at the stepped angles is far more than \"a bit\" lower because of the "
          "ends; E is lower at the stepped angles only as an edge effect that shrinks with "
          "size, and higher at 30° through the stress-area convention.",
          f"- **Symmetry.**  θ = {_deg(data['mirror_2d'])} against its mirror image "
          f"{_deg(data['mirror_of'])} (the same lattice, cut differently: "
          f"{small['mirror']['particles']} and {at[data['mirror_of']]['particles']} "
          f"particles): E {_pts(md['E'], 2)}, nu {_pts(md['nu'], 2)}, Tu {_pts(md['Tu'])}, "
          f"Cu {_pts(md['Cu'])} at N = {sizes[0]}; E {_pts(md2['E'], 2)}, Tu {_pts(md2['Tu'])},"
          f" Cu {_pts(md2['Cu'])} at N = {sizes[-1]}; the largest change between neighbouring "
          "stepped angles is, for comparison, "
          + ", ".join(f"{p} {_pts(_neighbour_step(small, p))}" for p in PROPS)
          + f" at N = {sizes[0]} and "
          + ", ".join(f"{p} {_pts(_neighbour_step(large, p))}" for p in PROPS)
          + f" at N = {sizes[-1]}.  {_repeats(small, large, sizes)}",
          "",
          f"**3D** (block of {data['size_3d']} elements along y).  Orientation 0 is the 2017 "
          "paper's: close-packed layers across the load (z).  Orientation 90 turns the block "
          "by 90° about x (`orientation=90`, `lattice.turned_block_3d`): the close-packed "
          "rows run along the load, one bond family along it, the layers stand upright, and "
          "the ends are stepped (rows alternate n_y and n_y − 1 elements), so the end bands "
          "are held as in 2D.", ""]
    L += _table_3d(data)
    dr, dp = t3["rows_minus_layers"], t3["platens_minus_layers"]
    bulk = t3["bulk_fcc"]
    combined = (1.0 + bulk["E_along_rows"]) * (1.0 + t3["side_chains_area"]) - 1.0
    L += ["",
          f"Turning the load from across the layers to along the rows changes E by "
          f"{_pts(dr['E'])}, nu by {_pts(dr['nu'])}, Tu by {_pts(dr['Tu'])} and Cu by "
          f"{_pts(dr['Cu'])}; with the paper's platens instead of held end layers the "
          f"paper's orientation changes E by {_pts(dp['E'])}, Tu by {_pts(dp['Tu'])} and Cu "
          f"by {_pts(dp['Cu'])}.  Of the broken bonds at orientation 90, "
          f"{_frac(r90['damage_near_ends']['Tu'])} (tension) and "
          f"{_frac(r90['damage_near_ends']['Cu'])} (compression) lie within 2 d of the ends "
          f"({_frac(r0['damage_near_ends']['Tu'])} and {_frac(r0['damage_near_ends']['Cu'])} "
          "at orientation 0).",
          "",
          "Unlike the 2D lattice, close packing is elastically anisotropic: an unbounded "
          "lattice with the same bonds (face-centred cubic, whose bonds make the same angles "
          "with the layers as the paper's hcp; `periodic.stiffness_matrix`) has E "
          f"{pct(bulk['E_across_layers'])} and nu {pct(bulk['nu_across_layers'])} across the "
          f"layers but E {pct(bulk['E_along_rows'])} and nu {pct(bulk['nu_along_rows'])} (the "
          "mean of its two lateral contractions) along a row.  The turned block measures nu "
          f"{pct(r90['relative_error']['nu'])}, close to that, but E "
          f"{pct(r90['relative_error']['E'])}: its side faces are row planes and layers, "
          "straight chains along the load, and the half spacing outside the outer centres "
          f"adds {pct(t3['side_chains_area'], 1)} to the area between them; with it the "
          f"unbounded lattice's E along a row would read {pct(combined)} on this block's "
          f"area; the measured value lies {_below(r90['relative_error']['E'] - combined)} it "
          "(the rest, not resolved here, is the small block's other edges and stepped ends, "
          "and the paper's hcp stacking against the fcc of the estimate).  The strengths "
          "repeat the 2D picture with a bond along the load: Tu "
          f"{pct(r90['relative_error']['Tu'], 1)} (2D at 30°: "
          f"{pct(along['relative_error']['Tu'], 1)}) and Cu "
          f"{pct(r90['relative_error']['Cu'], 0)} (2D: {pct(along['relative_error']['Cu'], 0)})."]
    return L


def anisotropy_png(path: Path, data: dict) -> None:
    """Errors against the 2D orientation (E and nu; Tu and Cu, with the unbounded lattice's
    Tu; both sizes, the mirror angle at its mirror image) and the two 3D orientations."""
    from ..plotting import _pyplot

    plt = _pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.6), gridspec_kw={"width_ratios": [1, 1, 0.8]})
    colors = {"E": "C0", "nu": "C1", "Tu": "C2", "Cu": "C3"}
    sizes = data["sizes_2d"]
    for ax, props in zip(axes[:2], (("E", "nu"), ("Tu", "Cu"))):
        for k, n in enumerate(sizes):
            block = data["two_d"][str(n)]
            angle = [r["orientation_deg"] for r in block["rows"]]
            for p in props:
                err = [100 * r["relative_error"][p] for r in block["rows"]]
                ax.plot(angle, err, "o-" if k == 0 else "s--", color=colors[p],
                        mfc=colors[p] if k == 0 else "none", label=f"{p}, N = {n}")
                ax.plot([data["mirror_of"]], [100 * block["mirror"]["relative_error"][p]],
                        "x" if k == 0 else "+", color=colors[p], ms=9, mew=2,
                        label=f"{p}, N = {n}, {data['mirror_2d']:g}° (at {data['mirror_of']:g}°)")
        if "Tu" in props:
            c = data["affine_Tu_error_curve"]
            ax.plot(c["angle_deg"], [100 * e for e in c["error"]], ":", color=colors["Tu"],
                    lw=2, label="Tu, unbounded lattice")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_xlabel("θ: rows' angle to x, load along y (degrees)")
        ax.set_ylabel("error against the formula (%)")
        ax.set_xticks(data["angles_2d"])
        ax.legend(fontsize=6, ncol=2)
        ax.set_title(f"2D, {' and '.join(props)}")
    ax = axes[2]
    t3 = data["three_d"]
    rows = t3["rows"] + [t3["papers_platens"]]
    labels = ["0°, held ends", "90°, held ends", "0°, platens"]
    width = 0.26
    for k, (r, label) in enumerate(zip(rows, labels)):
        x = [i + (k - 1) * width for i in range(len(PROPS))]
        heights = [100 * r["relative_error"][p] for p in PROPS]
        ax.bar(x, heights, width, label=label)
        for xi, h in zip(x, heights):
            ax.annotate(f"{h:+.0f}", (xi, h), ha="center", va="bottom" if h >= 0 else "top",
                        fontsize=6)
    ax.set_xticks(range(len(PROPS)))
    ax.set_xticklabels(PROPS)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_ylabel("error against the formula (%)")
    ax.set_title(f"3D, n_y = {data['size_3d']}: 0° the paper's, 90° rows along the load",
                 fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
