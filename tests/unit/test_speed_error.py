"""The pure functions of bonded_lattice.speed_error (no simulation; well under a second).

Pareto front, convergence-order fit, Verlet's discrete oscillator and its growth factor,
the bisection of a stability limit, the papers'-accuracy test and the recommendation rule,
each on synthetic data with a known answer.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bonded_lattice import speed_error


@pytest.fixture(scope="module")
def se():
    return speed_error


def test_pareto_front(se):
    #          0    1    2    3    4    5    6
    costs = [10, 20, 20, 30, 40, 5, 40]
    errors = [0.5, 0.2, 0.3, 0.25, 0.01, 0.9, 0.01]
    # 5 (cheapest), 0, 1 (beats 2 at equal cost), 4 (beats 3; 6 is its tie: first kept)
    assert se.pareto_front(costs, errors) == [5, 0, 1, 4]
    assert se.pareto_front([], []) == []
    # a single point that is best in both is the whole front
    assert se.pareto_front([3, 1, 2], [3.0, 1.0, 2.0]) == [1]


def test_convergence_order_exact_power_laws(se):
    dt = [1e-3 * 2.0**k for k in range(-3, 5)]
    p, c = se.convergence_order(dt, [3.0 * h**2 for h in dt])
    assert p == pytest.approx(2.0, abs=1e-12)
    assert c == pytest.approx(3.0, rel=1e-9)
    p, c = se.convergence_order(dt, [0.5 * h for h in dt])
    assert p == pytest.approx(1.0, abs=1e-12) and c == pytest.approx(0.5, rel=1e-9)
    assert se.local_orders(dt, [h**2 for h in dt]) == pytest.approx([2.0] * 7, abs=1e-12)


def test_convergence_order_with_a_kink_term(se):
    # e = dt^2 (1 + 0.3 (-1)^k): the alternating factor averages out of the least-squares
    # slope over an even number of points only approximately; the slope of the exact
    # alternation over 8 points is 2 + the fitted slope of log(1 +- 0.3) against k
    dt = np.array([1e-3 * 2.0**k for k in range(8)])
    alt = np.array([1.3 if k % 2 == 0 else 0.7 for k in range(8)])
    p, _ = se.convergence_order(dt, dt**2 * alt)
    k = np.arange(8)
    expected = 2.0 + np.polyfit(k, np.log(alt), 1)[0] / math.log(2.0)
    assert p == pytest.approx(expected, abs=1e-12)
    assert 1.8 < p < 2.0
    with pytest.raises(ValueError):
        se.convergence_order([1.0], [1.0])


def _recurrence(h: float, v0: float, k: float, n: int) -> np.ndarray:
    """Velocity Verlet for y'' = -k^2 y from y = 0, y' = v0, step by step."""
    dt = h / k
    y, v = 0.0, v0
    out = [y]
    for _ in range(n):
        a = -k * k * y
        y = y + v * dt + 0.5 * a * dt * dt
        v = v + 0.5 * (a - k * k * y) * dt
        out.append(y)
    return np.array(out)


@pytest.mark.parametrize("h", [0.05, 1.0, 1.9, 1.999, 2.0, 2.01, 2.5])
def test_verlet_oscillator_matches_the_recurrence(se, h):
    v0, k, n = -0.1, 15.938, 60
    exact = se.verlet_oscillator(np.arange(n + 1), h, v0, k)
    steps = _recurrence(h, v0, k, n)
    scale = np.abs(steps).max()
    assert np.abs(exact - steps).max() <= 1e-9 * scale
    if h < 2:
        # bounded: amplitude (v0/k)/sqrt(1 - h^2/4)
        assert np.abs(exact).max() <= abs(v0) / k / math.sqrt(1 - h * h / 4) * (1 + 1e-12)


def test_verlet_growth(se):
    assert se.verlet_growth(0.5) == 1.0
    assert se.verlet_growth(2.0) == 1.0       # marginal: linear, not exponential growth
    assert se.verlet_growth(2.5) == pytest.approx(4.0, rel=1e-12)   # (4.25 + 3.75) / 2
    # lambda + 1/lambda = h^2 - 2 for the growing root
    lam = se.verlet_growth(2.2)
    assert lam + 1 / lam == pytest.approx(2.2**2 - 2, rel=1e-12)


