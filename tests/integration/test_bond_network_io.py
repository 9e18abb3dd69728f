"""write_lattice_bonds / read_lattice_bonds: the bond network as text.  A fracturing 2D
scene (bonds broken in tension and in shear, new contacts with shear springs) is written as
a data file plus a bond-network file; a fresh session that reads both (on 1 or 2 ranks)
continues like the original run.  Bad files are refused with the line that is wrong."""

from __future__ import annotations

import re

import numpy as np
import pytest
from bonded_lattice.io import read_atom_dump
from helpers.decks import block_2d_deck, opening, run_deck
from helpers.materials import QUARTZ_2D, WEAK_SHEAR, coeffs

# quartz with 0.3 of the shear strength (helpers.materials), so that bonds also fail in shear
COEFFS = coeffs(WEAK_SHEAR[2])
SHAKE = """
variable        vx atom 0.3*normal(0,1,4931)+300*(y-3e-3)
variable        vy atom 0.3*normal(0,1,7253)
velocity        all set v_vx v_vy NULL units box
fix             nve all nve
compute         b all lattice/bonds
thermo_style    custom step pe ke c_b[1] c_b[2] c_b[3] c_b[4]
thermo          100
timestep        2.0e-8
"""
ORIGINAL = block_2d_deck("-4 16 -4 14", "0 12 0 10", coeffs=COEFFS) + SHAKE + """
run             600
write_lattice_bonds network.txt
write_data      state.data
run             400
write_dump      all custom final.dump id x y vx vy modify sort id format float %.17g
"""
RESUMED = opening(box=None) + """\
pair_style      lattice/bond
read_data       {dir}/state.data
read_lattice_bonds {dir}/network.txt
neighbor        1.0e-4 bin
fix             nve all nve
compute         b all lattice/bonds
thermo_style    custom step pe ke c_b[1] c_b[2] c_b[3] c_b[4]
thermo          100
timestep        2.0e-8
run             400
write_dump      all custom final.dump id x y vx vy modify sort id format float %.17g
"""


def read_dump(path):
    return read_atom_dump(path)[1]


@pytest.fixture(scope="module")
def original(tmp_path_factory):
    work = tmp_path_factory.mktemp("original")
    res = run_deck(ORIGINAL, work)
    assert res.returncode == 0, res.output[-2000:]
    return work, res


def test_network_file_is_readable_text(original):
    work, res = original
    lines = (work / "network.txt").read_text().splitlines()
    assert lines[0] == "# BONDED_LATTICE bond network, format 1"
    records = [l.split() for l in lines if not l.startswith("#")]
    states = {r[2] for r in records}
    # the scene at step 600 holds bonds intact and broken both ways (contacts of
    # never-bonded pairs come later)
    assert {"intact", "tension", "shear"} <= states <= {"intact", "tension", "shear", "contact"}
    owners, partners = (np.array([int(r[k]) for r in records]) for k in (0, 1))
    assert np.all(owners < partners)
    assert list(zip(owners, partners)) == sorted(zip(owners, partners))
    # the counts line matches the records and the compute's counts at step 600
    row = res.thermo[0]
    at600 = list(row["Step"]).index(600)
    n_intact = sum(r[2] == "intact" for r in records)
    assert n_intact == row["c_b[1]"][at600]
    assert sum(r[2] == "tension" for r in records) == row["c_b[2]"][at600]
    assert f"# records {len(records)}: intact {n_intact}," in lines[2]
    # shear springs of intact bonds and closed contacts are carried
    assert any(float(r[3]) != 0.0 for r in records if r[2] in ("intact", "contact", "shear"))


@pytest.mark.parametrize("np_", [1, pytest.param(2, marks=pytest.mark.mpi)])
def test_data_file_plus_network_continues_the_run(original, tmp_path, np_):
    work, res = original
    resumed = run_deck(RESUMED.format(dir=work), tmp_path, np=np_)
    assert resumed.returncode == 0, resumed.output[-2000:]
    assert "pair_style lattice/bond: created" not in resumed.output
    a, b = read_dump(work / "final.dump"), read_dump(tmp_path / "final.dump")
    assert np.array_equal(a[:, 0], b[:, 0])
    # the same trajectory to round-off (the data file keeps 17 digits)
    assert np.max(np.abs(a[:, 1:3] - b[:, 1:3])) < 1e-12 * 1.0e-3
    last = resumed.thermo[-1]
    for col in ("c_b[1]", "c_b[2]", "c_b[3]"):
        assert last[col][-1] == res.thermo[-1][col][-1]


@pytest.mark.parametrize("change,message", [
    (lambda t: t.replace("format 1", "format 7"), "unknown format"),
    (lambda t: re.sub(r"(?m)^(\d+ \d+) intact ", r"\1 bonded ", t, count=1),
     "is not 'owner partner state"),
    (lambda t: "\n".join(l for l in t.splitlines() if not l.startswith("# BONDED")),
     "not a write_lattice_bonds file"),
    (lambda t: t + "99999 100000 intact 0 0 0\n", "name an owner atom ID that does not exist"),
])
def test_bad_network_files_are_refused(original, tmp_path, change, message):
    work, _ = original
    (tmp_path / "network.txt").write_text(change((work / "network.txt").read_text()))
    (tmp_path / "state.data").write_bytes((work / "state.data").read_bytes())
    res = run_deck(RESUMED.format(dir=tmp_path), tmp_path / "run")
    assert res.returncode != 0
    assert message in res.output, res.output[-1500:]


def test_network_cannot_be_read_over_existing_bonds(tmp_path):
    deck = block_2d_deck("-2 8 -2 8", "0 3 0 3", coeffs=QUARTZ_2D) + """
run             0
write_lattice_bonds net.txt
read_lattice_bonds net.txt
"""
    res = run_deck(deck, tmp_path)
    assert res.returncode != 0
    assert "a bond network exists already" in res.output
