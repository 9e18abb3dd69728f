"""Write commented LAMMPS input decks for the standard rock-mechanics tests.

A deck reads a data file written by :func:`bonded_lattice.lattice.write_data`
and loads the block along its loading axis (y in 2D, z in 3D):

- ``tension``: the top and bottom layers of particles are held by smooth
  planes (free to slide sideways) that move apart at ``speed`` — the papers'
  "bonded smooth planes"; ``grips`` (:data:`GRIPS`) can clamp them sideways too, or tie
  them to the moving planes by axial springs of ``wall_kn`` instead of prescribing their
  motion, pull them by a uniform traction ramped at ``traction_rate``, or hold the two
  outermost rows or layers (:mod:`bonded_lattice.deck.grips`);
- ``compression``: two smooth platens (``fix lattice/wall``, ``mu 0``) move
  toward each other at ``speed``; with ``ends="layers"`` (stepped ends, e.g. a
  rotated 2D lattice, where platens would touch a few particles only) the end
  layers are held and pushed together as tension pulls them apart (also for
  ``elastic`` and ``confined``);
- ``elastic``: compression to a small strain with breaking switched off
  (``Xb`` and ``Fs0`` multiplied by 100, as in Liu et al. 2017), for E and nu;
  with ``elastic_load = "tension"`` the end layers are pulled apart instead, as
  in the tension test (Liu 2013, para. 46: E and nu change with the strain
  magnitude in opposite senses under tension and compression);
- ``confined``: compression between the platens while smooth side walls
  (``fix lattice/wall ... servo``) hold the confining stress ``confining``
  (biaxial in 2D, triaxial in 3D);
- ``periodic``: a fully periodic cell (:mod:`bonded_lattice.periodic`, no
  platens, no free surfaces) stretched along the loading axis by ``fix deform
  ... erate ... remap x`` at ``strain_rate`` while ``fix press/berendsen``
  holds the lateral faces at zero stress: uniaxial tension with no boundary
  layer; the stress is the virial pressure.

The deck is made of the shared sections of :mod:`bonded_lattice.deck` (the
opening with the pair style, the integrator, the platens and side walls, the
outputs) around the tests' own strain measurements and loading.  A
heterogeneous block (``DeckSpec.grains``, :mod:`bonded_lattice.grains`) has its
grain ids and stiffness factors in the data file's ``Grains`` section, read
into ``fix property/atom`` and named, with the strength options, to
``pair_style lattice/bond`` (:class:`bonded_lattice.deck.PairStyle`).

Two loading schedules:

- ``constant`` (ours, the default): platens or end layers move at a constant
  ``speed``; the speed is chosen so that loading takes many elastic-wave
  crossings of the block;
- ``stepwise`` (the papers'): platens or end layers jump by ``step_size``
  each, then the block relaxes for ``relax_steps`` time steps (Liu et al. 2013:
  400 steps; Liu et al. 2017: 100 steps).

Every deck prints the same thermo columns, which :mod:`bonded_lattice.analysis`
reads: ``Step Time v_strain v_lateral v_gauge v_stress c_bonds[1..4] KinEng``
(axial and lateral strain as least-squares slopes of all particles'
displacements, the lateral strain of mid-height gauges on the side faces,
stress in Pa, tension positive).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TextIO

from .conversion import BondParameters
from .deck import (ATOM_DUMP_COLUMNS, BOND_COUNTS, PairStyle, atom_bond_counts, bond_counts,
                   energy_budget, integrator, opening, smooth_wall, thermo)
from .deck.grips import GRIPS, end_layers, grip_title
from .deck.pair import SHEAR_FRAMES
from .grains import GrainPairOptions
from .lattice import check_atom_style
from .schedules import SCHEDULES  # the loading schedules' one vocabulary

TESTS = ("tension", "compression", "elastic", "confined", "periodic")
# how the ends are loaded (DeckSpec.ends)
ENDS = ("platens", "layers")
# how the elastic test loads: platens (compression) or end layers pulled apart (tension)
ELASTIC_LOADS = ("compression", "tension")
# how the end layers are gripped when a deck loads through them (DeckSpec.grips): GRIPS of
# bonded_lattice.deck.grips
# the per-step log of a deck with the energy budget (read by io.read_ave_time): every term
# the 2017 paper's Fig. 6c/d heat curves and insets need, at every time step of a window
# around the failure -- the breaking heat of the normal and of the shear springs (compute
# lattice/energy), the bonds broken in tension and in shear, the kinetic energy and the
# external work (the first six, the log's columns before issue 19), then the elastic
# energy, the viscous and the frictional heat, the balance error and the stress.  A
# failure lasts fewer steps than a thermo interval, so the thermo rows (the whole run,
# every term) cannot time it.
BREAKING_LOG = "breaking.dat"
BREAKING_COLUMNS = ("c_energy[5]", "c_energy[6]", "c_bonds[2]", "c_bonds[3]", "c_energy[2]",
                    "c_energy[8]", "c_energy[1]", "c_energy[4]", "c_energy[7]", "c_energy[10]",
                    "v_stress")
# the window: the last BREAKING_WINDOW steps of the run, kept in a ring buffer (fix vector
# ... nmax) and written to the log after the run.  A strength deck stops within a few
# thermo intervals of the failure (fix halt), so the window holds the failure and the
# steps before it, while the file stays bounded however long the loading was (the papers'
# stepwise schedule runs about 1e6 steps in 3D tension: about 150 MB at every step).
# 20000 steps hold a 3D compression failure (about 1e-4 s in the 2017 paper: 10000 of its
# 1e-8 s steps) twice over; the ring costs 8 bytes per column and step (about 2 MB).
BREAKING_WINDOW = 20000


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
    speed: float              # platen speed per side (m/s), constant schedule
    steps: int                # time steps to run
    dt: float = 2.0e-8        # time step (s)
    thermo_every: int = 500
    dump_every: int = 0       # >0: dump particles with their intact-bond count
    wall_kn: float | None = None  # platen stiffness, default 2*Kn
    confining: float = 0.0    # confining stress of the confined test (Pa, compression positive)
    schedule: str = "constant"  # one of SCHEDULES
    step_size: float = 0.0    # stepwise: displacement of each platen per loading step (m)
    relax_steps: int = 0      # stepwise: time steps after each loading step
    gauges: bool = True       # mid-height lateral gauges (False: blocks of 1-2 layers)
    halt_fraction: float = 0.3  # strength tests stop when |stress| < this x peak (0: never)
    halt_delay: int = 0       # ... this many steps later (energy decks: the failure's aftermath)
    energy: bool = False      # energy budget (compute lattice/energy) in the thermo output
    shear_frame: str = "fixed"  # one of SHEAR_FRAMES (the papers': fixed)
    # heterogeneous model: the data file has a Grains section (lattice.write_data) and the
    # pair style reads it; None: homogeneous
    grains: GrainPairOptions | None = None
    # "atomic": the data file was written with lattice.write_data(..., atom_style="atomic")
    # (per-type mass) and the pair style gets the diameter (pair_style lattice/bond diameter d)
    atom_style: str = "sphere"
    strain_rate: float = 0.0  # periodic: axial strain rate of fix deform (1/s)
    modulus: float = 0.0      # periodic: the barostat's estimate of the lattice's stiffness (Pa)
    # how compression, elastic and confined tests load the ends (tension always holds the end
    # layers): "platens" (the papers' smooth platens, fix lattice/wall) or "layers" (the end
    # layers' axial motion prescribed, as in tension: for stepped ends that platens would
    # touch at a few particles only, e.g. a rotated 2D lattice)
    ends: str = "platens"
    elastic_load: str = "compression"  # elastic test: one of ELASTIC_LOADS
    # how the end layers are gripped when the deck loads through them (tension, an elastic
    # test in tension, ends = "layers"): one of GRIPS; "springs" ties them to the moving planes
    # by springs of wall_kn (default 2 Kn, the platens' default); "traction" ramps the end
    # layers' traction at traction_rate (Pa/s)
    grips: str = "held"
    traction_rate: float = 0.0

    def __post_init__(self) -> None:
        if self.test not in TESTS:
            raise ValueError(f"test = {self.test!r} is not known: use one of {', '.join(TESTS)}")
        if self.dim not in (2, 3):
            raise ValueError(f"dim = {self.dim} is out of range: use 2 or 3")
        if self.grains is not None and not isinstance(self.grains, GrainPairOptions):
            raise ValueError(f"grains = {self.grains!r}: need a grains.GrainPairOptions or None")
        if self.shear_frame not in SHEAR_FRAMES:
            raise ValueError(f"shear_frame = {self.shear_frame!r} is not known: use one of "
                             f"{', '.join(SHEAR_FRAMES)}")
        check_atom_style(self.atom_style)
        if self.ends not in ENDS:
            raise ValueError(f"ends = {self.ends!r} is not known: use one of {', '.join(ENDS)}")
        if self.ends == "layers" and self.test == "periodic":
            raise ValueError("ends = 'layers': the periodic test has no ends (use 'platens', "
                             "which it ignores)")
        if self.elastic_load not in ELASTIC_LOADS:
            raise ValueError(f"elastic_load = {self.elastic_load!r} is not known: use one of "
                             f"{', '.join(ELASTIC_LOADS)}")
        if self.elastic_load != "compression" and self.test != "elastic":
            raise ValueError(f"elastic_load = {self.elastic_load!r} is for the elastic test "
                             f"only (test = {self.test!r})")
        if self.grips not in GRIPS:
            raise ValueError(f"grips = {self.grips!r} is not known: use one of {', '.join(GRIPS)}")
        if self.grips != "held" and not self.held_ends:
            raise ValueError(f"grips = {self.grips!r} is for decks that load through the end "
                             f"layers (tension, elastic_load 'tension', ends 'layers'); test = "
                             f"{self.test!r}, ends = {self.ends!r} uses platens")
        if self.grips in ("springs", "traction") and self.energy:
            raise ValueError(f"grips = {self.grips!r}: the grips' work (fix addforce) is not in "
                             "compute lattice/energy's budget; use grips 'held', 'clamped' or "
                             "'wide' with energy")
        if self.grips == "traction" and not (self.traction_rate > 0
                                             and math.isfinite(self.traction_rate)):
            raise ValueError(f"traction_rate = {self.traction_rate} is out of range: grips "
                             "'traction' need 0 < traction_rate < inf (Pa/s)")
        if self.grips == "traction" and self.schedule != "constant":
            raise ValueError("grips = 'traction' ramp the force at a constant rate: schedule "
                             f"must be 'constant' (not {self.schedule!r})")
        if self.schedule not in SCHEDULES:
            raise ValueError(f"schedule = {self.schedule!r} is not known: use one of "
                             f"{', '.join(SCHEDULES)}")
        positive = ("d", "area", "dt") + (("speed",) if self.schedule == "constant"
                                          else ("step_size",))
        for name in positive:
            value = getattr(self, name)
            if not (value > 0 and math.isfinite(value)):
                raise ValueError(f"{name} = {value} is out of range: need 0 < {name} < inf")
        # every number the deck prints must be finite
        for name in ("d", "area", "eta", "speed", "dt", "confining", "step_size",
                     "halt_fraction"):
            value = getattr(self, name)
            if not math.isfinite(value):
                raise ValueError(f"{name} = {value} is out of range: need a finite value")
        if self.wall_kn is not None and not (self.wall_kn > 0 and math.isfinite(self.wall_kn)):
            raise ValueError(f"wall_kn = {self.wall_kn} is out of range: need 0 < wall_kn < inf")
        if self.schedule == "stepwise" and self.relax_steps < 1:
            raise ValueError(f"relax_steps = {self.relax_steps} is out of range: the stepwise "
                             "schedule needs relax_steps >= 1")
        if not 0 <= self.halt_fraction < 1:
            raise ValueError(f"halt_fraction = {self.halt_fraction} is out of range: need "
                             "0 <= halt_fraction < 1")
        if self.halt_delay < 0:
            raise ValueError(f"halt_delay = {self.halt_delay} is out of range: need "
                             "halt_delay >= 0")
        if self.eta < 0:
            raise ValueError(f"eta = {self.eta} is out of range: need eta >= 0")
        if self.confining < 0:
            raise ValueError(f"confining = {self.confining} is out of range: need confining >= 0 "
                             "(compression positive)")
        if self.steps < 1:
            raise ValueError(f"steps = {self.steps} is out of range: need steps >= 1")
        if self.test == "periodic":
            for name in ("strain_rate", "modulus"):
                value = getattr(self, name)
                if not (value > 0 and math.isfinite(value)):
                    raise ValueError(f"{name} = {value} is out of range: the periodic test "
                                     f"needs 0 < {name} < inf")
            if self.schedule != "constant":
                raise ValueError("the periodic test strains its box at a constant rate: "
                                 "schedule must be 'constant'")
            if self.energy:
                raise ValueError("the periodic test's barostat does work that compute "
                                 "lattice/energy does not count: no energy budget with it")

    @property
    def axis(self) -> str:
        """Loading axis: y in 2D, z in 3D."""
        return "y" if self.dim == 2 else "z"

    @property
    def pulls(self) -> bool:
        """Whether the end layers are pulled apart (the tension test, the elastic test in
        tension) rather than pressed by platens."""
        return self.test == "tension" or (self.test == "elastic"
                                          and self.elastic_load == "tension")

    @property
    def held_ends(self) -> bool:
        """Whether the deck loads the block through its end layers (not platens)."""
        return self.test != "periodic" and (self.pulls or self.ends == "layers")

    @property
    def grip_kn(self) -> float:
        """Stiffness of each grip spring (N/m): wall_kn, default 2 Kn as the platens'."""
        return self.wall_kn if self.wall_kn is not None else 2.0 * self.bond.Kn

    @property
    def lateral_axes(self) -> tuple[str, ...]:
        """The axes across the load: x in 2D, x and y in 3D."""
        return ("x",) if self.dim == 2 else ("x", "y")


