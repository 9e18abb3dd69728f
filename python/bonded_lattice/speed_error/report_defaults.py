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
# a reference is called converged when its variants with 4x fewer relaxation steps or 4x
# larger loading steps, both 4x cheaper, measure the same strengths to within this: less than
# half the strengths' tolerance (0.5%), so the reference's own loading error, smaller than its
# coarser variants', uses at most a fraction of it
CONVERGED_WITHIN = 0.002


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


def converged_text(s: Settings, lat: dict, by_name: dict[str, dict]) -> str:
    """Whether the Tu, Cu reference is converged, in words, from
    :func:`reference_convergence`."""
    conv = reference_convergence(s, lat, by_name)
    dev = [conv[q] for q in ("Tu", "Cu")]
    variants = " or ".join(f"{r} relaxation steps" if f == 1 else f"{f:g}x larger steps"
                           for r, f in reference_variants(s))
    if any(d is None for d in dev) or not variants:
        return "its convergence was not measured (a variant is missing)"
    worst = max(dev)
    nums = ", ".join(f"{q} {100 * conv[q]:.3f}%" for q in ("Tu", "Cu"))
    if worst <= CONVERGED_WITHIN:
        return (f"a converged reference: the same schedule made 4x cheaper, with {variants}, "
                f"measures the same strengths to within {nums} (<= {100 * CONVERGED_WITHIN:g}%, "
                "under half the strengths' tolerance; the reference's own error is smaller "
                "than its coarser variants')")
    return (f"NOT a converged reference to {100 * CONVERGED_WITHIN:g}%: the same schedule with "
            f"{variants} differs by {nums}")


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


def default_on_fronts(s: Settings, lat: dict, by_name: dict[str, dict],
                      default: tuple[float, float] | None = None) -> dict:
    """Where the package's default (``s.default``, or ``default`` = (crossings, damping))
    stands among the constant grid's settings.

    joint: the Pareto front of the three tests' time steps against the largest share of the
    tolerance used at the setting and at every slower one of its damping (what the
    recommendation rule bounds); per quantity: the front of the main sweep's runs of time
    steps against the deviation from the reference's measurement, |error - error of the
    papers' schedule| (for Tu and Cu the error itself).
    """
    key = default if default is not None else (s.default["crossings"], s.default["damping"])
    costs = setting_costs(s, lat, by_name)
    robust = robust_shares(lat["grid"], lat["paper_err"], TOLERANCE)
    front = grid_front(costs, robust)
    per_q: dict[str, bool | None] = {}
    for q in QUANTITIES:
        runs = points(lat["results"], q)
        mine = by_name.get(grid_case(s, TEST_OF[q], *key).name)
        if mine is None or mine not in runs:
            per_q[q] = None
            continue
        dev = [abs(r["errors"][q] - lat["paper_err"][q]) for r in runs]
        idx = pareto_front([r["steps"] for r in runs], dev)
        # a run tied with a front run (same cost and deviation) counts as on the front
        on = any(runs[i] is mine or (runs[i]["steps"] == mine["steps"] and
                                     dev[i] == dev[runs.index(mine)]) for i in idx)
        per_q[q] = on
    return {"default": key, "in_grid": key in lat["grid"], "costs": costs, "robust": robust,
            "front": front, "on_front": key in front, "per_quantity": per_q,
            "share": worst_share(lat["grid"].get(key, {}), lat["paper_err"], TOLERANCE)
            if key in lat["grid"] else None}


def front_text(s: Settings, lat: dict, by_name: dict[str, dict]) -> str:
    """The default's place on the Pareto fronts (:func:`default_on_fronts`), in words."""
    d = default_on_fronts(s, lat, by_name)
    c, f = d["default"]
    name = f"The package's {s.dim}D default ({c:g} crossings, damping {f:g})"
    if not d["in_grid"]:
        return f"{name} is not a setting of this grid."
    front = "; ".join(f"{cc:g}/{ff:g} ({d['costs'][(cc, ff)]:.3g} steps, "
                      f"{d['robust'][(cc, ff)]:.2f})" for cc, ff in d["front"])
    per_q = ", ".join(f"{q} {'yes' if on else 'no' if on is not None else 'not measured'}"
                      for q, on in d["per_quantity"].items())
    return (f"{name} is **{'on' if d['on_front'] else 'NOT on'}** the Pareto front of the "
            f"grid's settings, cost (time steps of the three tests together) against the "
            f"largest share of the tolerance used at the setting and every slower one of its "
            f"damping (the recommendation rule's measure; the front, crossings/damping (steps, "
            f"share): {front}).  One setting serves all four quantities, so on the "
            "per-quantity fronts of all runs (time steps against the deviation from the "
            "papers' schedule) its own runs lie only where that quantity sets the pace: "
            f"{per_q}.")


def per_test_settings(s: Settings, lat: dict) -> dict[str, tuple[float, float, float] | None]:
    """Per test kind: the first candidate of :func:`recommend` on that test's quantities
    alone (elastic: E and nu), or None."""
    out = {}
    for t in TESTS:
        tol = {q: TOLERANCE[q] for q in QUANTITIES if TEST_OF[q] == t}
        cands = recommend(lat["grid"], lat["paper_err"], tol)
        out[t] = cands[0] if cands else None
    return out


def per_test_text(s: Settings, lat: dict, by_name: dict[str, dict]) -> str:
    """What a per-test-kind default would save against the one recommended setting."""
    if not lat["chosen"]:
        return ""
    c, f = lat["chosen"]
    parts = []
    for t, cand in per_test_settings(s, lat).items():
        one = by_name.get(grid_case(s, t, c, f).name)
        if cand is None or one is None:
            parts.append(f"{t}: none")
            continue
        own = by_name.get(grid_case(s, t, cand[0], cand[1]).name)
        parts.append(f"{t}: {cand[0]:g} crossings, damping {cand[1]:g} ({own['steps']} steps "
                     f"against {one['steps']}, {one['steps'] / own['steps']:.1f}x fewer)")
    return ("Per test kind, the same rule on that test's quantities alone (cheapest setting "
            "that holds them at every slower setting of its damping): " + "; ".join(parts) +
            ".")


def errors_text(lat: dict, key: tuple[float, float]) -> str:
    """The four errors at a grid setting."""
    errs = lat["grid"].get(key, {})
    return ", ".join(f"{q} {_pct(errs.get(q))}" for q in QUANTITIES)
