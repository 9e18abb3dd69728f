"""Periodic cells for the tests of boxes that change size and shape
(tests/validation/test_periodic_box*.py): the cells, their deck, LAMMPS' pressure tensor and
box matrix, the strains and barostats applied to them, and the comparison with the bond sums
of :mod:`bonded_lattice.periodic`."""

from __future__ import annotations

from dataclasses import astuple

import numpy as np
from bonded_lattice.conversion import rock_to_bond_props
from bonded_lattice.lattice import write_data
from bonded_lattice.periodic import PeriodicCell, paper_cell, periodic_cell
from bonded_lattice.rocks import get_rock

from .materials import D, QUARTZ, QUARTZ_MASS

# 2D quartz (per metre of thickness, helpers.materials) and 3D quartzite bond parameters (the
# conversion's, unrounded): Kn Ks Xb Fs0 mu_p
BOND = {2: list(astuple(QUARTZ[2])),
        3: list(astuple(rock_to_bond_props(get_rock("quartzite").properties, D, 3)))}
MASS = {2: QUARTZ_MASS[2], 3: 2.0e-6}

# cells: the papers' orthogonal orientation and two turned, triclinic ones
CELLS = {
    2: {"paper": paper_cell(2, 6), "turned": np.array([[3, 1], [-2, 4]]),
        "turned2": np.array([[4, -1], [1, 3]]),
        # tilt xy exactly half of x: the first increase of the tilt flips the box
        "edge": np.array([[6, 0], [0, 6]])},
    3: {"paper": paper_cell(3, 4), "turned": np.array([[3, 1, 0], [0, 3, 1], [1, 0, 3]]),
        # tilt yz exactly half of y (and xy > 0): a yz flip, which moves xz by xy too
        "edge": np.array([[4, 0, 0], [-1, 4, 0], [-2, 1, 3]])},
}
VOIGT = {2: [(0, 0), (1, 1), (0, 1)], 3: [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]}
# LAMMPS' pressure vector order: xx yy zz xy xz yz
P_ORDER = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
STRAIN = 1.0e-6
# relative to the largest stress component; see the module's text
TOL = 1.0e-5
# the runs that change the box: NSTEPS steps of DT reach STRAIN at the strain rate RATE
NSTEPS = 40
DT = 1.0e-9
RATE = STRAIN / (NSTEPS * DT)


def deck(dim: int, data: str, shear_frame: str = "fixed", bond: list[float] | None = None,
         extra: str = "") -> str:
    """A periodic cell read from ``data`` with lattice/bond, the pair pressure tensor in
    full precision, and fix lattice/nve."""
    kn, ks, xb, fs0, mu = bond or BOND[dim]
    return f"""
units           si
dimension       {dim}
boundary        p p p
atom_style      atomic
read_data       {data}
pair_style      lattice/bond diameter {D} shear_frame {shear_frame}
pair_coeff      * * {kn!r} {ks!r} {xb!r} {fs0!r} {mu!r}
neighbor        {0.1 * D} bin
compute         p all pressure NULL pair
compute         bonds all lattice/bonds
thermo_style    custom step c_p[1] c_p[2] c_p[3] c_p[4] c_p[5] c_p[6] c_bonds[1] c_bonds[2] c_bonds[3] &
                lx ly lz xy xz yz
thermo_modify   format float %.17g
timestep        1.0e-9
fix             nve all lattice/nve
{extra}
"""


def write_cell(tmp_path, dim: int, name: str) -> tuple[PeriodicCell, str]:
    cell = periodic_cell(dim, D, CELLS[dim][name])
    path = tmp_path / f"cell{dim}{name}.data"
    write_data(cell.lattice, path, MASS[dim], atom_style="atomic")
    return cell, str(path)


def cell_box(lattice) -> np.ndarray:
    """Box matrix (columns: the edges a, b, c) of a lattice written to a data file."""
    xy, xz, yz = lattice.tilt or (0.0, 0.0, 0.0)
    lx, ly, lz = lattice.box[:, 1] - lattice.box[:, 0]
    return np.array([[lx, xy, xz], [0.0, ly, yz], [0.0, 0.0, lz]])


def box_matrix(lmp) -> np.ndarray:
    lo, hi, xy, yz, xz, _, _ = lmp.extract_box()
    return np.array([[hi[0] - lo[0], xy, xz], [0.0, hi[1] - lo[1], yz], [0.0, 0.0, hi[2] - lo[2]]])


def pressure(lmp) -> np.ndarray:
    vec = [lmp.extract_compute("p", 0, 1)[k] for k in range(6)]
    P = np.zeros((3, 3))
    for (a, b), value in zip(P_ORDER, vec):
        P[a, b] = value
    return P