# the failure halt is armed once the peak stress exceeds this fraction of Kn Xb / d^(dim-1),
# the tensile stress scale of one bond (Tu is 2 (2D) or 3.1 (3D) times it)
ARM_FRACTION = 0.01


def halt_arm_stress(spec: DeckSpec) -> float:
    """Stress (Pa) the peak must exceed before the failure halt can stop a strength test."""
    return ARM_FRACTION * spec.bond.Kn * spec.bond.Xb / spec.d ** (spec.dim - 1)


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
        "elastic": f"Elastic test: small {spec.elastic_load} with unbreakable bonds "
                   "(Xb, Fs0 x 100)",
        "confined": f"Confined compression: platens plus side walls holding {spec.confining:g} Pa",
        "periodic": "Uniaxial tension of a periodic cell: no platens, no free surfaces",
    }[spec.test]
    if spec.test == "tension" and spec.grips != "held":
        title = f"Uniaxial tension, the {grip_title(spec.grips, spec.grip_kn)}"
    if spec.ends == "layers" and not spec.pulls:
        held = "smooth planes holding the end layers (stepped ends)"
        title = {"compression": f"Uniaxial compression between two {held}",
                 "elastic": f"Elastic test: small compression between two {held}, unbreakable "
                            "bonds (Xb, Fs0 x 100)",
                 "confined": f"Confined compression: two {held}, side walls holding "
                             f"{spec.confining:g} Pa"}[spec.test]
    b = deck_bond(spec)
    periodic = spec.test == "periodic"
    boundary = "p p p" if periodic else ("f f p" if spec.dim == 2 else "f f f")
    pair = PairStyle(b, spec.d, spec.atom_style, spec.grains, spec.shear_frame)
    opening_text = f"""# {title}
# Written by bonded_lattice.decks; edit freely.  Run: mpirun -np 2 lmp -in <this file>
# Bond parameters: Kn {b.Kn:.6g} N/m, Ks {b.Ks:.6g} N/m, Xb {b.Xb:.6g} m,
# Fs0 {b.Fs0:.6g} N, mu_p {b.mu_p:.6g}; particle diameter {spec.d:g} m.

""" + opening(spec.dim, boundary, spec.atom_style, spec.data_file, pair)
    if periodic:
        lateral = spec.lateral_axes
        text = opening_text + f"""
# strains from the box (the particles follow it: fix deform ... remap x)
variable        L0 equal $(l{spec.axis})
variable        strain equal (l{spec.axis}-v_L0)/v_L0
"""
        for a in lateral:
            text += f"variable        L{a}0 equal $(l{a})\n"
        mean = "+".join(f"(l{a}-v_L{a}0)/v_L{a}0" for a in lateral)
        return text + (f"variable        lateral equal ({mean})/{len(lateral)}\n"
                       "variable        gauge equal v_lateral\n")
    return opening_text + f"""
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
""" + _gauges(spec)


