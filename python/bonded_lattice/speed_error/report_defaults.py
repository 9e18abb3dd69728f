"""What the speed-against-error report says about its references and the package's defaults,
computed from the runs (2D and 3D alike): how converged the papers'-schedule reference is,
whether the default setting lies on the Pareto front, and per test kind the cheapest setting
that the recommendation rule would accept."""

from __future__ import annotations

from .fitting import grid_front, pareto_front, recommend, robust_shares, worst_share
from .lattice_runs import points
from .settings import QUANTITIES, TEST_OF, TOLERANCE, Case, Settings, grid_case, paper_relax
from .text import pct as _pct

TESTS = ("elastic", "tension", "compression")
# a reference is called converged when its own loading error, estimated from its variants
# with 4x fewer relaxation steps or 4x larger loading steps (both 4x cheaper), is at most this:
# a fifth of the strengths' tolerance (0.5%).  If the error falls at least in proportion to
# the relaxation time and the step size, a variant 4x coarser errs at least 4x as much, so
# the reference's own error is at most 1/(4 - 1) of the variants' deviation from it.
CONVERGED_WITHIN = 0.001
COARSER_BY = 4.0


def reference_variants(s: Settings) -> list[tuple[int, float]]:
    """(relax steps, step factor) of the stepwise variants one factor 4 cheaper than the
    papers' schedule: 4x fewer relaxation steps, or 4x larger steps (those in ``s``)."""
    paper = paper_relax(s.dim)
    wanted = [(paper // 4, 1.0), (paper, 4.0)]
    return [(r, f) for r, f in wanted if r in s.relax and f in s.step_factors]


def reference_convergence(s: Settings, lat: dict, by_name: dict[str, dict]
                          ) -> dict[str, float | None]:
    """Per quantity: the largest |measured by a variant / measured by the papers' schedule - 1|
    over :func:`reference_variants` (None if a variant is missing or failed)."""
    out: dict[str, float | None] = {}
    for q in QUANTITIES:
        test = TEST_OF[q]
        paper = lat["paper"].get(test)
        devs = []
        for r_, f in reference_variants(s):
            n = s.n_elastic if test == "elastic" else s.n_strength
            r = by_name.get(Case("stepwise", test, n, schedule="stepwise", relax_steps=r_,
                                 step_factor=f, dim=s.dim).name)
            if r is None or not r["ok"] or paper is None:
                devs.append(None)
                continue
            key = q if q in ("E", "nu") else "strength"
            devs.append(abs(r[key] / paper[key] - 1.0))
        out[q] = None if not devs or any(d is None for d in devs) else max(devs)
    return out


def converged_text(s: Settings, lat: dict, by_name: dict[str, dict], short: bool = False) -> str:
    """Whether the Tu, Cu reference is converged, in words, from
    :func:`reference_convergence` (``short``: one bracket of numbers)."""
    conv = reference_convergence(s, lat, by_name)
    dev = [conv[q] for q in ("Tu", "Cu")]
    variants = " or ".join(f"{r} relaxation steps" if f == 1 else f"{f:g}x larger steps"
                           for r, f in reference_variants(s))
    if any(d is None for d in dev) or not variants:
        return "its convergence was not measured (a variant is missing)"
    worst = max(dev)
    own = worst / (COARSER_BY - 1.0)
    nums = ", ".join(f"{q} {100 * conv[q]:.3f}%" for q in ("Tu", "Cu"))
    measured = (f"the same schedule made {COARSER_BY:g}x cheaper, with {variants}, measures the "
                f"strengths within {nums} of it; if the error falls at least in proportion to "
                "the relaxation time and the step size, the reference's own is at most "
                f"1/{COARSER_BY - 1:g} of that, {100 * own:.3f}%")
    if short:
        return (f"{'a converged reference' if own <= CONVERGED_WITHIN else 'NOT converged'} "
                f"(its {COARSER_BY:g}x cheaper variants within {nums}, so its own error "
                f"<= {100 * own:.3f}%)")
    if own <= CONVERGED_WITHIN:
        return (f"a converged reference: {measured}, within {100 * CONVERGED_WITHIN:g}% (a "
                "fifth of the strengths' tolerance)")
    return f"NOT a converged reference to {100 * CONVERGED_WITHIN:g}%: {measured}"


def setting_costs(s: Settings, lat: dict, by_name: dict[str, dict]
                  ) -> dict[tuple[float, float], float]:
    """Per grid setting: the time steps of its three tests together (settings with a missing
    run left out)."""
    out = {}
    for (c, f) in lat["grid"]:
        runs = [by_name.get(grid_case(s, t, c, f).name) for t in TESTS]
        if all(runs):
            out[(c, f)] = float(sum(r["steps"] for r in runs))
    return out


def package_defaults(s: Settings) -> dict[str, tuple[float, float]]:
    """The package's (crossings, damping) of each test kind in this dimension."""
    return {t: (s.default_for(t)["crossings"], s.default_for(t)["damping"]) for t in TESTS}


def test_tolerance(test: str) -> dict[str, float]:
    """The tolerances of the quantities ``test`` measures (elastic: E and nu)."""
    return {q: TOLERANCE[q] for q in QUANTITIES if TEST_OF[q] == test}


def default_on_fronts(s: Settings, lat: dict, by_name: dict[str, dict],
                      default: tuple[float, float] | dict[str, tuple[float, float]] | None = None
                      ) -> dict:
    """Where the package's defaults (:func:`package_defaults`, or ``default``: one
    (crossings, damping) for every test, or one per test kind) stand among the constant
    grid's settings.

    joint: cost (time steps of the three tests together) against the largest share of the
    tolerance used at the setting and at every slower one of its damping (what the
    recommendation rule bounds; for per-test defaults, each test's quantities at its own
    setting); the defaults are on the front when no grid setting is at least as cheap and as
    accurate and better in one.  Per quantity: the front of the main sweep's runs of time
    steps against the deviation from the reference's measurement, |error - error of the
    papers' schedule| (for Tu and Cu the error itself).
    """
    if default is None:
        defaults = package_defaults(s)
    elif isinstance(default, tuple):
        defaults = {t: default for t in TESTS}
    else:
        defaults = default
    grid = lat["grid"]
    costs = setting_costs(s, lat, by_name)
    robust = robust_shares(grid, lat["paper_err"], TOLERANCE)
    front = grid_front(costs, robust)
    in_grid = all(defaults[t] in grid for t in TESTS)
    cost = share = None
    on_front = False
    if in_grid:
        runs = [by_name.get(grid_case(s, t, *defaults[t]).name) for t in TESTS]
        shares = [robust_shares(grid, lat["paper_err"], test_tolerance(t))[defaults[t]]
                  for t in TESTS]
        if all(runs) and all(x is not None for x in shares):
            cost, share = float(sum(r["steps"] for r in runs)), max(shares)
            on_front = not any(
                costs[k] <= cost and robust[k] <= share and (costs[k] < cost or robust[k] < share)
                for k in costs if robust.get(k) is not None)
    per_q: dict[str, bool | None] = {}
    for q in QUANTITIES:
        runs = points(lat["results"], q)
        mine = by_name.get(grid_case(s, TEST_OF[q], *defaults[TEST_OF[q]]).name)
        if mine is None or mine not in runs:
            per_q[q] = None
            continue
        dev = [abs(r["errors"][q] - lat["paper_err"][q]) for r in runs]
        k = runs.index(mine)
        # on the front: no run at least as cheap and as close and better in one
        per_q[q] = not any(r["steps"] <= mine["steps"] and dev[i] <= dev[k] and
                           (r["steps"] < mine["steps"] or dev[i] < dev[k])
                           for i, r in enumerate(runs))
    return {"defaults": defaults, "in_grid": in_grid, "costs": costs, "robust": robust,
            "front": front, "cost": cost, "share": share, "on_front": on_front,
            "per_quantity": per_q}


def defaults_words(defaults: dict[str, tuple[float, float]]) -> str:
    """Per-test defaults in words: one setting, or the crossings per test at one damping."""
    settings = set(defaults.values())
    if len(settings) == 1:
        c, f = next(iter(settings))
        return f"{c:g} crossings, damping {f:g}"
    dampings = {f for _, f in settings}
    if len(dampings) == 1:
        return (", ".join(f"{t} {c:g}" for t, (c, _) in defaults.items()) +
                f" crossings, damping {next(iter(dampings)):g}")
    return ", ".join(f"{t} {c:g} crossings at damping {f:g}" for t, (c, f) in defaults.items())


def front_text(s: Settings, lat: dict, by_name: dict[str, dict]) -> str:
    """The defaults' place on the Pareto fronts (:func:`default_on_fronts`), in words."""
    d = default_on_fronts(s, lat, by_name)
    name = f"The package's {s.dim}D defaults ({defaults_words(d['defaults'])})"
    if not d["in_grid"] or d["share"] is None:
        return f"{name} are not settings of this grid."
    front = "; ".join(f"{cc:g}/{ff:g} ({d['costs'][(cc, ff)]:.3g} steps, "
                      f"{d['robust'][(cc, ff)]:.2f})" for cc, ff in d["front"])
    per_q = ", ".join(f"{q} {'yes' if on else 'no' if on is not None else 'not measured'}"
                      for q, on in d["per_quantity"].items())
    return (f"{name} are **{'on' if d['on_front'] else 'NOT on'}** the Pareto front of the "
            f"grid's settings ({d['cost']:.3g} time steps, {d['share']:.2f} of the tolerance "
            "used): cost (time steps of the three tests together) against the largest share "
            "of the tolerance used at the setting and every slower one of its damping (the "
            f"recommendation rule's measure; the grid's front, crossings/damping (steps, "
            f"share): {front}).  One setting per test serves that test's quantities, so on "
            "the per-quantity fronts of all runs (time steps against the deviation from the "
            "papers' schedule) its own runs lie only where that quantity sets the pace: "
            f"{per_q}." + chosen_note(lat, d))


def chosen_note(lat: dict, d: dict) -> str:
    """When the recommended single setting is not on the grid's front: the settings that
    beat it on the grid's blocks, and how they fared in the transfer check."""
    if not lat.get("chosen") or tuple(lat["chosen"]) in d["front"]:
        return ""
    key = tuple(lat["chosen"])
    if key not in d["costs"] or d["robust"].get(key) is None:
        return ""
    checks = {(x["crossings"], x["damping"]): x for x in lat["checks"]}
    better = [k for k in d["front"] if d["costs"][k] <= d["costs"][key] and
              d["robust"][k] <= d["robust"][key]]
    words = []
    for k in better:
        ch = checks.get(k)
        words.append(f"{k[0]:g}/{k[1]:g}" + (
            "" if ch is None else
            " (transfer check " + ("passed" if ch["passed"] else "FAILED: " + ", ".join(
                f"{q} {_pct(e)}" for q, e in ch["errors"].items())) + ")"))
    return (f"  The recommended single setting {key[0]:g}/{key[1]:g} (share "
            f"{d['robust'][key]:.2f}) is not on the grid's own front: on the grid's blocks "
            f"{'; '.join(words)} {'is' if len(words) == 1 else 'are'} as cheap and more "
            "accurate; the rule takes the first candidate that also passes the transfer check.")


def per_test_settings(s: Settings, lat: dict, damping: float | None = None
                      ) -> dict[str, tuple[float, float, float] | None]:
    """Per test kind: the first candidate of :func:`recommend` on that test's quantities
    alone (elastic: E and nu), among the grid's settings at ``damping`` if given; or None."""
    grid = {k: v for k, v in lat["grid"].items() if damping is None or k[1] == damping}
    out = {}
    for t in TESTS:
        cands = recommend(grid, lat["paper_err"], test_tolerance(t))
        out[t] = cands[0] if cands else None
    return out


def per_test_text(s: Settings, lat: dict, by_name: dict[str, dict]) -> str:
    """Per test kind, the rule on that test's quantities alone at the recommended damping,
    what it saves against the one recommended setting, and the package's per-test
    defaults."""
    if not lat["chosen"]:
        return ""
    c, f = lat["chosen"]
    parts = []
    for t, cand in per_test_settings(s, lat, damping=f).items():
        one = by_name.get(grid_case(s, t, c, f).name)
        if cand is None or one is None:
            parts.append(f"{t}: none")
            continue
        own = by_name.get(grid_case(s, t, cand[0], cand[1]).name)
        parts.append(f"{t} {cand[0]:g} crossings" + (
            " (the same)" if own is one else f" ({own['steps']} time steps against "
            f"{one['steps']}, {one['steps'] / own['steps']:.1f}x fewer)"))
    pkg = package_defaults(s)
    wanted = {t: (cand[0], cand[1]) for t, cand in per_test_settings(s, lat, damping=f).items()
              if cand is not None}
    same = all(pkg[t] == wanted.get(t) for t in TESTS)
    return ("Per test kind, the same rule on that test's quantities alone at damping "
            f"{f:g} (cheapest setting that holds them at every slower one): " +
            "; ".join(parts) + f".  The package's {s.dim}D defaults per test "
            f"(`schedules.default_loading`: {defaults_words(pkg)}) "
            f"{'are these' if same else 'DIFFER from these'}.")


def errors_text(lat: dict, key: tuple[float, float]) -> str:
    """The four errors at a grid setting."""
    errs = lat["grid"].get(key, {})
    return ", ".join(f"{q} {_pct(errs.get(q))}" for q in QUANTITIES)
