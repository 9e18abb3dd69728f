"""The pure functions of the speed-against-error study (tested by
tests/unit/test_speed_error.py): Pareto front, convergence order, Verlet's discrete harmonic
oscillator and its growth factor, the bisection of a stability limit, the stability test of
an oscillator run, the papers'-accuracy test and the recommendation rule."""

from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np

def pareto_front(costs: Sequence[float], errors: Sequence[float]) -> list[int]:
    """Indices of the non-dominated points, by increasing cost (and decreasing error).

    A point is dominated when another costs no more and errs no more, and is better in
    one of the two.  Of points with equal cost and error the first is kept.
    """
    order = sorted(range(len(costs)), key=lambda i: (costs[i], errors[i], i))
    front: list[int] = []
    best = math.inf
    for i in order:
        if errors[i] < best:
            front.append(i)
            best = errors[i]
    return front


def convergence_order(steps: Sequence[float], errors: Sequence[float]) -> tuple[float, float]:
    """Least-squares fit error = C step^p in log-log: returns (p, C)."""
    x, y = np.log(np.asarray(steps, float)), np.log(np.asarray(errors, float))
    if len(x) < 2:
        raise ValueError("a convergence order needs at least two points")
    p, logc = np.polyfit(x, y, 1)
    return float(p), float(math.exp(logc))


def local_orders(steps: Sequence[float], errors: Sequence[float]) -> list[float]:
    """log(e_i+1 / e_i) / log(dt_i+1 / dt_i) between neighbours."""
    return [math.log(errors[i + 1] / errors[i]) / math.log(steps[i + 1] / steps[i])
            for i in range(len(steps) - 1)]


def verlet_oscillator(n: np.ndarray, h: float, v0: float, k: float) -> np.ndarray:
    """Positions y_n of velocity Verlet for y'' = -k^2 y, y_0 = 0, y'_0 = v0, h = k dt.

    y_1 = v0 dt and y_n+1 = (2 - h^2) y_n - y_n-1, so y_n = v0 dt sin(n th)/sin(th) with
    cos th = 1 - h^2/2 for h < 2 (an oscillation of amplitude v0/k / sqrt(1 - h^2/4)),
    y_n = v0 dt n (-1)^(n+1) at h = 2, and y_n = v0 dt (-1)^(n+1) sinh(n ph)/sinh(ph) with
    cosh ph = h^2/2 - 1 beyond: growth by |lambda| = h^2/2 - 1 + sqrt((h^2/2 - 1)^2 - 1)
    per step.
    """
    n = np.asarray(n, float)
    dt = h / k
    c = 1.0 - 0.5 * h * h
    if c > -1.0:
        th = math.acos(c)
        return v0 * dt * np.sin(n * th) / math.sin(th)
    if c == -1.0:
        return v0 * dt * n * (-1.0) ** (n + 1)
    ph = math.acosh(-c)
    return v0 * dt * (-1.0) ** (n + 1) * np.sinh(n * ph) / math.sinh(ph)


def verlet_growth(h: float) -> float:
    """Largest |eigenvalue| of Verlet's step for a harmonic oscillator (1: stable)."""
    c = 0.5 * h * h - 1.0
    return 1.0 if c <= 1.0 else c + math.sqrt(c * c - 1.0)


def bisect_limit(stable: Callable[[float], bool], lo: float, hi: float, rel: float,
                 max_iter: int = 60) -> tuple[float, float]:
    """Narrow [lo, hi] (stable(lo) true, stable(hi) false) to hi/lo - 1 <= rel."""
    for _ in range(max_iter):
        if hi / lo - 1.0 <= rel:
            break
        mid = math.sqrt(lo * hi)
        if stable(mid):
            lo = mid
        else:
            hi = mid
    return lo, hi


def within(error: float | None, paper_error: float, tol: float) -> bool:
    """Whether an error reaches the papers' accuracy: |e - e_paper| <= tol."""
    return error is not None and math.isfinite(error) and abs(error - paper_error) <= tol


def recommend(grid: dict[tuple[float, float], dict[str, float | None]],
              paper_errors: dict[str, float], tolerance: dict[str, float]
              ) -> list[tuple[float, float, float]]:
    """Constant-schedule settings that keep every quantity at the papers' accuracy, best first.

    grid: {(crossings, damping): {quantity: error}}.  A damping qualifies from crossings c on
    when every quantity is within tolerance at c and at every slower setting of the grid with
    that damping (so a lucky fast point next to a failing slower one does not count).  The
    candidates are (crossings, damping, worst) sorted by crossings (the cost: time steps grow
    in proportion), then by the worst use of the tolerance, max_q |e_q - e_paper,q| / tol_q.
    """
    def ok(c: float, f: float) -> bool:
        errs = grid.get((c, f))
        return errs is not None and all(within(errs.get(q), paper_errors[q], tolerance[q])
                                        for q in tolerance)

    def worst(c: float, f: float) -> float:
        errs = grid[(c, f)]
        return max(abs(errs[q] - paper_errors[q]) / tolerance[q] for q in tolerance)

    out = []
    for f in sorted({f for _, f in grid}):
        cs = sorted(c for c, g in grid if g == f)
        start = None
        for c in reversed(cs):          # from the slowest down, as long as all pass
            if not ok(c, f):
                break
            start = c
        if start is not None:
            out.append((start, f, worst(start, f)))
    return sorted(out, key=lambda t: (t[0], t[2]))


def worst_share(errors: dict[str, float | None], paper_errors: dict[str, float],
                tolerance: dict[str, float]) -> float | None:
    """The largest use of the tolerance, max_q |e_q - e_paper,q| / tol_q (None when a
    quantity is missing or not finite)."""
    shares = []
    for q, tol in tolerance.items():
        e = errors.get(q)
        if e is None or not math.isfinite(e):
            return None
        shares.append(abs(e - paper_errors[q]) / tol)
    return max(shares)


def robust_shares(grid: dict[tuple[float, float], dict[str, float | None]],
                  paper_errors: dict[str, float], tolerance: dict[str, float]
                  ) -> dict[tuple[float, float], float | None]:
    """Per grid setting (crossings, damping): :func:`worst_share` at that setting and every
    slower one of the grid with the same damping (the quantity :func:`recommend` asks to be
    <= 1); None when one of them has a missing quantity."""
    out: dict = {}
    for (c, f) in grid:
        shares = [worst_share(grid[(cc, ff)], paper_errors, tolerance)
                  for (cc, ff) in grid if ff == f and cc >= c]
        out[(c, f)] = None if any(x is None for x in shares) else max(shares)
    return out


def grid_front(costs: dict[tuple[float, float], float],
               errors: dict[tuple[float, float], float | None]) -> list[tuple[float, float]]:
    """The settings on the Pareto front of cost against error (settings without an error
    left out), by increasing cost."""
    keys = [k for k in costs if errors.get(k) is not None]
    front = pareto_front([costs[k] for k in keys], [errors[k] for k in keys])
    return [keys[i] for i in front]


def speedup(paper_steps: float, steps: float) -> float:
    return paper_steps / steps if steps > 0 else math.inf



def oscillator_stable(y: np.ndarray, t_end_steps: int) -> bool:
    """Stable: the run reached its end (|y| stayed below 100 m) and its second half swings
    no wider than twice its first.  Near h = 2 a stable run beats with an envelope of period
    about pi / (2 sqrt(1 - h^2/4)) steps, so the run must be many envelopes long."""
    if len(y) < t_end_steps + 1:
        return False
    half = len(y) // 2
    return bool(np.abs(y[half:]).max() <= 2.0 * np.abs(y[:half]).max())