def _gauges(spec: DeckSpec) -> str:
    """Lateral strain gauges: the outermost particles of each side face at mid-height.

    Like strain gauges glued to a rock specimen, they sit away from the platens'
    end zones; the gauge strain is the change of the distance between the centres
    of the two faces' particles.  3D has gauges on the x and the y faces.
    """
    if not spec.gauges:
        return ("# no particles at mid-height (a single unit): the gauge is the all-particle fit\n"
                "variable        gauge equal v_lateral\n")
    ax, d = spec.axis, spec.d
    zone = ("$(v_lo0+0.25*v_H0)", "$(v_hi0-0.25*v_H0)")
    text = "# lateral strain gauges: outermost particles of the side faces at mid-height\n"
    names = []
    for a in spec.lateral_axes:
        k = "xyz".index(a) + 1
        for side, lo, hi in (("hi", f"$(bound(all,{a}max)-{0.6 * d!r})", "INF"),
                             ("lo", "INF", f"$(bound(all,{a}min)+{0.6 * d!r})")):
            g = f"g{a}{side}"
            text += (f"region          {g} block {_block({a: (lo, hi), ax: zone})} units box\n"
                     f"group           {g} region {g}\n"
                     f"compute         u{g} {g} reduce ave c_disp[{k}]\n")
        text += (f"variable        gauge_{a} equal (c_ug{a}hi-c_ug{a}lo)/"
                 f"$(xcm(g{a}hi,{a})-xcm(g{a}lo,{a}))\n")
        names.append(f"v_gauge_{a}")
    mean = "+".join(names)
    text += f"variable        gauge equal ({mean})/{len(names)}\n"
    return text


