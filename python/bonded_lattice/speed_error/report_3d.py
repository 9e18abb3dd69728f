"""Part 4 of the speed-against-error report: the 3D quartzite lattice (the same tables,
fronts, rule and transfer check as the 2D part, on 3D blocks), and the summary lines on the
references and the defaults of both dimensions."""

from __future__ import annotations

from ..schedules import PAPER_SCHEDULES
from .plots import plot_constant, plot_pareto
from .recommendation import alternative_and_check, recommendation_section
from .report_defaults import (converged_text, default_on_fronts, defaults_words, errors_text,
                              front_text, package_defaults, per_test_text)
from .report_fronts import front_tables
from .report_lattice import grid_tables, paper_table, stepwise_table
from .settings import QUANTITIES, TOLERANCE, Settings, grid_case
from .text import pct as _pct

TESTS = ("elastic", "tension", "compression")
# the 3D default before this study (DEFAULT_LOADING[3] until the study was made)
FORMER_3D = {"crossings": 100.0, "damping": 1.0}


def summary_lines(s2: Settings, lat2: dict, s3: Settings | None, lat3: dict | None) -> list[str]:
    """The summary's bullets on the references (per quantity, per dimension) and on the
    defaults' place on the Pareto fronts."""
    by2 = {r["name"]: r for r in lat2["results"]}
    refs = (f"E and nu against the closed-form formulas (docs/theory.md); Tu and Cu against "
            f"the strength the papers' stepwise schedule (`stepwise`, alias `paper`) measures "
            f"on a block of the same size, in 2D {converged_text(s2, lat2, by2, short=True)}")
    lines = []
    if s3 is not None and lat3 is not None:
        by3 = {r["name"]: r for r in lat3["results"]}
        refs += f", in 3D {converged_text(s3, lat3, by3, short=True)}"
    lines.append(f"- **References**: {refs}.  Neither is the papers' published value: the "
                 "study measures the loading's error, and the block's own size effect is in "
                 "the reference too (docs/validation.md compares with the papers' values).")
    fronts = []
    for s, lat in ((s2, lat2), (s3, lat3)):
        if s is None or lat is None:
            continue
        by = {r["name"]: r for r in lat["results"]}
        d = default_on_fronts(s, lat, by)
        fronts.append(f"{s.dim}D ({defaults_words(d['defaults'])}): "
                      f"{'on' if d['on_front'] else 'NOT on'} the front"
                      + (f", {d['share']:.2f} of the tolerance used" if d["share"] is not None
                         else ", not in the grid"))
    lines.append("- **The package's defaults on the Pareto front** (the grid's settings, time "
                 "steps against the largest share of the tolerance used at the setting and "
                 "every slower one; parts 3 and 4): " + "; ".join(fronts) + ".")
    if s3 is not None and lat3 is not None:
        by3 = {r["name"]: r for r in lat3["results"]}
        if lat3["chosen"]:
            c, f = lat3["chosen"]
            same = (s3.default["crossings"], s3.default["damping"]) == (c, f)
            lines.append(f"- **Recommended 3D defaults**: `--crossings {c:g} --damping {f:g}` "
                         f"(`DEFAULT_LOADING[3]` {'is this setting' if same else 'DIFFERS'}; "
                         f"before this study {FORMER_3D['crossings']:g} and "
                         f"{FORMER_3D['damping']:g}).  " + per_test_text(s3, lat3, by3) +
                         "  Cost of these per-test defaults: " +
                         cost_text(s3, lat3, by3, package_defaults(s3)) + ".")
        else:
            lines.append("- **Recommended 3D defaults**: none of the 3D grid's settings passed "
                         "every test (part 4).")
    return lines


