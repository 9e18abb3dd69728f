"""The openings of the tests' LAMMPS decks, and running a deck with mpirun.

Two ways to run LAMMPS in the tests:
- the ``lmp_instance`` fixture (tests/conftest.py): an in-process ``lammps`` object (fast,
  one rank);
- :func:`run_deck`: ``mpirun -np N lmp`` in a folder, for several ranks, error messages and
  restart files.

A deck starts with :func:`opening` (units, dimension, boundary, atom style, newton, the box)
and then places atoms one by one (:func:`atoms_at`) or fills a lattice block
(:func:`lattice_block`, :func:`block_2d_deck`); :func:`sphere_props` and :func:`pair_lines`
give the particles' size and mass and the pair style.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from bonded_lattice import runner
from bonded_lattice.runner import RunResult

from .materials import D, QUARTZ_2D, QUARTZ_MASS

__all__ = ["SHAKE", "TOUCHING_TRIANGLE", "atoms_at", "block_2d_deck", "lattice_block", "opening", "pair_lines",
           "patchy_grains", "run_deck", "shaken_block", "sphere_props"]


def run_deck(script: str, workdir: Path, np: int = 1, name: str = "in.test",
             files: dict[str, str] | None = None,
             args: list[str] | None = None) -> RunResult:
    """Write ``script`` to ``workdir/name`` (and ``files``: name -> text) and run it with
    ``mpirun -np np lmp`` in ``workdir``; ``args``: more command-line arguments of lmp."""
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / name).write_text(script)
    for fname, content in (files or {}).items():
        (workdir / fname).write_text(content)
    return runner.run_deck(workdir / name, workdir, np_=np, progress=False, extra_args=args)


def opening(dim: int = 2, box: str | None = "-0.01 0.01 -0.01 0.01 -0.001 0.001",
            types: int = 1, boundary: str | None = None, atom_style: str = "sphere",
            newton: str = "on", lattice: str | None = None, settings: str = "") -> str:
    """``units si`` to ``create_box``: boundaries ``f f p`` (2D) or ``f f f`` (3D) unless
    given; ``settings``: lines that must come before the box (``atom_modify map array``);
    ``lattice``: the arguments of a lattice command before the box (``hex 0.001``);
    ``box``: ``xlo xhi ylo yhi zlo zhi`` of the box region (in lattice units after a
    lattice, else in metres), None for no box (a data file follows); ``types`` atom types."""
    if boundary is None:
        boundary = "f f p" if dim == 2 else "f f f"
    text = f"""
units           si
dimension       {dim}
boundary        {boundary}
atom_style      {atom_style}
newton          {newton}
""" + (settings.rstrip("\n") + "\n" if settings else "")
    if lattice is not None:
        text += f"lattice         {lattice}\n"
    if box is not None:
        text += f"region          box block {box}\ncreate_box      {types} box\n"
    return text


def atoms_at(positions: Iterable[tuple[float, ...]], types: Iterable[int] | None = None,
             units: str = "") -> str:
    """One ``create_atoms T single x y z`` line per position (type 1 unless ``types``);
    ``units``: the keyword ``units box`` or ``units lattice`` appended to each line."""
    positions = list(positions)
    types = [1] * len(positions) if types is None else list(types)
    tail = f" {units}" if units else ""
    return "".join(f"create_atoms    {t} single {' '.join(str(c) for c in (*xyz, 0)[:3])}{tail}\n"
                   for t, xyz in zip(types, positions))


TOUCHING_TRIANGLE = atoms_at([(0, 0), (0.001, 0), (0.0005, 0.000866025403784)], types=[1, 1, 2])
"""Three touching 1 mm particles (types 1, 1, 2) at the origin, for decks that check input."""


def sphere_props(diameter: float = D, mass: float = QUARTZ_MASS[2], which: str = "atom *") -> str:
    """``set`` lines for the diameter and the mass of atom_style sphere particles (default:
    1 mm quartz in 2D, per metre of thickness); ``which``: the set command's selection."""
    return (f"set             {which} diameter {diameter!r}\n"
            f"set             {which} mass {mass!r}\n")


def pair_lines(coeffs: str | dict[str, str | None] = QUARTZ_2D, style: str = "") -> str:
    """``pair_style lattice/bond [style]`` and its ``pair_coeff`` lines: ``coeffs`` is the
    coefficient text of ``* *`` or a dict ``"I J" -> text`` (None: no line for that pair)."""
    table = {"* *": coeffs} if isinstance(coeffs, str) else coeffs
    lines = f"pair_style      lattice/bond{' ' + style if style else ''}\n"
    return lines + "".join(f"pair_coeff      {ij} {c}\n" for ij, c in table.items()
                           if c is not None)


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
lattice         hex {D if scale is None else repr(scale)}
region          box block {box} -0.5 0.5
create_box      {types} box
region          block block {block} -0.5 0.5
"""
    return f"""
dimension       3
boundary        f f f
lattice         fcc {D * 2 ** 0.5 if scale is None else repr(scale)}
region          box block {box}
create_box      {types} box
region          block block {block}
"""


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
lattice         hex {D!r}
region          box block {box} -0.5 0.5
create_box      {types} box
region          block block {block} -0.5 0.5
create_atoms    1 region block
set             type 1 diameter {D!r}
set             type 1 mass {QUARTZ_MASS[2]!r}
{pair}neighbor        1.0e-4 bin
"""


def patchy_grains(size: str, per_row: int, amplitude: float, rate: float) -> str:
    """Square grains for the heterogeneity keywords: atoms sorted by position (``reset_atoms``),
    grain ``floor(x/size) + per_row floor(y/size)`` in ``i_grain`` and the stiffness factor
    ``1 + amplitude sin(rate grain)`` in ``d_stiff``; ``size``: the grain size in metres, as
    the deck writes it (``8.0e-3``)."""
    return f"""reset_atoms     id sort yes
fix             props all property/atom i_grain d_stiff
variable        gid atom floor(x/{size})+{per_row}*floor(y/{size})
variable        sf atom 1.0+{amplitude}*sin(v_gid*{rate})
set             atom * i_grain v_gid
set             atom * d_stiff v_sf
"""


# random velocities on a simple shear: bonds break in tension and in shear, fragments collide
# (new contacts with friction); format with v (m/s), rate (1/s), mid (y of no shear
# velocity, m) and vz ('v_vz' in 3D, 'NULL' in 2D)
SHAKE = """
variable        vx atom {v}*normal(0,1,4931)+{rate}*(y-{mid})
variable        vy atom {v}*normal(0,1,7253)
variable        vz atom {v}*normal(0,1,1197)
velocity        all set v_vx v_vy {vz} units box
"""


def shaken_block(dim: int) -> str:
    """The block of the shaken scenes (tests of the compiled loop variants and of
    fix lattice/nve): 12 x 10 (2D) or 6 x 6 x 6 (3D) lattice units of 1 mm particles,
    two atom types, and the group 'half' (the lower half of the IDs); no pair style yet."""
    if dim == 2:
        block = lattice_block(2, "-4 16 -4 14", "0 12 0 10", types=2) + (
            f"create_atoms    1 region block\nset             type 1 mass {QUARTZ_MASS[2]!r}\n")
    else:
        block = lattice_block(3, "-4 10 -4 10 -4 10", "0 6 0 6 0 6", types=2) + (
            "create_atoms    1 region block\nset             type 1 mass 3.747e-6\n")
    return f"""
units           si
atom_style      sphere
newton          on
{block}
set             type 1 diameter {D}
group           half id <= $(floor(count(all)/2))
"""
