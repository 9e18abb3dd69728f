"""Where the validation's runs go and how one is made (or read back).

:class:`Validation` holds the options of ``bonded-lattice validate``; :meth:`Validation.run`
makes one :class:`~bonded_lattice.experiment.RockTest` in its own folder (or, with
``reuse``, reads the summary an earlier run left there) and returns its compact summary
(:func:`compact`): the numbers the results file keeps, not the whole ``summary.json``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..experiment import RockTest
from ..io import read_thermo
from ..rocks import Rock, get_rock

__all__ = ["PAPER_DAMPING_LOADING", "QUICK_SIZES", "SLOW_SIZES", "Validation", "compact",
           "curve", "rock_for"]

# the papers' block sizes: particles across (2D) and elements along y (3D)
QUICK_SIZES = {2: [4, 8, 15, 30], 3: [4, 6, 8, 10, 12]}
SLOW_SIZES = {2: [60, 120], 3: [16, 20, 24, 30]}

# constant loading at the papers' damping: 100 elastic-wave crossings to failure and eta x 1
# (the setting the series were first made with; the 2D defaults moved to 50 crossings and a
# quarter of eta, docs/speed_error.md)
PAPER_DAMPING_LOADING = {"crossings": 100.0, "damping": 1.0}

# the summary.json keys a results file keeps for every run
_KEPT = ("dim", "test", "n", "particles", "target", "measured", "relative_error",
         "nu_all_particles", "broken_bonds", "first_break_stress", "energy",
         "lateral_width_m", "confining_Pa", "orientation_deg", "wall_time_s")
_KEPT_PLAN = ("d", "schedule", "steps", "dt", "eta", "speed", "step_size", "relax_steps", "area")


def rock_for(dim: int) -> Rock:
    """The papers' rock: quartz in 2D (2013), quartzite with the same values in 3D (2017)."""
    return get_rock("quartz")


def compact(summary: dict) -> dict:
    """The numbers of a run's ``summary.json`` that the results file keeps."""
    out = {k: summary.get(k) for k in _KEPT}
    plan = summary.get("plan", {})
    out["plan"] = {k: plan.get(k) for k in _KEPT_PLAN}
    return out


def curve(folder: Path, columns: tuple[str, ...] = ("v_strain", "v_stress"),
          points: int = 400) -> dict[str, list[float]]:
    """Columns of the last thermo table of ``folder/log.lammps``, thinned to at most
    ``points`` rows (every k-th row, the last one kept), rounded to 6 significant digits."""
    tables = read_thermo(folder / "log.lammps")
    if not tables:
        raise RuntimeError(f"{folder / 'log.lammps'} has no thermo table")
    table = tables[-1]
    rows = len(table[columns[0]])
    keep = np.unique(np.r_[np.arange(0, rows, max(1, rows // points)), rows - 1])
    return {c: [float(f"{x:.6g}") for x in table[c][keep]] for c in columns}


@dataclass
class Validation:
    """Where the runs go and which of them to do.

    out: folder of the run folders; np_: MPI ranks per run; slow: also the largest sizes and
    the papers' stepwise schedule; reuse: keep every run whose ``summary.json`` exists;
    progress: print each run's name as it starts.
    """

    out: Path
    np_: int = 2
    slow: bool = False
    reuse: bool = False
    progress: bool = True

    def folder(self, name: str) -> Path:
        return self.out / name

    def run(self, name: str, rock: Rock, dim: int, test: str, n: int, **options) -> dict:
        """One test in ``out/name`` with ``options`` of
        :class:`~bonded_lattice.experiment.RockTest` (by default constant loading at the
        papers' damping, :data:`PAPER_DAMPING_LOADING`); its compact summary."""
        for key, value in PAPER_DAMPING_LOADING.items():
            options.setdefault(key, value)
        study = RockTest(rock, dim, test, n, self.folder(name), np_=self.np_, progress=False,
                         **options)
        stored = study.stored() if self.reuse else None
        if stored is None:
            if self.progress:
                print(f"validate: {name}", flush=True)
            stored = study.run()
        return compact(stored)

    def sizes(self, dim: int) -> list[int]:
        return QUICK_SIZES[dim] + (SLOW_SIZES[dim] if self.slow else [])
