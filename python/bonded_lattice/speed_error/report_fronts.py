"""Part 2 of the speed-against-error report, second half: the Pareto fronts, the cheapest run
within each error level, the 10x verdict, and the lattice's largest stable time step."""

from __future__ import annotations

from .fitting import pareto_front, speedup, within
from .lattice_runs import points
from .settings import LEVELS, QUANTITIES, TEST_OF, TOLERANCE, Case, Settings, grid_case
from .text import cost as _cost
from .text import pct as _pct

def fronts_section(L: list[str], s: Settings, lat: dict, V: dict, by_name: dict[str, dict],
                   rel: str, names: dict[str, str]) -> None:
    """Appended to ``L``: the Pareto fronts, the error levels, the 10x verdict (``V``:
    :func:`~.report.verdict`) and the lattice's stability scan."""
    res, pe, grid, ls = lat["results"], lat["paper"], lat["grid"], lat["stability"]
    add = L.append
    # Pareto
    add("### Pareto fronts: error against time steps")
    add("")
    add("All runs of the main sweep, per quantity; a run is on the front when no other run is "
        "both cheaper (or as cheap) and at least as accurate.  Speed-up: the papers' schedule's "
        "time steps over the run's.  For E and nu the error against the formula contains the "
        "block's size effect (nu -0.4% at N = 30) that no loading removes, so a fast run whose "
        "loading error cancels part of it looks best there; the second table of each ranks "
        "the runs by their deviation from the papers' schedule instead (dashed in the plot).")
    add("")
    front_tables(L, lat)
    add(f"![Pareto fronts]({rel}/{names['pareto']})")
    add("")
    add("Cheapest run within a given error (E, nu against the formulas, Tu, Cu against the "
        "papers' schedule), with its speed-up over the papers' schedule:")
    add("")
    add("| |error| <= | " + " | ".join(QUANTITIES) + " |")
    add("|---|" + "---|" * len(QUANTITIES))
    for lev in LEVELS:
        cells = []
        for q in QUANTITIES:
            pts = [p for p in points(res, q) if abs(p["errors"][q]) <= lev]
            if not pts or TEST_OF[q] not in lat["paper"]:
                cells.append("none")
                continue
            b = min(pts, key=lambda p: p["steps"])
            cells.append(f"{Case(**b['case']).label()}: {b['steps']} steps "
                         f"({speedup(lat['paper'][TEST_OF[q]]['steps'], b['steps']):.0f}x)")
        add(f"| {100 * lev:g}% | " + " | ".join(cells) + " |")
    add("")

    # 10x verdict
    add("### At least 10x fewer time steps than the papers' schedule?")
    add("")
    for q, v in V.items():
        n_all = len(points(res, q))
        if v["cheap"]:
            names_ = "; ".join(f"{Case(**p['case']).label()} ({p['steps']} steps, "
                               f"{_pct(p['errors'][q])})" for p in v["cheap"][:6])
            more = f" and {len(v['cheap']) - 6} more" if len(v["cheap"]) > 6 else ""
            add(f"- **{q}: yes.**  {len(v['cheap'])} of {n_all} runs reach the papers' accuracy "
                f"with at most {v['paper_steps'] // 10} steps (1/10 of {v['paper_steps']}); "
                f"cheapest first: {names_}{more}.")
        else:
            add(f"- **{q}: no.**  No run with at most {v['paper_steps'] // 10} steps reaches "
                "the papers' accuracy.")
    both = []
    for (c, f), errs in sorted(grid.items()):
        if all(within(errs.get(q), lat["paper_err"][q], TOLERANCE[q]) for q in QUANTITIES):
            steps = {t: by_name.get(grid_case(s, t, c, f).name) for t in pe}
            if all(r and r["steps"] * 10 <= pe[t]["steps"] for t, r in steps.items()):
                both.append((c, f, min(pe[t]["steps"] / r["steps"] for t, r in steps.items())))
    add("")
    if both:
        add("Constant-speed settings that keep **all four** quantities at the papers' accuracy "
            "with at least 10x fewer steps in every test (crossings, damping, smallest speed-up "
            "over the three tests): " + "; ".join(f"({c:g}, {f:g}, {x:.0f}x)" for c, f, x in both)
            + ".")
    else:
        add("No constant-speed setting keeps all four quantities at the papers' accuracy with "
            "10x fewer steps in every test.")
    add("")
    add("### Largest stable time step of the lattice")
    add("")
    add(f"Elastic test, N = {ls['rows'][0]['case']['n']}, 100 crossings, damping 1, time step "
        "scanned beyond the decks' 0.1 sqrt(m/Kn) (plan_test caps dt_scale at 2; the script "
        "rescales the plan), then bisected.  Unstable: LAMMPS stops (lost atoms) or E is off "
        "by more than 5%.")
    add("")
    add("| dt / sqrt(m/Kn) | time steps | E error | nu error | peak kinetic energy (J/m) | "
        "outcome |")
    add("|---|---|---|---|---|---|")
    for r in ls["rows"]:
        ok = r["ok"] and abs(r["errors"]["E"]) < 0.05
        add(f"| {r['case']['dt_fraction']:g} | {r['steps']} | "
            f"{_pct(r['errors'].get('E')) if r['ok'] else ''} | "
            f"{_pct(r['errors'].get('nu')) if r['ok'] else ''} | "
            f"{r.get('ke_max', float('nan')):.3g} | "
            f"{'stable' if ok else 'unstable: ' + (r['error'] or 'E off')[:60]} |")
    add("")
    if ls["stable"] is not None:
        add(f"Largest stable: **{ls['stable']:.3f} sqrt(m/Kn)** (unstable at {ls['unstable']}).  "
            f"`conversion.critical_time_step` gives the sufficient bound sqrt(2 m/(z k)) with "
            f"z = 6, k = max(Kn, Ks): {ls['formula']:.3f} sqrt(m/Kn) (0.71-0.87 of the periodic "
            f"lattice's exact limit, i.e. that limit is "
            f"{ls['formula'] / 0.87:.2f}-{ls['formula'] / 0.71:.2f} sqrt(m/Kn)); the measured "
            "limit, with the platens' 2 Kn springs and the damping, is inside that range.  "
            "Below it E and nu do not change with dt (second-order error, far below the size "
            "effect).  A single spring to a fixed particle (part 1) allows 2 sqrt(m/Kn).")
    add("")
    add(f"![lattice time step]({rel}/{names['lattice_dt']})")
    add("")