def _block(bounds: dict[str, tuple[str, str]]) -> str:
    """Region block bounds, INF along the axes not given, e.g. 'INF INF lo hi INF INF'."""
    return " ".join(" ".join(bounds.get(a, ("INF", "INF"))) for a in "xyz")


def _loading(spec: DeckSpec) -> str:
    ax, d = spec.axis, spec.d
    k = "xyz".index(ax) + 1  # index of the axis in fix outputs
    if spec.test == "periodic":
        lateral = spec.lateral_axes
        pdamp = 20.0 * spec.dt
        free = " ".join(f"{a} 0.0 0.0 {pdamp:.6g}" for a in lateral)
        return f"""
# ---- loading: the cell stretched along {ax} at the strain rate {spec.strain_rate:.6g} 1/s ----
# fix deform maps the particles with the box (remap x): no platens, no end zones;
# the lateral faces are held at zero stress by fix press/berendsen (relaxation
# time about {pdamp:.3g} s x its modulus / the lattice's, a few dozen steps)
{integrator("all", spec.eta)}fix             strain all deform 1 {ax} erate {spec.strain_rate:.6g} remap x
fix             free all press/berendsen {free} couple none modulus {spec.modulus:.6g}
# stress (tension positive): the virial pressure of the bonds and fixes, no kinetic part
compute         pvir all pressure NULL virial
variable        stress equal -c_pvir[{k}]
"""
    if spec.pulls:
        return end_layers(spec)
    wall_kn = spec.wall_kn if spec.wall_kn is not None else 2.0 * spec.bond.Kn
    r = 0.5 * d
    sides = ""
    if spec.test == "confined":
        # side faces: x in 2D (area = height x unit thickness), x and y in 3D
        lateral = spec.lateral_axes
        # areas between the outer particle centres, the convention of the
        # platen stress (Lattice.loaded_area), so sigma1 and sigma3 agree
        sides = "# ---- confinement: smooth side walls holding the confining stress (servo) ----\n"
        for a in lateral:
            other = "y" if a == "x" else "x"
            area = (f"$((v_hi0-v_lo0)*(bound(all,{other}max)-bound(all,{other}min)))"
                    if spec.dim == 3 else "$(v_hi0-v_lo0)")
            servo = f"servo {spec.confining:.6g} {area}"
            sides += (smooth_wall(f"side{a}lo", f"{a}lo", f"$(bound(all,{a}min)-{r!r})",
                                  wall_kn, servo)
                      + smooth_wall(f"side{a}hi", f"{a}hi", f"$(bound(all,{a}max)+{r!r})",
                                    wall_kn, servo))
    if spec.ends == "layers":
        return sides + end_layers(spec)
    if spec.schedule == "constant":
        title = f"moving in at {spec.speed:g} m/s"
        variables = ""
        platens = (smooth_wall("bottom", f"{ax}lo", f"$(v_lo0-{r!r})", wall_kn,
                               f"vel {spec.speed:.6g}")
                   + smooth_wall("top", f"{ax}hi", f"$(v_hi0+{r!r})", wall_kn,
                                 f"vel {-spec.speed:.6g}"))
    else:
        title = f"jumping in by {spec.step_size:g} m every {spec.relax_steps} steps"
        jump = f"{spec.step_size:.6g}*ceil((step-v_s0)/{spec.relax_steps})"
        variables = (f"variable        s0 equal $(step)\n"
                     f"variable        wbot equal $(v_lo0-{r!r})+{jump}\n"
                     f"variable        wtop equal $(v_hi0+{r!r})-{jump}\n")
        platens = (smooth_wall("bottom", f"{ax}lo", "v_wbot", wall_kn)
                   + smooth_wall("top", f"{ax}hi", "v_wtop", wall_kn))
    return sides + f"""
# ---- loading: smooth platens touching the end layers, {title} ----
{variables}{platens}{integrator("all", spec.eta)}# stress (tension positive) from the platen forces
variable        stress equal 0.5*(f_bottom[{k}]-f_top[{k}])/{spec.area:.8g}
"""


