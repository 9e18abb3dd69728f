"""Errors that name the real cause (issue 17): atoms lost from a non-periodic box,
coincident and overlapping atoms at bonding, a zero diameter, an atom off the 2D plane,
atoms renumbered after bonding, a runaway atom; and the README's minimal input script,
which must run twice in a row.

Each error test also checks that the message does not blame a wrong cause (the time step,
the neighbour skin, a bond length) as the messages before these checks did.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from bonded_lattice.io import read_atom_dump
from helpers import REPO
from helpers.decks import block_2d_deck, run_deck

README = REPO / "README.md"

# a 2D quartz block (7 x 5 rows of 1 mm particles) with room around it in the box
ROOMY = block_2d_deck("-1 7 -1 5", "0 6 0 4")
# the same block filling its box exactly: particles on the fixed (f) boundaries
TIGHT = block_2d_deck("0 6 0 4", "0 6 0 4")
INTEGRATE = "fix 1 all nve\ntimestep 2.0e-8\n"
BONDS = "compute b all lattice/bonds\nthermo_style custom step atoms c_b[1]\nthermo 10\n"


def readme_script() -> str:
    """The README's minimal input script, as printed there."""
    text = README.read_text()
    match = re.search(r"## A minimal input script\n\n```\n(.*?)```", text, re.S)
    assert match, "README.md has no 'A minimal input script' code block"
    return match.group(1)


def error_line(res) -> str:
    assert res.returncode != 0, f"the run did not stop:\n{res.output[-1500:]}"
    return res.error


def assert_not_blamed(text: str, *wrong: str) -> None:
    for w in wrong:
        assert w not in text, f"{w!r} blamed in: {text}"


# ---------------------------------------------------------------- README, lost atoms

def test_readme_minimal_script_runs_twice(tmp_path):
    script = readme_script()
    assert script.rstrip().endswith("run             1000")
    res = run_deck(script + "run             1000\n", tmp_path)
    assert res.returncode == 0, res.error
    assert len(res.thermo) == 2
    assert res.thermo[1]["Step"][-1] == 2000
    assert "WARNING: pair_style" not in res.output and "Lost atoms" not in res.output
    # nothing breaks under gravity: the same bonds at the end of both runs
    assert res.thermo[0]["c_bonds[1]"][0] == res.thermo[1]["c_bonds[1]"][-1] > 0


# the bottom row starts on the box's lower boundary and moves down by 2e-10 m
# in 10 steps: LAMMPS deletes it at the next reneighbouring (the second run's setup)
LEAVING = TIGHT + """
region          bottom block INF INF INF 0.1 INF INF
group           bottom region bottom
velocity        bottom set 0 -1.0e-3 0 units box
""" + INTEGRATE + BONDS


def test_atoms_leaving_the_box_are_lost_atoms_not_lost_partners(tmp_path):
    res = run_deck(LEAVING + "run 10\nrun 10\n", tmp_path)
    err = error_line(res)
    # LAMMPS' own message, after ours that names the cause and the remedies
    assert "Lost atoms: original" in err
    assert "particles left the non-periodic box" in res.output
    for remedy in ("larger than the block", "boundary s", "thermo_modify lost ignore"):
        assert remedy in res.output
    assert_not_blamed(res.output, "lost its partner", "communication cutoff", "skin")


