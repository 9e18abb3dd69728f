"""3D close-packed block, periodic in x and y so that bonds cross the periodic
boundaries, pulled apart along z by its top and bottom layers until it
fractures; the same on 1 and 2 ranks (the ranks split a periodic direction)."""

from __future__ import annotations

import numpy as np
import pytest
from bonded_lattice.io import read_atom_dump
from helpers.decks import run_deck
from helpers.materials import D, QUARTZITE_3D

# quartzite in 3D (helpers.materials): Kn Ks Xb Fs0 mu_p, mass rho*sqrt(2)*d^3/2
DECK = f"""
units           si
dimension       3
boundary        p p f
processors      * * 1    # split the periodic directions between ranks
atom_style      sphere
newton          on
lattice         fcc $(sqrt(2)*{D})
region          box block 0 4 0 4 -0.2 4.1
create_box      1 box
region          block block INF INF INF INF 0 3.9
create_atoms    1 region block
reset_atoms     id sort yes
set             type 1 diameter {D}
set             type 1 mass $(2650*sqrt(2)*{D}^3/2)
pair_style      lattice/bond
pair_coeff      1 1 {QUARTZITE_3D}
neighbor        $(0.1*{D}) bin
variable        zmin equal $(bound(all,zmin))
variable        zmax equal $(bound(all,zmax))
region          toplayer block INF INF INF INF $(v_zmax-0.25*{D}) INF units box
region          botlayer block INF INF INF INF INF $(v_zmin+0.25*{D}) units box
group           top region toplayer
group           bottom region botlayer
group           inner subtract all top bottom
velocity        top set 0 0 0.05 units box
velocity        bottom set 0 0 -0.05 units box
fix             ztop top setforce 0 0 0
fix             zbot bottom setforce 0 0 0
fix             nve all nve
fix             damp all lattice/viscous 0.05
compute         b all lattice/bonds
compute         peratom all lattice/bonds
thermo_style    custom step pe ke f_zbot[3] f_ztop[3] c_b[1] c_b[2] c_b[3] c_b[4]
thermo          500
dump            d all custom 1000 dump.3d.* id x y z c_peratom
dump_modify     d sort id format float %.17g
timestep        1.0e-8
run             6000
"""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    out = {}
    for np_ in (1, 2):
        work = tmp_path_factory.mktemp(f"p3d{np_}")
        res = run_deck(DECK, work, np=np_)
        assert res.returncode == 0, res.output[-3000:]
        out[np_] = (work, res)
    return out


def read(path):
    """The rows of a dump sorted by id: id x y z c_peratom."""
    return read_atom_dump(path)[1]


@pytest.mark.mpi
def test_periodic_bonds_created_and_counted(runs):
    _, res = runs[1]
    natoms = 4 * 4 * 4 * 4  # 4 fcc cells per direction in x, y; 4 cells in z
    first = res.thermo[0]
    # a periodic fcc layer stack: every atom has 12 neighbours except the
    # top and bottom layers (which lack 4 each): bonds = (12*N - 4*2*layer)/2
    layer = 2 * 4 * 4
    assert first["c_b[1]"][0] == (12 * natoms - 4 * 2 * layer) / 2
    work, _ = runs[1]
    counts = read(work / "dump.3d.0")[:, 4]
    assert counts.sum() == 2 * first["c_b[1]"][0]
    assert counts.max() == 12 and counts.min() == 8


@pytest.mark.mpi
def test_periodic_3d_same_on_two_ranks(runs):
    (w1, r1), (w2, r2) = runs[1], runs[2]
    t1, t2 = r1.thermo[0], r2.thermo[0]
    broken1 = t1["c_b[2]"] + t1["c_b[3]"]
    assert broken1[-1] > 0, "the block must fracture"
    # IDs are assigned by spatial sort, independent of the rank count
    for step in range(0, 7000, 1000):
        a, b = read(w1 / f"dump.3d.{step}"), read(w2 / f"dump.3d.{step}")
        assert np.array_equal(a[:, 0], b[:, 0])
        before_break = broken1[t1["Step"] == step][0] == 0
        if before_break:
            # round-off only: summation order differs
            assert np.max(np.abs(a[:, 1:4] - b[:, 1:4])) < 1e-12 * D
            assert np.array_equal(a[:, 4], b[:, 4])
    for col in ("c_b[2]", "c_b[3]"):
        assert t2[col][-1] == pytest.approx(t1[col][-1], rel=0.01, abs=1)
    for col in ("f_ztop[3]", "f_zbot[3]"):
        np.testing.assert_allclose(t2[col], t1[col], rtol=0.01, atol=1e-3 * np.max(np.abs(t1[col])))
