"""BONDED_LATTICE_LMP and BONDED_LATTICE_MPIRUN point the runner at another LAMMPS and MPI."""

import stat

import pytest
from bonded_lattice import runner


def _program(path):
    path.write_text("#!/bin/sh\nexit 0\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


def test_variables_give_the_command_line(tmp_path, monkeypatch):
    lmp = _program(tmp_path / "lmp_site")
    mpirun = _program(tmp_path / "mpirun site")          # a space in the path: quoted below
    monkeypatch.setenv("BONDED_LATTICE_LMP", str(lmp))
    monkeypatch.setenv("BONDED_LATTICE_MPIRUN", f"'{mpirun}' --oversubscribe --bind-to none")
    assert runner.lmp_command(1) == [str(lmp)]
    assert runner.lmp_command(3) == [str(mpirun), "--oversubscribe", "--bind-to", "none",
                                     "-np", "3", str(lmp)]


def test_a_command_on_path_is_found(tmp_path, monkeypatch):
    _program(tmp_path / "lmp_cluster")
    monkeypatch.setenv("PATH", f"{tmp_path}:/usr/bin:/bin")
    monkeypatch.setenv("BONDED_LATTICE_LMP", "lmp_cluster -sf opt")
    assert runner.lmp_command(1) == [str(tmp_path / "lmp_cluster"), "-sf", "opt"]


def test_lmp_without_mpirun_is_refused(tmp_path, monkeypatch):
    monkeypatch.setenv("BONDED_LATTICE_LMP", str(_program(tmp_path / "lmp")))
    monkeypatch.delenv("BONDED_LATTICE_MPIRUN", raising=False)
    assert runner.lmp_command(1) == [str(tmp_path / "lmp")]      # one rank needs no launcher
    with pytest.raises(RuntimeError, match="BONDED_LATTICE_MPIRUN is not"):
        runner.lmp_command(2)


@pytest.mark.parametrize("variable", ["BONDED_LATTICE_LMP", "BONDED_LATTICE_MPIRUN"])
def test_missing_program_is_named(tmp_path, monkeypatch, variable):
    monkeypatch.setenv("BONDED_LATTICE_LMP", str(_program(tmp_path / "lmp")))
    monkeypatch.setenv("BONDED_LATTICE_MPIRUN", str(_program(tmp_path / "mpirun")))
    monkeypatch.setenv(variable, f"{tmp_path}/nothere -x")
    with pytest.raises(FileNotFoundError, match=f"{variable}=.*nothere.*not an executable"):
        runner.lmp_command(2)


def test_unbalanced_quote_is_refused(monkeypatch):
    monkeypatch.setenv("BONDED_LATTICE_MPIRUN", "mpirun '--oversubscribe")
    monkeypatch.setenv("BONDED_LATTICE_LMP", "sh")
    with pytest.raises(ValueError, match="BONDED_LATTICE_MPIRUN=.*not a valid command line"):
        runner.lmp_command(2)