def _output(spec: DeckSpec) -> str:
    dump = ""
    if spec.dump_every > 0:
        dump = (f"dump            particles all custom {spec.dump_every} dump.lammpstrj "
                f"{ATOM_DUMP_COLUMNS}\n"
                "dump_modify     particles sort id format float %.17g\n")
    halt = ""
    if spec.energy and spec.test != "elastic":
        halt += _breaking_ring()
    if spec.test != "elastic" and spec.halt_fraction > 0:
        halt += f"""# stop once the block has failed: |stress| below {spec.halt_fraction:g} of its peak so far,
# armed only once the peak exceeds {ARM_FRACTION:g} of a bond's tensile stress Kn Xb / d^{spec.dim - 1}
# (a platen's first jump can leave the stress at zero while the peak is still rounding)
variable        smag equal abs(v_stress)
fix             peaklog all vector {spec.thermo_every} v_smag
variable        failed equal (v_smag<{spec.halt_fraction:g}*max(f_peaklog))&&(max(f_peaklog)>{halt_arm_stress(spec):.6g})
""" + _halt(spec)
    energy = columns = ""
    if spec.energy:
        # after the fixes that add forces, as compute lattice/energy requires; the
        # end layers' prescribed motion does external work in tension
        layers = spec.held_ends
        energy, columns = energy_budget("top bottom" if layers else "")
    table = thermo(f"step time v_strain v_lateral v_gauge v_stress {BOND_COUNTS} ke{columns}",
                   spec.thermo_every, flush=True)
    full = "modify sort id format float %.17g"
    return f"""
# ---- output ----
{energy}{bond_counts()}{atom_bond_counts()}{table}timestep        {spec.dt:.6g}
# run 0 makes the bonds, so the first dump shows them
run             0
# full precision: displacements of 1e-7 m vanish in the default %g format
write_dump      all custom dump.initial {ATOM_DUMP_COLUMNS} {full}
{dump}{halt}run             {spec.steps}
{_breaking_log() if spec.energy and spec.test != "elastic" else ""}write_dump      all custom dump.final {ATOM_DUMP_COLUMNS} {full}
"""