def bond_records(path: Path) -> set[tuple[int, int, str]]:
    """(owner, partner, state) of a write_lattice_bonds file."""
    rows = [line.split() for line in path.read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    return {(int(r[0]), int(r[1]), r[2]) for r in rows}


@pytest.mark.parametrize("np_", [1, 2])
def test_lost_atoms_take_their_bonds_with_them(tmp_path, np_):
    # thermo_modify lost ignore: the run goes on; the remaining particles keep every
    # bond among themselves and lose those to the deleted ones
    res = run_deck(LEAVING + "thermo_modify lost ignore\nrun 10\n"
                   "write_lattice_bonds before.bonds\nrun 10\n"
                   "write_lattice_bonds after.bonds\n"
                   "write_dump all custom ids.txt id modify sort id\n", tmp_path, np=np_)
    assert res.returncode == 0, res.error
    assert "particles left the non-periodic box" in res.output
    remaining = {int(v) for v in read_atom_dump(tmp_path / "ids.txt")[1][:, 0]}
    assert 0 < len(remaining) < res.thermo[0]["Atoms"][0]
    before = bond_records(tmp_path / "before.bonds")
    kept = {r for r in before if r[0] in remaining and r[1] in remaining}
    assert kept and len(kept) < len(before)
    assert bond_records(tmp_path / "after.bonds") == kept
    assert res.thermo[-1]["c_b[1]"][-1] == len(kept)


# ---------------------------------------------------------------- at bonding

def test_coincident_atoms_are_named(tmp_path):
    # a second atom on top of atom 5 (2 mm, 0): bonded at distance 0 it gave NaN
    res = run_deck(ROOMY + "create_atoms 1 single 2 0 0\nset type 1 diameter 1.0e-3\n"
                   "set type 1 mass 2.295e-3\n" + INTEGRATE + "run 10\n", tmp_path)
    err = error_line(res)
    assert re.search(r"atoms 5 and \d+ are at the same position \(0\.002 0 0", err), err
    assert "coincident" in err and "delete_atoms overlap" in err
    assert_not_blamed(err.lower(), "time step", "nan", "unstable")


def test_particle_too_large_for_its_lattice_site_is_named(tmp_path):
    # 20% too large: its bonds would start compressed by 9% of their rest length
    res = run_deck(ROOMY + "set atom 5 diameter 1.2e-3\n" + INTEGRATE + "run 10\n", tmp_path)
    err = error_line(res)
    m = re.search(r"atoms (\d+) and (\d+) overlap at bonding: their distance 0.001 is 9.09% below "
                  r"r_i \+ r_j = 0.0011", err)
    assert m and "5" in m.groups(), err
    assert "radii 0.0005 and 0.0006" in err or "radii 0.0006 and 0.0005" in err
    assert "0.001089 to 0.001111" in err and "tolerance 0.01" in err
    assert_not_blamed(err, "time step")


def test_slightly_compressed_lattice_still_bonds(tmp_path):
    # a lattice 0.5% closer than its diameters (within the bonding tolerance): no error
    res = run_deck(ROOMY + "set type 1 diameter 1.005e-3\n" + INTEGRATE + BONDS + "run 0\n",
                   tmp_path)
    assert res.returncode == 0, res.error
    assert res.thermo[-1]["c_b[1]"][-1] > 0


def test_zero_diameter_is_named(tmp_path):
    res = run_deck(ROOMY + "set atom 5 diameter 0\n" + INTEGRATE + "run 10\n", tmp_path)
    err = error_line(res)
    assert "atom 5 has diameter 0" in err and "diameter > 0" in err
    assert "set atom 5 diameter" in err


def test_atom_off_the_2d_plane_is_named(tmp_path):
    res = run_deck(ROOMY + "set atom 5 z 1.0e-4\n" + INTEGRATE + "run 10\n", tmp_path)
    err = error_line(res)
    assert "atom 5 is at z = 0.0001" in err and "off the plane" in err
    # LAMMPS checks z only where atoms are made: the message says so
    assert "create_atoms, read_data" in err


# ---------------------------------------------------------------- after bonding

def test_renumbering_after_bonding_is_named(tmp_path):
    # reset_atoms id sort yes renumbers the block by spatial bins: records name old IDs
    res = run_deck(ROOMY + INTEGRATE + "run 10\nreset_atoms id sort yes\nrun 10\n", tmp_path)
    err = error_line(res)
    assert "atom IDs changed after the bonds were made" in err
    assert "reset_atoms id" in err and "renumber before the first run" in err
    assert_not_blamed(err, " long", "skin")


@pytest.mark.parametrize("integrator,np_", [("nve", 1), ("lattice/nve", 2)])
def test_runaway_atom_is_reported_by_the_stability_test(tmp_path, integrator, np_):
    # 1e4 m/s: 2e-4 m (0.4 radius) in the first step, which also stretches its
    # bonds beyond the ghost cutoff and triggers a reneighbouring
    res = run_deck(ROOMY + f"set atom 12 vx 1.0e4\nfix 1 all {integrator}\n"
                   "timestep 2.0e-8\nrun 100\n", tmp_path, np=np_)
    err = error_line(res)
    assert "atom 12 moved 0.0002 in one time step at step 1" in err
    assert "unstable" in err
    assert_not_blamed(err, "skin", "communication cutoff")


def test_runaway_found_by_the_force_loop_on_rank_1_is_reported(tmp_path):
    # 4e3 m/s: 8e-5 m (0.16 radius, above the tenth of a radius) in the first step,
    # but the bonds stay inside the ghost cutoff (1e-3 + 8e-5 < 1.11e-3 m): no record
    # trouble, so the force loop's own test finds it, on the rank that owns atom 50
    # alone (rank 1 of the 1 by 2 grid: y = 5.2e-3 m is above the middle, 3.46e-3 m);
    # its message must reach the output before the abort
    res = run_deck(ROOMY + "set atom 50 vx 4.0e3\nfix 1 all lattice/nve\n"
                   "timestep 2.0e-8\nrun 100\n", tmp_path, np=2)
    err = error_line(res)
    assert "ERROR on proc 1" in err
    # 4e3 m/s x 2e-8 s = 8e-5 m, printed with 6 significant digits
    assert "atom 50 moved 8e-05 in one time step at step 1" in err
    assert "unstable" in err
    assert_not_blamed(err, "skin", "communication cutoff")


# ---------------------------------------------------------------- Python: failed runs

def bad_scene():
    """A tiny polycrystal whose bond has a negative breaking stretch: the Python side
    writes it, LAMMPS refuses it (pair_coeff ... Xb = -1e-06 is out of range)."""
    from bonded_lattice.conversion import BondParameters
    from bonded_lattice.scenes import Scene

    return Scene("polycrystal", n_x=10, n_steps=2, bond=BondParameters(1e8, 0.0, -1e-6, 1.0, 0.0))


def test_failed_scene_run_raises_lammps_error(tmp_path):
    from bonded_lattice.scene_study import run_scene

    with pytest.raises(RuntimeError) as info:
        run_scene(bad_scene(), tmp_path, pictures=False)
    text = str(info.value)
    assert "the scene run failed" in text
    assert "ERROR" in text and "Xb = -1e-06 is out of range: need Xb > 0" in text
    assert "Last input line: pair_coeff" in text


def cli(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "bonded_lattice.cli", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=120)


def test_failed_scene_run_from_the_command_line(tmp_path):
    res = cli("scene", "polycrystal", "--n", "10", "--steps", "2", "--bond", "1e8", "-0.000001",
              "--run", "--np", "1", "--quiet", "--out", "scene", cwd=tmp_path)
    assert res.returncode != 0
    assert "Traceback" not in res.stderr, res.stderr
    assert res.stderr.startswith("bonded-lattice scene: the scene run failed")
    assert "ERROR" in res.stderr and "Xb = -1e-06 is out of range" in res.stderr


def test_failed_test_run_from_the_command_line(tmp_path):
    # platens at 1e4 m/s: the first step is unstable
    res = cli("run", "--dim", "2", "--test", "tension", "--n", "5", "--speed", "1e4",
              "--np", "1", "--quiet", "--out", "run", cwd=tmp_path)
    assert res.returncode != 0
    assert "Traceback" not in res.stderr, res.stderr
    assert res.stderr.startswith("bonded-lattice run: LAMMPS failed")
    assert "ERROR" in res.stderr and "in one time step" in res.stderr
