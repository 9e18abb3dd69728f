"""Calibrate the bond parameters of one lattice size against a rock's properties.

The conversion formulas describe the papers' single unit.  A block of many
units comes out a little softer laterally (nu low by a free-side effect that
shrinks as 1/N) and clearly weaker (Tu about 5% low, Cu 15-20% low: its
boundary bonds fail first, Liu et al. 2013, 2017).  The papers suggest feeding
larger strengths into the formulas by hand; :func:`calibrate` does it by
measuring the user's own block and correcting the formulas' inputs:

1. elastic tests (unbreakable bonds) until E and nu match: E_in is scaled by
   E_target / E_measured, nu_in shifted by nu_target - nu_measured (Kn and Ks
   depend on E and nu only, so this fixes both springs);
2. tension tests until Tu matches, scaling Tu_in (Xb is proportional to it);
3. compression tests until Cu matches, scaling Cu_in (Fs0 is proportional to it).

Each stage takes secant steps after the first ratio step and stops when its
measured values are within ``tol`` of the targets.  Strength is nearly
proportional to the input strength (the lattice is linear up to its first
breaks), so each stage usually needs two or three runs.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path

from .conversion import NU_MAX, BondParameters, rock_to_bond
from .experiment import run_test
from .rocks import Rock

PROPERTIES = ("E", "nu", "Tu", "Cu")
STAGES = (("elastic", ("E", "nu")), ("tension", ("Tu",)), ("compression", ("Cu",)))


@dataclass
class CalibrationStep:
    """One test run of the calibration: the inputs fed to the formulas and what came out."""

    stage: str                    # elastic, tension or compression
    inputs: dict[str, float]      # E, nu, Tu, Cu, mu_i given to rock_to_bond
    measured: dict[str, float]    # properties measured in this run


@dataclass
class CalibrationResult:
    """Calibrated bond parameters of one lattice, and how they were found.

    inputs: the rock properties that, put into the conversion formulas, give a
        lattice of this size the target properties; bond: the resulting pair
        coefficients; corrections: inputs relative to the targets (ratios for
        E, Tu, Cu; a difference for nu); measured / errors: the last run of
        each property; converged: every error within ``tol``.
    """

    rock: str
    dim: int
    n: int
    particles: int
    tol: float
    inputs: dict[str, float]
    bond: BondParameters
    target: dict[str, float]
    measured: dict[str, float]
    errors: dict[str, float]
    corrections: dict[str, float]
    converged: bool
    steps: list[CalibrationStep] = field(default_factory=list)

    def to_json(self) -> str:
        data = asdict(self)
        return json.dumps(data, indent=2)


def _error(measured: float, target: float) -> float:
    """Relative error (nu too: the 2% goal is relative)."""
    return measured / target - 1.0


def _next_input(prop: str, history: list[tuple[float, float]], target: float) -> float:
    """Next input from (input, measured) pairs: a secant step, or a ratio step at first.

    nu is shifted, the other properties are scaled.  A secant through two nearly
    equal measurements (noise) falls back to the ratio step.
    """
    x1, m1 = history[-1]
    ratio_step = x1 + (target - m1) if prop == "nu" else x1 * target / m1
    if len(history) < 2:
        return ratio_step
    x0, m0 = history[-2]
    slope = (m1 - m0) / (x1 - x0) if x1 != x0 else 0.0
    if slope <= 0 or not math.isfinite(slope):
        return ratio_step
    return x1 + (target - m1) / slope


def _check_input(prop: str, value: float, dim: int) -> float:
    if prop == "nu":
        if not 0.0 <= value <= NU_MAX[dim]:
            raise ValueError(f"calibration needs nu_in = {value:.4g}, out of the lattice's range "
                             f"0 <= nu <= {NU_MAX[dim]:g} ({dim}D): this lattice cannot reach "
                             "the target Poisson's ratio")
    elif not value > 0:
        raise ValueError(f"calibration needs {prop}_in = {value:.4g} <= 0: it diverged")
    return value


def calibrate(rock: Rock, dim: int, n: int, out: str | Path, np_: int = 2,
              d: float = 1.0e-3, tol: float = 0.01, max_runs: int = 5,
              progress: bool = False, orientation: float = 0.0,
              **plan_options) -> CalibrationResult:
    """Find the inputs of the conversion formulas that give this lattice the rock's properties.

    rock: target properties; dim, n, d, orientation: the lattice (as for
    ``bonded-lattice run``);
    tol: relative tolerance per property (default 1%, inside the 2% goal);
    max_runs: test runs per stage at most; progress: print one line per run;
    plan_options: loading options of
    :func:`bonded_lattice.experiment.plan_test` (schedule, crossings, ...) and
    ``atom_style`` of :func:`bonded_lattice.experiment.run_test`.
    Writes each run into ``out/<stage>_<k>`` and the result to ``out/calibration.json``.
    Raises ValueError when a needed input leaves the lattice's valid range.
    """
    if not 0 < tol < 0.5:
        raise ValueError(f"tol = {tol} is out of range: need 0 < tol < 0.5")
    if max_runs < 1:
        raise ValueError(f"max_runs = {max_runs} is out of range: need max_runs >= 1")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    target = {p: float(getattr(rock, p)) for p in PROPERTIES}
    inputs = {**target, "mu_i": float(rock.mu_i)}
    measured: dict[str, float] = {}
    steps: list[CalibrationStep] = []
    particles = 0
    for stage, props in STAGES:
        history: dict[str, list[tuple[float, float]]] = {p: [] for p in props}
        for k in range(max_runs):
            bond = rock_to_bond(inputs["E"], inputs["nu"], inputs["Tu"], inputs["Cu"],
                                inputs["mu_i"], d, dim)
            summary = run_test(rock, dim, stage, n, out / f"{stage}_{k}", np_=np_, d=d,
                               progress=False, bond=bond, orientation=orientation,
                               **plan_options)
            particles = summary["particles"]
            got = {p: float(summary["measured"][p]) for p in props}
            measured.update(got)
            steps.append(CalibrationStep(stage, dict(inputs), got))
            if progress:
                print(f"calibrate {stage} run {k}: " + ", ".join(
                    f"{p} {100 * _error(got[p], target[p]):+.2f}%" for p in props))
            for p in props:
                history[p].append((inputs[p], got[p]))
            if all(abs(_error(got[p], target[p])) <= tol for p in props):
                break
            if k + 1 < max_runs:
                for p in props:
                    inputs[p] = _check_input(p, _next_input(p, history[p], target[p]), dim)
        # keep the inputs of the last measured run of this stage
        for p in props:
            inputs[p] = history[p][-1][0]
    bond = rock_to_bond(inputs["E"], inputs["nu"], inputs["Tu"], inputs["Cu"], inputs["mu_i"],
                        d, dim)
    errors = {p: _error(measured[p], target[p]) for p in PROPERTIES}
    corrections = {"E": inputs["E"] / target["E"], "nu": inputs["nu"] - target["nu"],
                   "Tu": inputs["Tu"] / target["Tu"], "Cu": inputs["Cu"] / target["Cu"]}
    result = CalibrationResult(rock=rock.name, dim=dim, n=n, particles=particles, tol=tol,
                               inputs=inputs, bond=bond, target=target, measured=measured,
                               errors=errors, corrections=corrections,
                               converged=all(abs(e) <= tol for e in errors.values()),
                               steps=steps)
    (out / "calibration.json").write_text(result.to_json())
    return result


def calibration_table(result: CalibrationResult) -> str:
    """Target, measured, error and the correction applied to each property."""
    units = {"E": (1e9, "GPa"), "nu": (1.0, ""), "Tu": (1e6, "MPa"), "Cu": (1e6, "MPa")}
    lines = [f"{result.rock}, {result.dim}D, {result.particles} particles: "
             f"{len(result.steps)} runs, " + ("converged" if result.converged else
                                               f"NOT converged within {100 * result.tol:g}%"),
             f"{'property':>10s} {'target':>10s} {'measured':>10s} {'error':>8s} "
             f"{'input':>10s} {'correction':>11s}"]
    for p in PROPERTIES:
        scale, unit = units[p]
        label = p + (f" ({unit})" if unit else "")
        corr = (f"{result.corrections[p]:+.4f}" if p == "nu"
                else f"x {result.corrections[p]:.4f}")
        lines.append(f"{label:>10s} {result.target[p] / scale:10.5g} "
                     f"{result.measured[p] / scale:10.5g} {100 * result.errors[p]:+7.2f}% "
                     f"{result.inputs[p] / scale:10.5g} {corr:>11s}")
    lines.append(result.bond.pair_coeff())
    return "\n".join(lines)
