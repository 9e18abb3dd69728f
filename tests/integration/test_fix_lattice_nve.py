"""fix lattice/nve: velocity Verlet with the arithmetic of fix nve, compiled for
2D (x and y only: no fix enforce2d) and 3D, with a loop without group test for
group all.  A fracturing scene (random velocities on a simple shear: bonds
break in tension and shear, fragments collide) must end bit for bit where fix
nve (plus fix enforce2d in 2D) takes it, with damping on part of the block."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import INPUTS
from helpers.decks import SHAKE, atoms_at, opening, run_deck, shaken_block
from helpers.materials import D, WEAK_SHEAR, coeffs

COEFFS = {dim: "* * " + coeffs(WEAK_SHEAR[dim]) for dim in (2, 3)}


def run_scene(dim: int, integrator: str, group: str, steps: int = 800) -> tuple[np.ndarray, list]:
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.commands_string(shaken_block(dim) + f"""
pair_style      lattice/bond
pair_coeff      {COEFFS[dim]}
neighbor        {0.1 * D} bin
{SHAKE.format(v=0.3, rate=300.0, mid=3 * D, vz='v_vz' if dim == 3 else 'NULL')}
compute         b all lattice/bonds
thermo          {steps}
fix             move {group} {integrator}
fix             damp half lattice/viscous 0.5
{"fix plane all enforce2d" if dim == 2 and integrator == "nve" else ""}
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
run             {steps}
""")
        ids = lmp.numpy.extract_atom("id")
        order = np.argsort(ids)
        x = np.array(lmp.numpy.extract_atom("x"))[order]
        v = np.array(lmp.numpy.extract_atom("v"))[order]
        counts = [lmp.extract_compute("b", 0, 1)[k] for k in range(4)]
    finally:
        lmp.close()
    return np.hstack([x, v]), counts


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("group", ["all", "half"])
def test_same_trajectory_as_fix_nve(dim, group):
    ref, c_ref = run_scene(dim, "nve", group)
    ours, c_ours = run_scene(dim, "lattice/nve", group)
    intact, tension, shear, contacts = c_ref
    assert tension > 0 and contacts > 0, c_ref    # a violent scene: cracks and collisions
    assert c_ours == c_ref
    assert np.array_equal(ours, ref), np.max(np.abs(ours - ref))
    if dim == 2:
        assert np.all(ours[:, 2] == 0.0) and np.all(ours[:, 5] == 0.0)    # z and vz untouched


def test_per_type_mass_matches_fix_nve(lmp_instance):
    """atom_style atomic: masses per type (mass command), particles in free flight
    under gravity reach x = x0 + v0 t + g t^2 / 2 (velocity Verlet is exact for a
    constant force) exactly like fix nve."""
    lmp = lmp_instance
    lmp.commands_string(opening(3, box="0 10 0 10 0 10", types=2, atom_style="atomic")
                        + atoms_at([(1, 1, 5), (5, 5, 8)], types=[1, 2]) + """\
mass            1 2.0
mass            2 3.0
velocity        all set 1.0 -0.5 0.25
pair_style      zero 1.0
pair_coeff      * *
fix             move all lattice/nve
fix             g all gravity 9.81 vector 0 0 -1
timestep        0.01
run             100
""")
    x = np.array(lmp.numpy.extract_atom("x"))
    t = 1.0
    expected_z = np.array([5.0, 8.0]) + 0.25 * t - 0.5 * 9.81 * t ** 2
    assert np.allclose(x[:, 0], np.array([1.0, 5.0]) + t, rtol=0, atol=1e-12)
    assert np.allclose(x[:, 2], expected_z, rtol=0, atol=1e-12)


def test_measured_displacements_give_the_same_bits(tmp_path):
    """fix lattice/nve on every atom measures each step's displacements while it
    moves the atoms, and the record store skips its own pass; any other fix that
    may move atoms (here a fix nve on an empty group) brings the pass back.  Both
    give the same bits through elastic loading and fracture (2D tension deck)."""
    deck = (INPUTS / "in.tension2d").read_text()
    dump = ("write_dump      all custom final.dump id x y vx vy c_bonds_per_atom "
            "modify sort id format float %.17g\n")
    deck = deck.replace("compute         bonds all lattice/bonds\n",
                        "compute         bonds all lattice/bonds\n"
                        "compute         bonds_per_atom all lattice/bonds\n") + dump
    args = ["-var", "N", "15", "-var", "vpull", "0.02", "-var", "steps", "4600"]
    measured = run_deck(deck, tmp_path / "measured", args=args)
    idle = "group           idle empty\nfix             idle idle nve\n"
    passed = run_deck(deck.replace("fix             integrate all lattice/nve\n",
                                   "fix             integrate all lattice/nve\n" + idle),
                      tmp_path / "pass", args=args)
    assert measured.returncode == 0 and passed.returncode == 0, passed.output[-2000:]
    assert "measures the steps" in measured.output
    assert "measures the steps" not in passed.output
    a = (tmp_path / "measured" / "final.dump").read_text()
    b = (tmp_path / "pass" / "final.dump").read_text()
    assert a == b
    broken = measured.thermo[-1]["c_bonds[2]"][-1]
    assert broken > 0, "the run must reach fracture"