def compare(P: np.ndarray, expected: np.ndarray, dim: int, what: str) -> None:
    """LAMMPS' pressure against the bond sum, on the components LAMMPS reports
    (xx yy zz and the upper off-diagonal ones; 2D: xx yy xy)."""
    comps = [c for c in P_ORDER if c[0] < dim and c[1] < dim]
    scale = max(abs(expected[c]) for c in comps)
    worst = max(abs(P[c] - expected[c]) for c in comps) / scale
    assert worst < TOL, (f"{what}: pressure differs from the bond sum by {worst:.3g} of its "
                         f"largest component\nLAMMPS\n{P}\nbond sum\n{expected}")


def strained_box(h0: np.ndarray, H: np.ndarray) -> np.ndarray:
    return (np.eye(3) + H) @ h0


def change_box_command(h: np.ndarray, lo: np.ndarray, dim: int, triclinic: bool) -> str:
    """change_box to the box matrix h (same lower corner), atoms remapped; the tilts
    only for a triclinic box."""
    h, lo = h.tolist(), lo.tolist()
    parts = [f"x final {lo[0]!r} {lo[0] + h[0][0]!r}", f"y final {lo[1]!r} {lo[1] + h[1][1]!r}"]
    if dim == 3:
        parts.append(f"z final {lo[2]!r} {lo[2] + h[2][2]!r}")
    if triclinic:
        if dim == 3:
            parts += [f"xz final {h[0][2]!r}", f"yz final {h[1][2]!r}"]
        parts.append(f"xy final {h[0][1]!r}")
    return "change_box all " + " ".join(parts) + " remap units box"


def strain_cases(dim: int) -> list[tuple[str, np.ndarray]]:
    """Upper-triangular displacement gradients (what a restricted triclinic box can
    do): each normal strain, each tilt (a simple shear, rotation included), one mix."""
    cases = []
    for a, b in VOIGT[dim]:
        H = np.zeros((3, 3))
        H[a, b] = STRAIN
        cases.append((f"H{'xyz'[a]}{'xyz'[b]}", H))
    mix = np.zeros((3, 3))
    for k, (a, b) in enumerate(VOIGT[dim]):
        mix[a, b] = STRAIN * (1.0 - 0.3 * k)
    cases.append(("mixed", mix))
    return cases


# the barostats' "temperature" for their mass W = (N + 1) k_B T Pdamp^2: with
# millimetre grains in SI the thermal scale is meaningless, and a W that lets the
# box respond within Pdamp needs k_B T of the order of the cell's elastic energy
# scale V B / N (2D, per metre of thickness: about 1e5 J here, T ~ 1e28 K; 3D: about
# 1e2 J, T ~ 2e25 K)
PTEMP = {2: "1e28", 3: "2e25"}
BAROSTATS = {
    # uniaxial stress along x (and zero shear stress where the box is tilted) by each
    # barostat; the target is 1e5 Pa of tension, a strain of about 1e-6.
    # press/berendsen leaves the integration to fix lattice/nve; nph and npt
    # integrate themselves (drag damps the barostat's oscillation)
    "press/berendsen": "fix baro all press/berendsen x -1e5 -1e5 2e-8 y 0 0 2e-8 "
                       "couple none modulus 1e11",
    "nph": "unfix nve\nfix baro all nph x -1e5 -1e5 2e-8 y 0 0 2e-8 drag 2.0 ptemp PTEMP",
    # npt takes the barostat's mass from its target temperature (no ptemp): T = PTEMP
    # with a thermostat too slow (Tdamp 1e3 s) to touch the particles at rest
    "npt": "unfix nve\nfix baro all npt temp PTEMP PTEMP 1e3 x -1e5 -1e5 2e-8 "
           "y 0 0 2e-8 drag 2.0",
}


def barostat_command(barostat: str, dim: int) -> str:
    """The commands of one of BAROSTATS for a cell of dimension dim: z held at zero
    stress too in 3D, and the xy shear stress for the barostats that take triclinic
    boxes (press/berendsen takes orthogonal ones only)."""
    command = BAROSTATS[barostat].replace("PTEMP", PTEMP[dim])
    if dim == 3:
        command = command.replace("y 0 0 2e-8", "y 0 0 2e-8 z 0 0 2e-8")
    if barostat != "press/berendsen":
        command = command.replace("y 0 0 2e-8", "y 0 0 2e-8 xy 0 0 2e-8")
    return command


def thermo_pressure(row: dict) -> tuple[np.ndarray, np.ndarray]:
    """Pressure tensor and box matrix from the last row of a thermo table."""
    P = np.zeros((3, 3))
    for k, (a, b) in enumerate(P_ORDER):
        P[a, b] = row[f"c_p[{k + 1}]"][-1]
    h = np.array([[row["Lx"][-1], row["Xy"][-1], row["Xz"][-1]],
                  [0.0, row["Ly"][-1], row["Yz"][-1]], [0.0, 0.0, row["Lz"][-1]]])
    return P, h
