"""Part 2 of the speed-against-error study: the lattice runs (one :class:`SpeedErrorRun`
per :class:`~bonded_lattice.speed_error.settings.Case`, cached as ``result.json``), their
errors, the lattice's stability scan, the references, the recommendation and its check on
another block size."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import numpy as np

from ..analysis import STRENGTH_WINDOW, _elastic_window, measure
from ..conversion import critical_time_step, lattice_mass, rock_to_bond
from ..decks import write_deck
from ..experiment import THERMO_LINES, RockTest, RunPlan
from ..lattice import Lattice
from ..rocks import Rock, get_rock
from ..runner import RunResult
from ..schedules import DEFAULT_DT_FRACTION, PAPER_SCHEDULES
from .fitting import recommend, within
from .settings import (QUANTITIES, ROCK_OF, TEST_OF, TOLERANCE, Case, Settings, lattice_cases,
                       paper_relax)

_LOOP = re.compile(r"Loop time of (\S+) on \d+ procs for (\d+) steps")


def case_folder(case: Case, out: Path) -> Path:
    """The run folder of ``case``: ``out/lattice/<family>/<name>`` (2D) or
    ``out/lattice3d/<family>/<name>`` (3D)."""
    return out / ("lattice" if case.dim == 2 else f"lattice{case.dim}d") / case.family / case.name


class SpeedErrorRun(RockTest):
    """One lattice run of the study: a 2D quartz or 3D quartzite (``case.dim``)
    :class:`~bonded_lattice.experiment.RockTest` on one rank in :func:`case_folder`, without
    pictures, whose result
    (:func:`run_record`, ``result.json``) records a failed run instead of raising.

    plan: :func:`~bonded_lattice.experiment.plan_test` with the case's schedule, then with
    ``dt_fraction`` any time step (plan_test limits dt_scale to 2: the same loading, the
    steps rescaled).  execute: a strength run that ``fix halt`` stopped prematurely
    (:func:`premature_halt`) is run again without the halt.  ``run(reuse=True)`` keeps a
    stored result of the same case that is not such a premature halt (marked ``cached``).
    """

    summary_file = "result.json"
    json_indent = 1

    def __init__(self, case: Case, out: Path) -> None:
        options: dict = {"damping": case.damping}
        if case.schedule == "stepwise":
            step = PAPER_SCHEDULES[case.dim]["step_size"][case.test]
            options.update(schedule="stepwise", relax_steps=case.relax_steps,
                           step_size=case.step_factor * step)
        else:
            options.update(crossings=case.crossings)
        super().__init__(get_rock(ROCK_OF[case.dim]), case.dim, case.test, case.n,
                         case_folder(case, out), np_=1, d=1.0e-3,
                         progress=False, pictures=False, **options)
        self.case = case

    def _plan(self) -> None:
        super()._plan()
        case, plan = self.case, self.plan
        if case.dt_fraction is not None:
            # any time step (plan_test limits dt_scale to 2): same loading, steps rescaled
            own = PAPER_SCHEDULES[case.dim]["dt_fraction"] if case.schedule == "stepwise" else DEFAULT_DT_FRACTION
            dt = plan.dt * case.dt_fraction / own
            steps = int(math.ceil(plan.steps * plan.dt / dt))
            if case.schedule == "stepwise":
                raise ValueError("dt_fraction is for the constant schedule")
            self.plan = dataclasses.replace(plan, dt=dt, steps=steps,
                                            thermo_every=max(1, steps // THERMO_LINES))

    def _execute(self, deck: Path) -> RunResult:
        result = self._launch(deck)
        self.halt_disabled = False
        if premature_halt(self._record(result)):
            # the deck's fix halt compares |stress| with 0.3 x its peak so far from the first
            # thermo row on: after a large platen jump the end particles bounce off the platen,
            # the stress of that row is 0 while the "peak" is a round-off value, and the run
            # stops at once (docs: see the report).  Run again without the halt.
            write_deck(dataclasses.replace(self.spec, halt_fraction=0.0), deck)
            result = self._launch(deck)
            self.halt_disabled = True
        return result

    def _record(self, result: RunResult) -> dict:
        return run_record(self.case, result, self.plan, self.lattice, self.rock, self.d)

    def _measure(self, result: RunResult) -> None:
        self.record = self._record(result)
        self.record["halt_disabled"] = self.halt_disabled

    def _summary(self) -> dict:
        for dump in ("dump.initial", "dump.final"):   # not needed here; keep the cache small
            (self.out / dump).unlink(missing_ok=True)
        return self.record

    def _accept_stored(self, stored: dict) -> dict | None:
        # (a cached premature halt of an older version of this study is run again; a 2D
        # result stored before cases had a dim is the same 2D case)
        if ({"dim": 2} | stored.get("case", {})) == dataclasses.asdict(self.case) and \
                not premature_halt(stored):
            stored["case"] = dataclasses.asdict(self.case)
            stored["cached"] = True
            return stored
        return None


def run_case(case: Case, out: Path, reuse: bool) -> dict:
    """Plan, write and run one lattice test on one rank; measure; cache result.json."""
    return SpeedErrorRun(case, out).run(reuse=reuse)


def premature_halt(res: dict) -> bool:
    """A strength run that fix halt stopped at one of its first three checks, before the
    block carried half its strength (a block that really fails that early, e.g. undamped,
    is left alone: it runs for many checks first)."""
    if not res.get("halted") or res["case"]["test"] == "elastic" or res.get("halt_disabled"):
        return False
    q = "Tu" if res["case"]["test"] == "tension" else "Cu"
    early = res["steps"] <= 3 * res["plan"]["thermo_every"]
    return early and (not res["ok"] or res["strength"] < 0.5 * res["target"][q])


def run_record(case: Case, result: RunResult, plan: RunPlan, lattice: Lattice, rock: Rock,
               d: float) -> dict:
    """The result record of one finished LAMMPS run of the study: its cost, and E, nu, the
    strength and the viscous offset (with its 2D estimate), or the error that stopped it."""
    dim = case.dim
    loops = _LOOP.findall(result.output)
    steps_run = int(loops[-1][1]) if loops else 0
    res: dict = {"case": dataclasses.asdict(case), "name": case.name, "particles": lattice.n,
                 "plan": dataclasses.asdict(plan), "steps": steps_run,
                 "particle_steps": steps_run * lattice.n, "wall_s": result.wall_time,
                 "loop_s": float(loops[-1][0]) if loops else None,
                 "halted": "Fix halt condition" in result.output,
                 "target": {"E": rock.E, "nu": rock.nu, "Tu": rock.Tu, "Cu": rock.Cu},
                 "ok": False, "error": None}
    try:
        if result.returncode != 0:
            raise RuntimeError(result.error.strip())
        thermo = result.last_thermo()
        got = measure(thermo, case.test, dim)
        values = [got.E, got.nu] + ([got.strength] if got.strength is not None else [])
        if not all(math.isfinite(v) for v in values):
            raise RuntimeError("non-finite measurement")
        res.update(ok=True, E=got.E, nu=got.nu, strength=got.strength,
                   ke_max=float(np.max(thermo["KinEng"])),
                   broken=[got.broken_tension, got.broken_shear])
        if got.strength is not None:
            res["offset"] = stress_offset(thermo, case.test)
        # viscous drag of a block moving with a linear velocity profile (platens at +-speed):
        # the half between a platen and the middle adds eta * sum(v) to the platen force,
        # eta * speed * H / (2 sqrt3 d^2) per unit area (2D hexagonal packing, 2/(sqrt3 d^2)
        # particles per unit area, mean speed speed/2 over H/2)
        if dim == 2:
            res["viscous_estimate"] = (plan.eta * plan.speed * lattice.height /
                                       (2 * math.sqrt(3) * d * d))
    except (RuntimeError, ValueError) as exc:
        res["error"] = str(exc)[:300]
    return res


def stress_offset(thermo: dict, test: str) -> float:
    """Intercept of the straight-line fit of stress on strain in the strength tests' elastic
    window (10-25% of the peak), in Pa, signed like the strength: the part of the measured
    stress that does not come from the strain, e.g. the viscous drag of the moving block."""
    sign = 1.0 if test == "tension" else -1.0
    strain, stress = sign * thermo["v_strain"], sign * thermo["v_stress"]
    mask = _elastic_window(strain, stress, STRENGTH_WINDOW)
    if mask.sum() < 3:
        return float("nan")
    return float(np.polyfit(strain[mask], stress[mask], 1)[1])



class Runner:
    """Runs cases in order, with progress lines and a running total."""

    def __init__(self, out: Path, reuse: bool) -> None:
        self.out, self.reuse = out, reuse
        self.done = 0
        self.seconds = 0.0
        self.memo: dict[Case, dict] = {}

    def __call__(self, case: Case) -> dict:
        if case in self.memo:        # the same run asked for twice in one invocation
            return self.memo[case]
        res = run_case(case, self.out, self.reuse)
        self.memo[case] = res
        self.done += 1
        if not res.get("cached"):
            self.seconds += res["wall_s"]
        status = "cached" if res.get("cached") else f"{res['wall_s']:.1f} s"
        if res["ok"]:
            vals = (f"E {res['E'] / 1e9:.4f} GPa nu {res['nu']:.5f}" if case.test == "elastic"
                    else f"strength {res['strength'] / 1e6:.3f} MPa")
        else:
            vals = f"FAILED: {res['error'][:80]}"
        print(f"[{self.done:3d}] {case.name:42s} {res['steps']:9d} steps  {status:>9s}  {vals}  "
              f"(total {self.seconds / 60:.1f} min)", flush=True)
        return res


def add_errors(res: dict, refs: dict) -> dict:
    """Errors of one run: E, nu against the formulas; Tu, Cu against the papers' schedule,
    and against the formulas (key + '_formula')."""
    errs: dict = {}
    if not res["ok"]:
        return errs
    test = res["case"]["test"]
    if test == "elastic":
        errs["E"] = res["E"] / res["target"]["E"] - 1.0
        errs["nu"] = res["nu"] / res["target"]["nu"] - 1.0
    else:
        q = "Tu" if test == "tension" else "Cu"
        errs[q + "_formula"] = res["strength"] / res["target"][q] - 1.0
        if refs.get(q):
            errs[q] = res["strength"] / refs[q] - 1.0
    return errs


def lattice_stability(s: Settings, run: Runner) -> dict:
    """Largest stable time step of the 2D lattice (elastic test, constant schedule, walls
    2 Kn)."""
    rock = get_rock("quartz")
    bond = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, 1e-3, 2)
    m = lattice_mass(rock.rho, 1e-3, 2)

    def stable(res: dict) -> bool:
        return bool(res["ok"]) and abs(res["E"] / rock.E - 1.0) < 0.05

    rows = [run(Case("stability", "elastic", s.n_stability, dt_fraction=f))
            for f in s.stability_fractions]
    good = [r["case"]["dt_fraction"] for r in rows if stable(r)]
    bad = [r["case"]["dt_fraction"] for r in rows if not stable(r)]
    lo = max(good) if good else None
    hi = min([b for b in bad if lo is None or b > lo], default=None)
    if lo is not None and hi is not None:
        for _ in range(s.stability_bisections):
            mid = round(0.5 * (lo + hi), 4)
            r = run(Case("stability", "elastic", s.n_stability, dt_fraction=mid))
            rows.append(r)
            if stable(r):
                lo = mid
            else:
                hi = mid
    return {"rows": sorted(rows, key=lambda r: r["case"]["dt_fraction"]), "stable": lo,
            "unstable": hi, "formula": critical_time_step(m, bond.Kn, bond.Ks, 2) /
            math.sqrt(m / bond.Kn)}


def check_reference_case(s: Settings, test: str) -> Case:
    """The reference run of the transfer check: a slow constant run
    (``s.check_reference_crossings``, damping 1) or, when that is None, the papers' stepwise
    schedule at the check's size."""
    if s.check_reference_crossings is None:
        return Case("check", test, s.n_check, schedule="stepwise",
                    relax_steps=paper_relax(s.dim), dim=s.dim)
    return Case("check", test, s.n_check, crossings=s.check_reference_crossings, dim=s.dim)


