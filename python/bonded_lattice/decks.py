"""Write commented LAMMPS input decks for the standard rock-mechanics tests.

A deck reads a data file written by :func:`bonded_lattice.lattice.write_data`
and loads the block along its loading axis (y in 2D, z in 3D):

- ``tension``: the top and bottom layers of particles are held by smooth
  planes (free to slide sideways) that move apart at ``speed`` — the papers'
  "bonded smooth planes";
- ``compression``: two smooth platens (``fix lattice/wall``, ``mu 0``) move
  toward each other at ``speed``;
- ``elastic``: compression to a small strain with breaking switched off
  (``Xb`` and ``Fs0`` multiplied by 100, as in Liu et al. 2017), for E and nu;
- ``confined``: compression between the platens while smooth side walls
  (``fix lattice/wall ... servo``) hold the confining stress ``confining``
  (biaxial in 2D, triaxial in 3D).

Every deck prints the same thermo columns, which :mod:`bonded_lattice.analysis`
reads: ``Step Time v_strain v_lateral v_stress c_bonds[1..4] KinEng``
(strain and lateral strain from the particles' extent, stress in Pa,
tension positive).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import TextIO

from .conversion import BondParameters

TESTS = ("tension", "compression", "elastic", "confined")


@dataclass(frozen=True)
class DeckSpec:
    """Everything a test deck needs besides the lattice itself."""

    test: str                 # one of TESTS
    dim: int                  # 2 or 3
    d: float                  # particle diameter (m)
    bond: BondParameters
    data_file: str            # LAMMPS data file, relative to the deck
    area: float               # loaded cross-section (m^2; per unit thickness in 2D: width x 1)
    eta: float                # viscous damping coefficient (N s/m)
    speed: float              # platen speed per side (m/s)
    steps: int                # time steps to run
    dt: float = 2.0e-8        # time step (s)
    thermo_every: int = 500
    dump_every: int = 0       # >0: dump particles with their intact-bond count
    wall_kn: float | None = None  # platen stiffness, default 2*Kn
    confining: float = 0.0    # confining stress of the confined test (Pa, compression positive)

    def __post_init__(self) -> None:
        if self.test not in TESTS:
            raise ValueError(f"test = {self.test!r} is not known: use one of {', '.join(TESTS)}")
        if self.dim not in (2, 3):
            raise ValueError(f"dim = {self.dim} is out of range: use 2 or 3")
        for name in ("d", "area", "speed", "dt"):
            value = getattr(self, name)
            if not value > 0:
                raise ValueError(f"{name} = {value} is out of range: need {name} > 0")
        if self.eta < 0:
            raise ValueError(f"eta = {self.eta} is out of range: need eta >= 0")
        if self.confining < 0:
            raise ValueError(f"confining = {self.confining} is out of range: need confining >= 0 "
                             "(compression positive)")
        if self.steps < 1:
            raise ValueError(f"steps = {self.steps} is out of range: need steps >= 1")

    @property
    def axis(self) -> str:
        """Loading axis: y in 2D, z in 3D."""
        return "y" if self.dim == 2 else "z"


def deck_bond(spec: DeckSpec) -> BondParameters:
    """Bond parameters used in the deck (unbreakable for the elastic test)."""
    if spec.test == "elastic":
        return replace(spec.bond, Xb=100 * spec.bond.Xb, Fs0=100 * spec.bond.Fs0)
    return spec.bond


def _header(spec: DeckSpec) -> str:
    k = "xyz".index(spec.axis) + 1
    title = {
        "tension": "Uniaxial tension between two smooth planes holding the end layers",
        "compression": "Uniaxial compression between two smooth platens (fix lattice/wall, mu 0)",
        "elastic": "Elastic test: small compression with unbreakable bonds (Xb, Fs0 x 100)",
        "confined": f"Confined compression: platens plus side walls holding {spec.confining:g} Pa",
    }[spec.test]
    b = deck_bond(spec)
    boundary = "f f p" if spec.dim == 2 else "f f f"
    return f"""# {title}
# Written by bonded_lattice.decks; edit freely.  Run: mpirun -np 2 lmp -in <this file>
# Bond parameters: Kn {b.Kn:.6g} N/m, Ks {b.Ks:.6g} N/m, Xb {b.Xb:.6g} m,
# Fs0 {b.Fs0:.6g} N, mu_p {b.mu_p:.6g}; particle diameter {spec.d:g} m.

units           si
dimension       {spec.dim}
boundary        {boundary}
atom_style      sphere
newton          on
read_data       {spec.data_file}

pair_style      lattice/bond
{b.pair_coeff()}
# a small skin keeps the search for new contacts cheap
neighbor        {0.1 * spec.d:.6g} bin
neigh_modify    every 1 delay 0 check yes