def _halt(spec: DeckSpec) -> str:
    """``fix halt`` at the first thermo row with ``v_failed``, or with ``halt_delay`` the
    first one at least that many steps later (counted in failed rows: the stress of a broken
    block can swing back above the threshold with its waves, never for long)."""
    if spec.halt_delay == 0:
        return f"fix             stop all halt {spec.thermo_every} v_failed > 0.5 error continue\n"
    rows = 1 + math.ceil(spec.halt_delay / spec.thermo_every)
    return f"""# go on for {spec.halt_delay} steps after the failure ({rows} failed thermo rows): the kinetic
# energy the failure releases peaks and is damped into heat after the stress has dropped
fix             faillog all vector {spec.thermo_every} v_failed
variable        failedrows equal sum(f_faillog)
fix             stop all halt {spec.thermo_every} v_failedrows >= {rows} error continue
"""


def _breaking_ring() -> str:
    """The ring buffer of the per-step log: :data:`BREAKING_COLUMNS` at every step, the last
    :data:`BREAKING_WINDOW` steps kept."""
    # each column through an equal-style variable: fix vector takes only values that are all
    # intensive or all extensive (the computes' are extensive, the stress is intensive)
    names = [f"v_ring{j}" for j in range(len(BREAKING_COLUMNS))]
    variables = "".join(f"variable        ring{j} equal {c}\n"
                        for j, c in enumerate(BREAKING_COLUMNS))
    return f"""# every term of the energy budget, the broken bonds and the stress at every step, the last
# {BREAKING_WINDOW} steps kept (fix vector ... nmax: a ring buffer), to time the failure at the
# resolution of a step (the 2017 paper reads the crack's crossing time off the breaking heat)
variable        logstep equal step
{variables}variable        ringstart equal $(step)
fix             breakring all vector 1 v_logstep {" ".join(names)} nmax {BREAKING_WINDOW}
"""


def _breaking_log() -> str:
    """Write the ring buffer to :data:`BREAKING_LOG` in the format of ``fix ave/time ... file``
    (two header lines, then a step and the columns per line; io.read_ave_time reads it)."""
    k = len(BREAKING_COLUMNS)
    values = " ".join(f"$(f_breakring[v_breakrow][{j}]:%.17g)" for j in range(2, k + 2))
    return f"""# the per-step window: the ring buffer's rows (oldest first) to {BREAKING_LOG}
variable        ringsteps equal step-v_ringstart+1
variable        ringrows equal $(v_ringsteps*(v_ringsteps<={BREAKING_WINDOW})+{BREAKING_WINDOW}*(v_ringsteps>{BREAKING_WINDOW}))
print           "# Time-averaged data for fix breakring (every step, the last $(v_ringrows:%.0f) steps of the run)" file {BREAKING_LOG} screen no
print           "# TimeStep {" ".join(BREAKING_COLUMNS)}" append {BREAKING_LOG} screen no
variable        breakrow loop $(v_ringrows:%.0f)
label           breakrow_next
print           "$(f_breakring[v_breakrow][1]:%.0f) {values}" append {BREAKING_LOG} screen no
next            breakrow
jump            SELF breakrow_next
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