def run_lattice(s: Settings, out: Path, reuse: bool) -> dict:
    """Part 2 and 3 (2D) or the 3D part: the sweeps, the references, the recommendation and
    its check."""
    run = Runner(out, reuse)
    cases = lattice_cases(s)
    what = (f"2D quartz; elastic N = {s.n_elastic}, strength N = {s.n_strength}" if s.dim == 2
            else f"3D quartzite; elastic n_y = {s.n_elastic}, strength n_y = {s.n_strength}")
    print(f"lattice: {len(cases)} runs in the main sweep ({what}), one rank", flush=True)
    results = [run(c) for c in cases]
    stability = lattice_stability(s, run) if s.stability else None

    refs: dict = {}
    paper = {}
    for r in results:
        if r["case"]["family"] == "paper" and r["ok"]:
            paper[r["case"]["test"]] = r
            if r["case"]["test"] != "elastic":
                refs["Tu" if r["case"]["test"] == "tension" else "Cu"] = r["strength"]
    for r in results + (stability["rows"] if stability else []):
        r["errors"] = add_errors(r, refs)
    paper_err = {q: paper[TEST_OF[q]]["errors"].get(q, 0.0) if TEST_OF[q] in paper else 0.0
                 for q in QUANTITIES}

    grid = constant_grid(results)
    candidates = recommend(grid, paper_err, TOLERANCE)
    # transfer check on another block: candidates against the check's reference (2D: a slow
    # constant run, the papers' schedule at N = 30 would cost ~20 min per test; 3D: the
    # papers' schedule); first candidate that passes
    checks = []
    chosen = None
    ref_check = {t: run(check_reference_case(s, t)) for t in ("tension", "compression")}
    default_check = {t: run(Case("check", t, s.n_check, **s.default_for(t), dim=s.dim))
                     for t in ref_check}
    for c, f, _ in candidates[:3]:
        rows = {t: run(Case("check", t, s.n_check, crossings=c, damping=f, dim=s.dim))
                for t in ref_check}
        errs = {}
        for t, r in rows.items():
            q = "Tu" if t == "tension" else "Cu"
            ref = ref_check[t]
            errs[q] = (r["strength"] / ref["strength"] - 1.0) if r["ok"] and ref["ok"] else None
        passed = all(within(e, 0.0, TOLERANCE[q]) for q, e in errs.items())
        checks.append({"crossings": c, "damping": f, "errors": errs, "passed": passed,
                       "steps": {t: r["steps"] for t, r in rows.items()}})
        if passed:
            chosen = (c, f)
            break
    ref_err = {}
    for t, r in ref_check.items():
        q = "Tu" if t == "tension" else "Cu"
        ref_err[q] = {"ref": r.get("strength"), "formula": r["strength"] / r["target"][q] - 1
                      if r["ok"] else None,
                      "default": (default_check[t]["strength"] / r["strength"] - 1.0)
                      if default_check[t]["ok"] and r["ok"] else None,
                      "ref_steps": r["steps"], "default_steps": default_check[t]["steps"],
                      "ref_wall_s": r["wall_s"]}
    return {"dim": s.dim, "results": results, "stability": stability, "refs": refs,
            "paper": paper, "paper_err": paper_err, "grid": grid, "candidates": candidates,
            "checks": checks, "check_ref": ref_err, "chosen": chosen, "seconds": run.seconds,
            "total_seconds": sum(r["wall_s"] for r in run.memo.values()),
            "total_steps": sum(r["steps"] for r in run.memo.values()),
            "runs": len(run.memo)}


def constant_grid(results: list[dict]) -> dict[tuple[float, float], dict[str, float | None]]:
    """{(crossings, damping): {quantity: error}} of the constant schedule at its default dt."""
    grid: dict = {}
    for r in results:
        cs = r["case"]
        if cs["schedule"] != "constant" or cs["dt_fraction"] is not None or \
                cs["family"] not in ("constant", "slow"):
            continue
        cell = grid.setdefault((cs["crossings"], cs["damping"]), {q: None for q in QUANTITIES})
        for q in QUANTITIES:
            if TEST_OF[q] == cs["test"]:
                cell[q] = r["errors"].get(q)
    return grid


def points(results: list[dict], q: str) -> list[dict]:
    """Runs of the main sweep that measure q, with their error."""
    return [r for r in results if r["case"]["test"] == TEST_OF[q] and r["ok"]
            and q in r["errors"] and r["case"]["family"] not in ("check", "stability")]

