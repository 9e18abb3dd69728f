"""The shape every simulation study of the package shares: plan, write, run, measure, plot,
summary.

A :class:`Study` is one simulation in one output folder.  Its :meth:`Study.run` is a fixed
template, as in MDAnalysis' ``AnalysisBase`` (whose ``run()`` calls ``_prepare``,
``_single_frame`` and ``_conclude``); subclasses fill the hooks and do not override ``run``:

    _plan()              choose the numbers (lattice, time step, loading ...)
    _write() -> deck     the data file and the LAMMPS deck in the folder
    _execute(deck)       run LAMMPS (default: ``runner.run_deck`` on ``np_`` ranks,
                         RuntimeError naming LAMMPS' ERROR line if it fails)
    _measure(result)     the measured quantities, from the thermo output and the dumps
    _plot()              the pictures (only when ``pictures`` is true)
    _summary() -> dict   the summary, written to ``summary_file`` and returned

The subclasses:

- :class:`bonded_lattice.experiment.RockTest`: one rock-mechanics test of a block
  (``run_test``, ``bonded-lattice run``);
- :class:`bonded_lattice.scene_study.SceneStudy`: one Mike/Elle scene (``run_scene``,
  ``bonded-lattice scene --run``);
- :class:`bonded_lattice.speed_error.lattice_runs.SpeedErrorRun`: one run of the
  speed-against-error study (a RockTest that records failures instead of raising).

``run(reuse=True)`` returns the stored summary of an earlier run when there is one and the
subclass accepts it (:meth:`Study._accept_stored`), without running anything.
"""

from __future__ import annotations

import json
from abc import ABC, abstractmethod
from pathlib import Path
from typing import ClassVar

from .runner import RunResult, run_deck

__all__ = ["Study"]


class Study(ABC):
    """One simulation in one folder; :meth:`run` is the template, the ``_`` methods its hooks.

    out: the output folder (created by :meth:`run`); np_: MPI ranks; progress: show the
    run's progress; pictures: call :meth:`_plot`.
    """

    #: the summary's file name in ``out``
    summary_file: ClassVar[str] = "summary.json"
    #: ``json.dumps`` indentation of the summary file, and what follows the JSON text
    json_indent: ClassVar[int] = 2
    json_end: ClassVar[str] = ""

    def __init__(self, out: str | Path, np_: int = 1, progress: bool = False,
                 pictures: bool = True) -> None:
        self.out = Path(out)
        self.np_ = np_
        self.progress = progress
        self.pictures = pictures
        self.result: RunResult | None = None

    # ------------------------------------------------------------------ the template

    def run(self, reuse: bool = False) -> dict:
        """Plan, write, run, measure, plot and summarise; returns the summary.

        reuse: return the stored summary of an earlier run instead, if there is one and
        :meth:`_accept_stored` accepts it.
        """
        if reuse:
            stored = self.stored()
            if stored is not None:
                return stored
        self.out.mkdir(parents=True, exist_ok=True)
        self._plan()
        deck = self._write()
        self.result = self._execute(deck)
        self._measure(self.result)
        if self.pictures:
            self._plot()
        summary = self._summary()
        (self.out / self.summary_file).write_text(
            json.dumps(summary, indent=self.json_indent) + self.json_end)
        return summary

    def stored(self) -> dict | None:
        """The summary an earlier run left in ``out``, if any and accepted."""
        path = self.out / self.summary_file
        if not path.exists():
            return None
        return self._accept_stored(json.loads(path.read_text()))

    # ------------------------------------------------------------------ hooks

    @abstractmethod
    def _plan(self) -> None:
        """Choose the run's numbers (and build what the deck needs)."""

    @abstractmethod
    def _write(self) -> Path:
        """Write the data file and the deck into ``out``; return the deck's path."""

    def _execute(self, deck: Path) -> RunResult:
        """Run the deck; raise RuntimeError (:meth:`_failure`) if LAMMPS fails."""
        result = self._launch(deck)
        if result.returncode != 0:
            raise RuntimeError(self._failure(result))
        return result

    @abstractmethod
    def _measure(self, result: RunResult) -> None:
        """Measure the finished run (store the results on ``self``)."""

    def _plot(self) -> None:
        """Draw the pictures (none by default)."""

    @abstractmethod
    def _summary(self) -> dict:
        """The summary written to :attr:`summary_file` and returned by :meth:`run`."""

    # ------------------------------------------------------------------ helpers of the hooks

    def _launch(self, deck: Path) -> RunResult:
        """``run_deck`` in ``out`` on ``np_`` ranks (the progress bar counts
        :meth:`_total_steps`); does not check the outcome."""
        return run_deck(deck, self.out, np_=self.np_, total_steps=self._total_steps(),
                        progress=self.progress)

    def _total_steps(self) -> int | None:
        """Time steps of the run, for the progress bar (None: unknown)."""
        return None

    def _failure(self, result: RunResult) -> str:
        """The message of a failed run, with LAMMPS' ERROR line."""
        return f"LAMMPS failed in {self.out}: {result.error}"

    def _accept_stored(self, stored: dict) -> dict | None:
        """A stored summary to return from ``run(reuse=True)``, or None to run again."""
        return stored