def cost_text(s: Settings, lat: dict, by_name: dict[str, dict],
              settings: dict[str, tuple[float, float]] | None = None) -> str:
    """Time steps per test at ``settings`` (per test kind; default the recommended setting
    for all) against the former 3D default and the papers' stepwise schedule."""
    if settings is None:
        settings = {t: tuple(lat["chosen"]) for t in TESTS}
    parts = []
    for t in TESTS:
        new = by_name.get(grid_case(s, t, *settings[t]).name)
        old = by_name.get(grid_case(s, t, FORMER_3D["crossings"], FORMER_3D["damping"]).name)
        paper = lat["paper"].get(t)
        if not new:
            continue
        txt = f"{t} {new['steps']} time steps"
        if old:
            txt += f" ({new['steps'] / old['steps']:.2g}x the former default's"
            txt += f", {paper['steps'] / new['steps']:.3g}x fewer than the papers' schedule)" \
                if paper else ")"
        parts.append(txt)
    return "; ".join(parts)


def recommendation_text_3d(lat: dict, s: Settings, V: dict, by_name: dict) -> str:
    """The reasoning of the 3D recommendation, from the numbers."""
    if not lat["chosen"]:
        return ("**No recommendation:** no candidate passed the check; the 3D default is "
                "unmeasured.")
    c, f = lat["chosen"]
    pkg = s.default
    same = (pkg["crossings"], pkg["damping"]) == (c, f)
    former = (FORMER_3D["crossings"], FORMER_3D["damping"])
    text = [f"**Recommendation (3D): `crossings = {c:g}`, `damping = {f:g}`.**  The package's "
            f"3D default (`schedules.DEFAULT_LOADING[3]`: {pkg['crossings']:g} crossings, "
            f"damping {pkg['damping']:g}) {'is this setting' if same else 'DIFFERS from it'}.",
            ""]
    text.append(f"- Errors at the recommended setting: {errors_text(lat, (c, f))} (E, nu "
                "against the formulas, Tu, Cu against the papers' schedule); at the former 3D "
                f"default ({former[0]:g} crossings, damping {former[1]:g}): "
                f"{errors_text(lat, former)}.")
    text.append("- Cost of the package's per-test defaults: " +
                cost_text(s, lat, by_name, package_defaults(s)) + ".")
    text.append("- Cost of the one recommended setting: " + cost_text(s, lat, by_name) +
                ".  Wall time on one rank at the "
                "recommended setting: " + ", ".join(
                    f"{t} {r['wall_s']:.1f} s" for t in TESTS
                    for r in [by_name.get(grid_case(s, t, c, f).name)] if r) +
                f" (elastic n_y = {s.n_elastic}, strength n_y = {s.n_strength}).")
    text.append("- It is the cheapest setting of the grid that holds the papers' accuracy for "
                "every quantity and at every slower setting with the same damping, and it "
                f"passed the check on the n_y = {s.n_check} block.")
    slow = max(cc for cc, _ in lat["grid"])
    cu_slow = sorted((ff, e.get("Cu")) for (cc, ff), e in lat["grid"].items() if cc == slow)
    text.append(f"- Why this damping: at the slowest loading ({slow:g} crossings) Cu reads "
                + ", ".join(f"{_pct(e)} at damping {ff:g}" for ff, e in cu_slow) +
                " against the papers' schedule (papers' damping): in 3D the damping takes part "
                "in how the block fails, so away from the papers' damping Cu converges to "
                "another strength however slow the loading (docs/validation.md, '3D "
                "compression: how slow constant loading must be').")
    text += alternative_and_check(lat, s)
    pt = per_test_text(s, lat, by_name)
    if pt:
        text.append("- " + pt)
    sizes = sorted({s.n_elastic, s.n_strength, s.n_check})
    text.append(f"- Scope: 3D quartzite blocks of n_y = {', '.join(map(str, sizes))}, time "
                "step 0.1 sqrt(m/Kn) as in 2D.")
    return "\n".join(text)


