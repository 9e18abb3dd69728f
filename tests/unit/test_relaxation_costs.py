"""scene_analysis.relaxation_costs: the summary lines of lattice/quasistatic, summed."""

from __future__ import annotations

from bonded_lattice.scene_analysis import relaxation_costs

# the lines the command prints (lattice_quasistatic.cpp), among other output
LOG = """\
lattice/quasistatic: 0 bonds broke (0 in tension, 0 in shear) in 2 relaxations (158 sweeps, 481559 particle moves); largest remaining ratio to the threshold 0.431773
Loop time of 1e-06 on 1 procs for 0 steps with 4200 atoms
lattice/quasistatic: 73 bonds broke (73 in tension, 0 in shear) in 75 relaxations (12601 sweeps, 29620913 particle moves); largest remaining ratio to the threshold 0.941677
"""
FIRE = """\
lattice/quasistatic: 5 bonds broke (5 in tension, 0 in shear) in 6 relaxations (868 minimiser iterations); largest remaining ratio to the threshold 0.966078
lattice/quasistatic: 1 bonds broke (1 in tension, 0 in shear) in 2 relaxations (400 time steps); largest remaining ratio to the threshold 0.5
"""


def test_relax_local_moves_are_summed(tmp_path):
    (tmp_path / "log.lammps").write_text(LOG)
    assert relaxation_costs(tmp_path / "log.lammps", 4200) == {
        "breaks": 73, "relaxations": 77, "iterations": 12759, "updates": 481559 + 29620913,
        "factorisations": 0}


def test_minimiser_iterations_and_time_steps_evaluate_every_particle(tmp_path):
    (tmp_path / "log.lammps").write_text(FIRE)
    assert relaxation_costs(tmp_path / "log.lammps", 100) == {
        "breaks": 6, "relaxations": 8, "iterations": 1268, "updates": 1268 * 100,
        "factorisations": 0}


DIRECT = """\
lattice/quasistatic: 0 bonds broke (0 in tension, 0 in shear) in 2 relaxations (3 solves, 1 factorisations); largest remaining ratio to the threshold 0.43
lattice/quasistatic: 12 bonds broke (12 in tension, 0 in shear) in 3 relaxations (15 solves, 0 factorisations); largest remaining ratio to the threshold 0.97
"""


def test_relax_direct_solves_update_every_particle(tmp_path):
    (tmp_path / "log.lammps").write_text(DIRECT)
    # a solve gives every particle its displacement: solves x particles updates
    assert relaxation_costs(tmp_path / "log.lammps", 100) == {
        "breaks": 12, "relaxations": 5, "iterations": 18, "updates": 18 * 100,
        "factorisations": 1}