def front_tables(L: list[str], lat: dict) -> None:
    """Per quantity, the Pareto front of all runs of the main sweep (error against the
    quantity's reference; for E and nu also the front of the deviation from the papers'
    schedule), appended to ``L``."""
    add, res = L.append, lat["results"]
    for q in QUANTITIES:
        pts = points(res, q)
        if not pts:
            continue
        ps = lat["paper"][TEST_OF[q]]["steps"] if TEST_OF[q] in lat["paper"] else None
        front = [pts[i] for i in pareto_front([p["steps"] for p in pts],
                                              [abs(p["errors"][q]) for p in pts])]
        add(f"**{q}**" + (" (error against the formula)" if q in ("E", "nu") else ""))
        add("")
        add("| setting | time steps | particle-steps | wall (s) | error | speed-up | "
            "papers' accuracy |")
        add("|---|---|---|---|---|---|---|")
        if q in ("E", "nu"):
            # the front of the loading error, |error - papers' error|, below it
            dev = [pts[i] for i in pareto_front(
                [p["steps"] for p in pts],
                [abs(p["errors"][q] - lat["paper_err"][q]) for p in pts])]
            front = front + [None] + dev
        for p in front:
            if p is None:
                add("")
                add(f"**{q}** (deviation from the papers' schedule, |error - "
                    f"({_pct(lat['paper_err'][q], 3)})|: the loading's own error, without "
                    "the block's size effect; the column shows the error against the formula)")
                add("")
                add("| setting | time steps | particle-steps | wall (s) | error | speed-up | "
                    "papers' accuracy |")
                add("|---|---|---|---|---|---|---|")
                continue
            add(f"| {Case(**p['case']).label()} | {_cost(p)} | {_pct(p['errors'][q], 3)} | "
                f"{speedup(ps, p['steps']):.1f}x | "
                f"{'yes' if within(p['errors'][q], lat['paper_err'][q], TOLERANCE[q]) else 'no'} |"
                if ps else "")
        add("")