def test_bisect_limit(se):
    limit = 1 / math.sqrt(2)
    calls = []

    def stable(x):
        calls.append(x)
        return x < limit

    lo, hi = se.bisect_limit(stable, 0.5, 1.0, 1e-4)
    assert lo < limit <= hi and hi / lo - 1 <= 1e-4
    assert len(calls) <= 14        # log2(ln 2 / 1e-4) ~ 12.8 halvings (geometric midpoints)


def test_oscillator_stable(se):
    n = np.arange(2001)
    assert se.oscillator_stable(np.sin(0.3 * n), 2000)
    assert not se.oscillator_stable(np.sin(0.3 * n) * 1.001**n, 2000)     # grows 7x
    assert not se.oscillator_stable(np.sin(0.3 * n)[:500], 2000)           # stopped early
    # a bounded beat with its envelope maximum late still passes when several envelopes fit
    assert se.oscillator_stable(np.sin(np.pi * 0.999 * n) * np.abs(np.sin(0.01 * n)) + 1e-3,
                                2000)


def test_within(se):
    assert se.within(-0.0045, -0.004, 0.001)
    assert not se.within(-0.0025, -0.004, 0.001)   # closer to the formula, but not the paper
    assert se.within(0.0049, 0.0, 0.005) and not se.within(-0.0051, 0.0, 0.005)
    assert not se.within(None, 0.0, 1.0) and not se.within(float("nan"), 0.0, 1.0)


def test_recommend(se):
    tol = {"E": 0.001, "Cu": 0.005}
    paper = {"E": -0.0005, "Cu": 0.0}

    def cell(e, cu):
        return {"E": e, "Cu": cu}

    grid = {
        # damping 0.5: passes from 25 crossings on
        (12, 0.5): cell(-0.0005, 0.009), (25, 0.5): cell(-0.0005, 0.004),
        (50, 0.5): cell(-0.0005, 0.002), (100, 0.5): cell(-0.0005, 0.001),
        # damping 1: a lucky pass at 12, fails at 25 and 50, passes from 100 on
        (12, 1.0): cell(-0.0005, 0.001), (25, 1.0): cell(-0.0005, 0.007),
        (50, 1.0): cell(-0.0005, 0.006), (100, 1.0): cell(-0.0005, 0.004),
        (400, 1.0): cell(-0.0004, 0.001),
        # damping 4: E off everywhere
        (12, 4.0): cell(0.003, 0.0), (100, 4.0): cell(0.002, 0.0),
        # damping 0.25: passes everywhere, but has a failed run (None) at 100
        (12, 0.25): cell(-0.0005, 0.001), (100, 0.25): cell(None, 0.001),
    }
    got = se.recommend(grid, paper, tol)
    assert [(c, f) for c, f, _ in got] == [(25, 0.5), (100, 1.0)]
    # worst share of the allowance: Cu 0.004 / 0.005 in both
    assert got[0][2] == pytest.approx(0.8) and got[1][2] == pytest.approx(0.8)
    # ties in crossings go to the smaller worst share
    grid[(25, 2.0)] = cell(-0.0005, 0.001)
    grid[(100, 2.0)] = cell(-0.0005, 0.0)
    got = se.recommend(grid, paper, tol)
    assert [(c, f) for c, f, _ in got][:2] == [(25, 2.0), (25, 0.5)]
    assert got[0][2] == pytest.approx(0.2)
    assert se.recommend({}, paper, tol) == []


def test_case_names_are_distinct(se):
    Case = se.Case
    names = {c.name for c in se.lattice_cases(se.FULL)}
    assert len(names) == len(se.lattice_cases(se.FULL))
    assert Case("paper", "tension", 15,
                schedule="stepwise").name == "tension_n15_stepwise_r400_s1"
    assert Case("dt", "elastic", 30, dt_fraction=0.2).name == "elastic_n30_c100_f1_dt0.2"
    # exactly one papers' reference per test
    fams = [(c.family, c.test) for c in se.lattice_cases(se.FULL) if c.family == "paper"]
    assert sorted(fams) == [("paper", "compression"), ("paper", "elastic"), ("paper", "tension")]
