"""Bond records travel with their atoms: a vibrating bonded block drifts once
around a periodic box, crossing subdomain and periodic boundaries, and ends
where the 1-rank run ends, with the same bonds and spring energy."""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.io import read_atom_dump
from helpers.decks import block_2d_deck, run_deck
from helpers.materials import D, QUARTZ, coeffs

# quartz springs that never break (Xb 1 m, Fs0 1e9 N/m): the block only vibrates
DECK = block_2d_deck("0 24 0 6", "2 10 1 4", boundary="p p p",
                     coeffs=coeffs(QUARTZ[2], Xb=1.0, Fs0=1.0e9)) + """\
reset_atoms     id sort yes
# a random vibration of ~0.02 m/s (seeded per atom position, so it does not
# depend on the rank count) plus a drift of one box length in the run
velocity        all create 1.0e20 4928459 loop geom
variable        vx atom vx+0.024/(STEPS*1.0e-8)
velocity        all set v_vx NULL 0 units box
compute         b all lattice/bonds
thermo_style    custom step pe ke c_b[1] c_b[2] c_b[3] c_b[4]
thermo          1000
fix             nve all nve
timestep        1.0e-8
run             STEPS
write_dump      all custom final.dump id x y vx vy modify sort id format float %.17g
"""


def read(path):
    """The rows of a dump sorted by id: id x y vx vy."""
    return read_atom_dump(path)[1]


BALANCE = "fix             lb all balance 500 1.05 shift x 10 1.05\n"


@pytest.mark.mpi
@pytest.mark.parametrize("np_,balance,frame,integrator", [
    (2, False, "fixed", "nve"), (3, False, "fixed", "nve"), (4, False, "fixed", "nve"),
    (4, True, "fixed", "nve"), (2, False, "corotational", "nve"),
    (3, False, "corotational", "nve"),
    (2, False, "fixed", "lattice/nve"), (4, True, "fixed", "lattice/nve"),
    (3, False, "corotational", "lattice/nve")])
def test_drift_around_periodic_box(tmp_path, np_, balance, frame, integrator):
    """Also with more ranks than cores (4 on the 2-core machine), with fix balance
    moving the subdomain boundaries while the block drifts through them, with the
    corotational shear frame (its rotation fit sums ghosts' terms across subdomain and
    periodic boundaries), and with fix lattice/nve, which measures each step's
    displacements while it moves the atoms (they migrate with their atoms)."""
    # 4 ranks on 2 cores are slow (busy-waiting MPI): the same trip in fewer, longer steps
    steps = "1000" if np_ > 2 else "5000"
    plain = DECK.replace("STEPS", steps).replace("fix             nve all nve\n",
                                                 f"fix             nve all {integrator}\n")
    if frame != "fixed":
        plain = plain.replace("pair_style      lattice/bond\n",
                              f"pair_style      lattice/bond shear_frame {frame}\n")
        assert frame in plain
    deck = plain.replace(f"fix             nve all {integrator}\n",
                         f"fix             nve all {integrator}\n" + (BALANCE if balance else ""))
    one = run_deck(plain, tmp_path / "one")
    many = run_deck(deck, tmp_path / "many", np=np_)
    assert one.returncode == 0 and many.returncode == 0, many.output[-2000:]
    t1, tn = one.thermo[0], many.thermo[0]
    # the vibration is elastic: no bond breaks, energy is exchanged
    assert t1["c_b[1]"][-1] == t1["c_b[1]"][0] and t1["c_b[2]"][-1] == 0
    assert np.all(tn["c_b[1]"] == t1["c_b[1]"])
    assert t1["PotEng"][-1] > 0
    # the springs hardly stretch (energies at the round-off of the positions): compare
    # against a millionth of a millionth of one bond's breaking energy, Kn Xb^2 / 2
    np.testing.assert_allclose(tn["PotEng"], t1["PotEng"], rtol=1e-9,
                               atol=1e-12 * 0.5 * QUARTZ[2].Kn * QUARTZ[2].Xb**2)
    a, b = read(tmp_path / "one" / "final.dump"), read(tmp_path / "many" / "final.dump")
    assert np.array_equal(a[:, 0], b[:, 0])
    # positions (wrapped into the box) agree to round-off
    delta = a[:, 1:3] - b[:, 1:3]
    delta[:, 0] -= 0.024 * np.round(delta[:, 0] / 0.024)
    assert np.max(np.abs(delta)) < 1e-12 * D
    # the block really travelled across the ranks: many reneighbourings
    builds = int(many.output.split("Neighbor list builds =")[1].split()[0])
    assert builds > 20
