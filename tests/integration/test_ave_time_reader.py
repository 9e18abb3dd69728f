"""io.read_ave_time against files LAMMPS itself writes, and the breaking duration of a test
(experiment.breaking_duration) from such a file."""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.decks import BREAKING_COLUMNS
from bonded_lattice.experiment import breaking_duration, peak_work_fraction
from bonded_lattice.io import read_ave_time


def write_with_lammps(lmp, path, mode_vector: bool = False) -> None:
    """Five steps of one atom; fix ave/time writes the step and twice the step."""
    lmp.commands_string(f"""
units lj
region box block 0 1 0 1 0 1
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5
mass 1 1.0
variable s equal step
variable t equal 2*step
compute com all com
fix nve all nve
""")
    if mode_vector:
        lmp.command(f"fix out all ave/time 1 1 1 c_com mode vector file {path}")
    else:
        lmp.command(f"fix out all ave/time 1 1 1 v_s v_t file {path}")
    lmp.command("run 5")


def test_columns_by_the_header_lammps_writes(lmp_instance, tmp_path):
    path = tmp_path / "out.dat"
    write_with_lammps(lmp_instance, path)
    lmp_instance.command("unfix out")    # flush and close the file
    cols = read_ave_time(path)
    assert list(cols) == ["TimeStep", "v_s", "v_t"]
    # one line per step (LAMMPS writes every step from 0 or 1 to 5)
    assert cols["TimeStep"][-1] == 5 and np.all(np.diff(cols["TimeStep"]) == 1)
    np.testing.assert_array_equal(cols["v_s"], cols["TimeStep"])
    np.testing.assert_array_equal(cols["v_t"], 2 * cols["TimeStep"])


def test_a_vector_mode_file_is_refused(lmp_instance, tmp_path):
    path = tmp_path / "vector.dat"
    write_with_lammps(lmp_instance, path, mode_vector=True)
    lmp_instance.command("unfix out")
    with pytest.raises(ValueError, match="not a 'fix ave/time' file in scalar mode"):
        read_ave_time(path)


def test_breaking_duration_from_two_to_ninety_eight_percent_of_the_heat(tmp_path):
    # breaking heat rising linearly with the step, 0 to 100 J over steps 0-100: it passes 2%
    # (> 2 J) at step 3 and reaches 98% (>= 98 J) at step 98, so 95 steps of dt
    path = tmp_path / "breaking.dat"
    steps = np.arange(101)
    lines = ["# Time-averaged data for fix breaklog", "# TimeStep " + " ".join(BREAKING_COLUMNS)]
    # the two breaking heats first, the other columns (BREAKING_COLUMNS[2:]) zero
    zeros = " 0" * (len(BREAKING_COLUMNS) - 2)
    lines += [f"{k} {0.75 * k} {0.25 * k}{zeros}" for k in steps]
    path.write_text("\n".join(lines) + "\n")
    assert breaking_duration(path, dt=1e-8) == pytest.approx(95e-8, rel=1e-12)
    # the 2017 paper's definition, start to end: the first heat (step 1) to 100 J (step 100)
    assert breaking_duration(path, dt=1e-8, fraction=0.0) == pytest.approx(99e-8, rel=1e-12)
    with pytest.raises(ValueError, match="fraction = 0.5 is out of range"):
        breaking_duration(path, dt=1e-8, fraction=0.5)
    assert breaking_duration(tmp_path / "missing.dat", dt=1e-8) is None


def test_peak_work_fraction_skips_the_first_percent_of_the_work():
    # work 0.001 J is below 1% of the final 40 J: that row's ratio (1000) is the start-up
    # transient and does not count; of the others (0.1, 0.25, 0.05) the largest is 0.25
    kinetic = np.array([1.0, 1.0, 5.0, 2.0])
    work = np.array([0.001, -10.0, 20.0, 40.0])    # the work's sign does not matter
    assert peak_work_fraction(kinetic, work) == 0.25
    assert peak_work_fraction(kinetic[:0], work[:0]) == 0.0