# extent of the block along the loading axis ({spec.axis})
variable        lo0 equal $(bound(all,{spec.axis}min))
variable        hi0 equal $(bound(all,{spec.axis}max))
variable        H0 equal $(v_hi0-v_lo0)
# strains: least-squares slopes of the displacement against the initial
# position over all particles (the end and corner particles, held by fewer
# bonds, move more than the block as a whole)
compute         disp all displace/atom
variable        x0 atom x-c_disp[1]
variable        x0ux atom v_x0*c_disp[1]
variable        x0sq atom v_x0*v_x0
variable        a0 atom {spec.axis}-c_disp[{k}]
variable        a0ua atom v_a0*c_disp[{k}]
variable        a0sq atom v_a0*v_a0
compute         lat all reduce sum v_x0 c_disp[1] v_x0ux v_x0sq
compute         ax all reduce sum v_a0 c_disp[{k}] v_a0ua v_a0sq
variable        strain equal (count(all)*c_ax[3]-c_ax[1]*c_ax[2])/(count(all)*c_ax[4]-c_ax[1]^2)
variable        lateral equal (count(all)*c_lat[3]-c_lat[1]*c_lat[2])/(count(all)*c_lat[4]-c_lat[1]^2)
"""


def _slab(axis: str, lo: str, hi: str) -> str:
    """Region bounds of a slab across the loading axis, e.g. 'INF INF lo hi INF INF'."""
    bounds = {"x": ["INF", "INF"], "y": ["INF", "INF"], "z": ["INF", "INF"]}
    bounds[axis] = [lo, hi]
    return " ".join(bounds["x"] + bounds["y"] + bounds["z"])


def _vector(axis: str, value: str, other: str = "0") -> str:
    """'other value other' with value in the loading axis' slot."""
    return " ".join(value if a == axis else other for a in "xyz")


def _loading(spec: DeckSpec) -> str:
    ax, d = spec.axis, spec.d
    k = "xyz".index(ax) + 1  # index of the axis in fix outputs
    if spec.test == "tension":
        return f"""
# ---- loading: end layers held by smooth planes moving apart at {spec.speed:g} m/s ----
region          toplayer block {_slab(ax, f"$(v_hi0-{0.25 * d!r})", "INF")} units box
region          botlayer block {_slab(ax, "INF", f"$(v_lo0+{0.25 * d!r})")} units box
group           top region toplayer
group           bottom region botlayer
group           inner subtract all top bottom
velocity        all set 0 0 0 units box
velocity        top set {_vector(ax, f"{spec.speed:.6g}")} units box
velocity        bottom set {_vector(ax, f"{-spec.speed:.6g}")} units box
# the planes are smooth: only the axial force is taken over (and reported)
fix             ftop top setforce {_vector(ax, "0.0", "NULL")}
fix             fbot bottom setforce {_vector(ax, "0.0", "NULL")}
fix             integrate all nve
fix             damp inner lattice/viscous {spec.eta:.6g}
# stress (tension positive) from the force the block exerts on the end layers
variable        stress equal 0.5*(f_fbot[{k}]-f_ftop[{k}])/{spec.area:.8g}
"""
    wall_kn = spec.wall_kn if spec.wall_kn is not None else 2.0 * spec.bond.Kn
    r = 0.5 * d
    sides = ""
    if spec.test == "confined":
        # side faces: x in 2D (area = height x unit thickness), x and y in 3D
        lateral = "x" if spec.dim == 2 else "xy"
        # areas between the outer particle centres, the convention of the
        # platen stress (Lattice.loaded_area), so sigma1 and sigma3 agree
        sides = "# ---- confinement: smooth side walls holding the confining stress (servo) ----\n"
        for a in lateral:
            other = "y" if a == "x" else "x"
            area = (f"$((v_hi0-v_lo0)*(bound(all,{other}max)-bound(all,{other}min)))"
                    if spec.dim == 3 else "$(v_hi0-v_lo0)")
            sides += (f"fix             side{a}lo all lattice/wall {a}lo $(bound(all,{a}min)-{r!r}) "
                      f"{wall_kn:.6g} 0 0 servo {spec.confining:.6g} {area}\n"
                      f"fix             side{a}hi all lattice/wall {a}hi $(bound(all,{a}max)+{r!r}) "
                      f"{wall_kn:.6g} 0 0 servo {spec.confining:.6g} {area}\n")
    return sides + f"""
# ---- loading: smooth platens touching the end layers, moving in at {spec.speed:g} m/s ----
fix             bottom all lattice/wall {ax}lo $(v_lo0-{r!r}) {wall_kn:.6g} 0 0 vel {spec.speed:.6g}
fix             top all lattice/wall {ax}hi $(v_hi0+{r!r}) {wall_kn:.6g} 0 0 vel {-spec.speed:.6g}
fix             integrate all nve
fix             damp all lattice/viscous {spec.eta:.6g}
# stress (tension positive) from the platen forces
variable        stress equal 0.5*(f_bottom[{k}]-f_top[{k}])/{spec.area:.8g}
"""


def _output(spec: DeckSpec) -> str:
    dump = ""
    if spec.dump_every > 0:
        dump = f"""dump            particles all custom {spec.dump_every} dump.lammpstrj id type x y z c_nbonds
dump_modify     particles sort id
"""
    return f"""
# ---- output ----
compute         bonds all lattice/bonds
compute         nbonds all lattice/bonds
thermo_style    custom step time v_strain v_lateral v_stress c_bonds[1] c_bonds[2] c_bonds[3] c_bonds[4] ke
thermo_modify   norm no flush yes
thermo          {spec.thermo_every}
timestep        {spec.dt:.6g}
# run 0 makes the bonds, so the first dump shows them
run             0
write_dump      all custom dump.initial id type x y z c_nbonds modify sort id
{dump}run             {spec.steps}
write_dump      all custom dump.final id type x y z c_nbonds modify sort id
"""


def deck_text(spec: DeckSpec) -> str:
    """The whole deck as a string."""
    return _header(spec) + _loading(spec) + _output(spec)


def write_deck(spec: DeckSpec, target: str | Path | TextIO) -> None:
    """Write the deck to a path or an open text file."""
    text = deck_text(spec)
    if hasattr(target, "write"):
        target.write(text)  # type: ignore[union-attr]
    else:
        Path(target).write_text(text)
