"""inputs/cluster: the batch script continues a run from its newest restart file, stops
cleanly at the job's time limit and submits the next job (Slurm's squeue and sbatch are
replaced by stand-ins that answer like them)."""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from bonded_lattice.io import read_atom_dump
from bonded_lattice.runner import lmp_command, run_environment
from helpers import INPUTS

EXAMPLE = INPUTS / "cluster"
D = 1.0e-3


def job(work: Path, steps: int, slurm_time_left: str | None = None, **extra) -> str:
    """Run run.slurm once in work (copied there the first time); its screen output."""
    if not (work / "run.slurm").exists():
        work.mkdir(parents=True, exist_ok=True)
        for f in EXAMPLE.iterdir():
            shutil.copy(f, work)
    env = dict(run_environment(2), MODULES="", PLUGIN_DIR=os.environ.get("LAMMPS_PLUGIN_PATH", ""),
               STEPS=str(steps), EVERY="250", DECK_ARGS="-var N 8 -var thermo 200",
               LAUNCH=shlex.join(lmp_command(2)), **extra)
    env.pop("SLURM_JOB_ID", None)
    if slurm_time_left is not None:      # inside a job: squeue tells the time left
        bindir = work / "fake-slurm"
        bindir.mkdir(exist_ok=True)
        for name, body in (("squeue", f'echo "{slurm_time_left}"'),
                           ("sbatch", 'echo "$@" >> sbatch.calls')):
            (bindir / name).write_text(f"#!/bin/sh\n{body}\n")
            (bindir / name).chmod(0o755)
        env.update(SLURM_JOB_ID="4711", SLURM_SUBMIT_DIR=str(work),
                   PATH=f"{bindir}:{env['PATH']}")
    proc = subprocess.run(["bash", "run.slurm"], cwd=work, env=env, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return proc.stdout


def final_positions(work: Path) -> np.ndarray:
    return read_atom_dump(work / "final.dump")[1]


@pytest.mark.mpi
def test_second_job_continues_from_the_newest_restart_file(tmp_path):
    first = job(tmp_path / "chain", 600)
    assert "a new model" in first and "reached step 600" in first
    assert {p.name for p in (tmp_path / "chain").glob("ckpt.*")} == \
        {"ckpt.250", "ckpt.500", "ckpt.600"}
    second = job(tmp_path / "chain", 1200)
    assert "continuing from ckpt.600" in second and "reached step 1200" in second
    whole = job(tmp_path / "whole", 1200)
    assert "a new model" in whole
    # before any bond breaks: the same positions and velocities to round-off
    a, b = final_positions(tmp_path / "chain"), final_positions(tmp_path / "whole")
    assert a.shape == b.shape and np.all(a[:, :2] == b[:, :2])
    assert np.max(np.abs(a[:, 2:5] - b[:, 2:5])) < 1e-12 * D
    assert np.max(np.abs(a[:, 5:] - b[:, 5:])) < 1e-9 * np.max(np.abs(b[:, 5:]))


@pytest.mark.mpi
def test_job_stops_at_its_time_limit_and_submits_the_next(tmp_path):
    work = tmp_path / "job"
    # 61 s left, 60 s kept for the restart file: LAMMPS stops after 1 s
    out = job(work, 10**8, slurm_time_left="01:01", MARGIN="60")
    assert "time limit 1 s" in out, out
    log = next(work.glob("log.4711")).read_text()
    stopped = re.search(r"^RESULT stopped at step (\d+) by the time limit", log, re.M)
    assert stopped, log[-2000:]
    step = int(stopped[1])
    assert 0 < step < 10**8 and (work / f"ckpt.{step}").exists()
    assert (work / "sbatch.calls").read_text().split() == [f"{work}/run.slurm"]
    # the next job: days of time left; it reaches the end and submits nothing more
    out = job(work, step + 200, slurm_time_left="1-00:00:00")
    assert f"continuing from ckpt.{step}" in out and "time limit 85800 s" in out, out
    assert f"reached step {step + 200}" in out
    assert len((work / "sbatch.calls").read_text().split()) == 1