def spread_text(lat: dict) -> str:
    """How far each quantity moves over the whole constant grid (max - min of the errors),
    against its tolerance."""
    spread = {}
    for q in QUANTITIES:
        vals = [e[q] for e in lat["grid"].values() if e.get(q) is not None]
        if vals:
            spread[q] = max(vals) - min(vals)
    calm = [q for q, x in spread.items() if x <= TOLERANCE[q]]
    return ("Spread of the errors over the whole grid (max - min, percentage points): " +
            ", ".join(f"{q} {100 * x:.3f}" for q, x in spread.items()) + "." +
            (f"  Within its tolerance at every setting of the grid: {', '.join(calm)}: "
             "there the loading hardly matters." if calm else ""))


def section_3d(L: list[str], s: Settings, lat: dict, V: dict, rel: str, img) -> None:
    """Part 4 (appended to ``L``): the 3D quartzite lattice; its figures go to ``img``."""
    add = L.append
    by_name = {r["name"]: r for r in lat["results"]}
    names = {"constant": "speed_error_constant_3d.png", "pareto": "speed_error_pareto_3d.png"}
    plot_constant(lat, img / names["constant"], default=package_defaults(s),
                  title="3D: constant schedule, error against loading rate and damping")
    plot_pareto(lat, img / names["pareto"], default=package_defaults(s),
                title="3D: error against cost, Pareto fronts, the papers' schedule")
    pe = lat["paper"]
    paper3 = PAPER_SCHEDULES[3]
    add("## 4. The 3D quartzite lattice: error against cost")
    add("")
    add(f"Blocks: elastic test n_y = {s.n_elastic} "
        f"({pe['elastic']['particles'] if 'elastic' in pe else '?'} elements), strength tests "
        f"n_y = {s.n_strength} ({pe['tension']['particles'] if 'tension' in pe else '?'} "
        "elements); rock: the 2017 paper's quartzite (the same values as the 2D quartz).  "
        f"The papers' 3D stepwise schedule (`stepwise`, alias `paper`; PAPER_SCHEDULES[3]: "
        f"{paper3['relax_steps']} relaxation steps at dt = {paper3['dt_fraction']:g} "
        "sqrt(m/Kn), steps of " + " / ".join(f"{paper3['step_size'][t]:g}" for t in TESTS) +
        " m for the elastic / tension / compression tests) against the constant schedule "
        "(dt = 0.1 sqrt(m/Kn)) over crossings x damping.")
    add("")
    add("**References and errors.**  E and nu: error against the closed-form formulas "
        "(docs/theory.md).  Tu and Cu: error against the strength the papers' stepwise "
        f"schedule measures at the same n_y, {converged_text(s, lat, by_name)}; that "
        "schedule runs at the papers' damping, which in 3D is part of the set-up.  The same "
        "tolerances (" + ", ".join(f"{q} {100 * TOLERANCE[q]:g}%" for q in QUANTITIES) +
        ") and the same rule as in 2D.")
    add("")
    add("### The papers' 3D stepwise schedule (reference points)")
    add("")
    paper_table(L, lat, "n_y", "elements")
    add("Its variants (relaxation steps x step size):")
    add("")
    stepwise_table(L, s, lat, by_name)
    add("### Constant speed in 3D: loading rate and damping")
    add("")
    add("Errors (E, nu against the formulas; Tu, Cu against the papers' schedule); **bold**: "
        "within the papers' accuracy.")
    add("")
    grid_tables(L, s, lat, by_name)
    add(spread_text(lat))
    add("")
    add(f"![3D constant schedule: error against crossings and damping]({rel}/{names['constant']})")
    add("")
    add("### 3D Pareto fronts: error against time steps")
    add("")
    front_tables(L, lat)
    add(f"![3D Pareto fronts]({rel}/{names['pareto']})")
    add("")
    recommendation_section(L, s, lat, V, by_name,
                           heading="### Recommended 3D defaults", text=recommendation_text_3d)
    add("**The defaults on the Pareto front.**  " + front_text(s, lat, by_name))
    add("")
