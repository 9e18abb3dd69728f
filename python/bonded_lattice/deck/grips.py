"""Grips of the end layers when a rock test loads its block through them (tension, an elastic
test in tension, compression with ``ends="layers"``; :data:`GRIPS`).

- :func:`end_layers`: the end layers' groups, their grips and the loading through them, with
  ``variable stress``;
- :func:`grip_title`: what holds the end layers, for a deck's comments;
- :func:`spring_grips`: each end-layer particle tied to a moving smooth plane by an axial
  spring (``fix addforce`` of an atom-style variable), free sideways: the 2013 paper's
  "lattice bonded by two smooth planes" (para. 42) with a finite stiffness, like its
  platens';
- :func:`traction_grips`: every end-layer particle pulled by the same axial force, ramped at
  a constant rate (a uniform traction; no prescribed displacement, free sideways).

The held, clamped and wide grips prescribe the end layers' axial motion (``fix move``).

Needs the groups' extent along the loading axis ``v_lo0``, ``v_hi0``, ``v_H0`` and
``compute disp`` (displace/atom), which :mod:`bonded_lattice.decks` writes before the loading.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .integrator import integrator

if TYPE_CHECKING:   # decks imports this module
    from ..decks import DeckSpec

__all__ = ["GRIPS", "RUNAWAY", "TRACTION_LOG", "check_grips", "end_layers", "grip_depth", "grip_title",
           "spring_grips", "traction_grips"]

# how the end layers are gripped (DeckSpec.grips): "held" (their axial motion prescribed,
# free sideways: smooth planes holding them), "clamped" (their lateral motion fixed too),
# "springs" (each end particle tied to a moving smooth plane by an axial spring of stiffness
# wall_kn, free sideways: the 2013 paper's "lattice bonded by two smooth planes", para. 42,
# with a compliance like that of its platens), "traction" (every end particle pulled by the
# same axial force ramped at a constant rate, free sideways: force-controlled ends) or "wide"
# (held as "held", but the two outermost rows or layers at each end)
GRIPS = ("held", "clamped", "springs", "traction", "wide")
# traction grips: the block has failed once its end layers separate faster than RUNAWAY times
# the quasi-static rate (2 x speed: the rate at which the held end layers move apart).  Before
# the failure they separate at that rate (the block starts at it, the traction's rate matched to
# the block's modulus; within 2.5% of it in the validation's runs, N = 4 to 60); once bonds
# at the ends break, the loose particles accelerate under the rising force and the rate jumps
# (7 to 44 times the quasi-static one within one thermo row in those runs), so the threshold
# marks the end of equilibrium while staying clear of the end layers' vibrations
RUNAWAY = 1.5
# the traction grips' per-row log: step, traction (Pa), separation, separation rate / 2 speed
TRACTION_LOG = "traction.dat"


def check_grips(grips: str) -> str:
    """``grips`` if one of :data:`GRIPS`; else a ValueError naming it and the valid ones."""
    if grips not in GRIPS:
        raise ValueError(f"grips = {grips!r} is not known: use one of {', '.join(GRIPS)}")
    return grips


def grip_title(grips: str, kn: float) -> str:
    """A phrase naming the grips ``grips`` (one of :data:`GRIPS`; ``kn``: the springs' N/m)."""
    titles = {"held": "end layers held by smooth planes",
              "clamped": "end layers clamped (axial and lateral motion prescribed)",
              "springs": f"end layers tied by axial springs of {kn:.6g} N/m to smooth planes",
              "traction": "end layers pulled by a uniform traction",
              "wide": "two outermost layers at each end held by smooth planes"}
    check_grips(grips)
    return titles[grips]


def grip_depth(grips: str, dim: int) -> float:
    """How far from each end (in particle diameters d) the centres of the gripped particles
    lie: within 0.6 d (the outermost row or layer, or both staggered rows of a rotated
    lattice's stepped end), for ``wide`` grips 0.6 d plus the spacing of the close-packed rows
    (2D: sqrt(3)/2 d) or layers (3D: sqrt(2/3) d) across the load, so the two outermost."""
    check_grips(grips)
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim} is out of range: use 2 or 3")
    if grips != "wide":
        return 0.6
    return 0.6 + (math.sqrt(3.0) / 2.0 if dim == 2 else math.sqrt(2.0 / 3.0))


def spring_grips(axis: str, plane: str, kn: float, eta: float, area: float,
                 speed: float = 0.0) -> str:
    """Spring grips along ``axis`` (``y`` or ``z``): the top plane's displacement is the
    equal-style expression ``plane`` (the bottom one's its negative), each end particle feels
    ``kn`` times its plane's displacement minus its own; every particle is integrated and
    damped (eta, N s/m); ``variable stress`` is the springs' mean force over ``area`` (m^2),
    tension positive.

    speed: the top plane's constant velocity (m/s; 0 for a stepwise schedule).  The block
    then starts with the matching uniform strain rate (each particle's axial velocity in
    proportion to its height: the velocities the planes impose), so that the springs do not
    ring at their own frequency from a sudden start, as the stiffer ones would for thousands
    of steps at the papers' light damping."""
    if axis not in ("y", "z"):
        raise ValueError(f"axis = {axis!r} is out of range: the loading axis is y or z")
    if not kn > 0:
        raise ValueError(f"kn = {kn} is out of range: need kn > 0 (N/m)")
    k = "xyz".index(axis) + 1
    force = {a: f"v_g{{side}}" if a == axis else "0.0" for a in "xyz"}
    vector = " ".join(force[a] for a in "xyz")
    stiff = f"{kn:.8g}"
    start = _start(axis, speed) if speed != 0.0 else ""
    return start + f"""# each end-layer particle is tied to its plane by an axial spring of {stiff} N/m: its
# force is the stiffness times the plane's displacement minus the particle's own (fix
# addforce); sideways the particles move freely (smooth planes), and every particle is
# integrated and damped
variable        dtop equal {plane}
variable        dbot equal -v_dtop
variable        gtop atom {stiff}*(v_dtop-c_disp[{k}])
variable        gbot atom {stiff}*(v_dbot-c_disp[{k}])
fix             gtop top addforce {vector.format(side="top")}
fix             gbot bottom addforce {vector.format(side="bot")}
{integrator("all", eta)}# stress (tension positive) from the grip springs' forces
compute         ftop top reduce sum v_gtop
compute         fbot bottom reduce sum v_gbot
variable        stress equal 0.5*(c_ftop-c_fbot)/{area:.8g}
"""


def _start(axis: str, speed: float) -> str:
    """Velocities of a block that starts at the strain rate of end layers moving apart at
    ``speed`` each: each particle's axial velocity in proportion to its height."""
    rate = " ".join("v_vstart" if a == axis else "NULL" for a in "xyz")
    return (f"# start at the planes' uniform strain rate\n"
            f"variable        vstart atom {speed:.8g}*({axis}-0.5*(v_lo0+v_hi0))/(0.5*v_H0)\n"
            f"velocity        all set {rate} units box\n")


def traction_grips(axis: str, rate: float, dt: float, speed: float, eta: float,
                   area: float, every: int) -> str:
    """Traction grips along ``axis`` (``y`` or ``z``): every particle of the top layer pulled
    by the same axial force, every one of the bottom layer by the same opposite force, each
    layer's sum
    ``rate`` (Pa/s, negative: pushed together) times the time since the loading started times
    ``area`` (m^2); sideways free; every particle integrated and damped (eta, N s/m).

    The block starts at the quasi-static strain rate of end layers moving at ``speed`` (m/s,
    signed as ``rate``; the traction's rate over the block's modulus), so that it does not
    ring from a sudden start.  ``variable applied`` is the traction (Pa, tension positive);
    ``variable stress`` is the traction while the end layers separate at no more than
    :data:`RUNAWAY` times the quasi-static rate 2 ``speed``, and 0 from the first thermo row
    where they run away: the block no longer carries the force (the failure halt stops the run
    there), so the stress's peak is the traction at the last row of equilibrium.  Every
    ``every`` steps the traction, the end layers' separation (over their initial span) and
    separation rate (over the quasi-static one) go to :data:`TRACTION_LOG`."""
    if axis not in ("y", "z"):
        raise ValueError(f"axis = {axis!r} is out of range: the loading axis is y or z")
    for name, value in (("rate", rate), ("speed", speed)):
        if not (value != 0 and math.isfinite(value)):
            raise ValueError(f"{name} = {value} is out of range: need a finite non-zero value")
    if every < 1:
        raise ValueError(f"every = {every} is out of range: need every >= 1 (steps)")
    if (rate > 0) != (speed > 0):
        raise ValueError(f"rate = {rate} and speed = {speed}: need the same sign (both "
                         "positive: pulled apart)")
    k = "xyz".index(axis) + 1
    vector = " ".join("v_f{side}" if a == axis else "0.0" for a in "xyz")
    return _start(axis, speed) + f"""# the traction: every end-layer particle pulled by the same axial force, the total ramped at
# {rate:.8g} Pa/s times {area:.8g} m^2; sideways the particles move freely, and every particle
# is integrated and damped
variable        applied equal {rate * dt:.8g}*(step-v_s0)
variable        ftop equal v_applied*{area:.8g}/count(top)
variable        fbot equal -v_applied*{area:.8g}/count(bottom)
fix             gtop top addforce {vector.format(side="top")}
fix             gbot bottom addforce {vector.format(side="bot")}
{integrator("all", eta)}# the end layers' separation rate against the quasi-static one (2 x {abs(speed):.6g} m/s)
compute         vtop top reduce ave v{axis}
compute         vbot bottom reduce ave v{axis}
variable        runaway equal (c_vtop-c_vbot)/{2.0 * speed:.8g}
# stress (tension positive): the traction while the block carries it (the end layers separate
# at most {RUNAWAY:g} times the quasi-static rate), 0 once they run away
variable        stress equal v_applied*(v_runaway<={RUNAWAY:g})
# separation of the end layers' centres over their initial span, per thermo row
compute         utop top reduce ave c_disp[{k}]
compute         ubot bottom reduce ave c_disp[{k}]
variable        separation equal (c_utop-c_ubot)/v_H0
fix             tractionlog all ave/time {every} 1 {every} v_applied v_separation v_runaway file {TRACTION_LOG}
"""


def end_layers(spec: DeckSpec) -> str:
    """Loading through the end layers: the particles whose centres lie within
    :func:`grip_depth` of either end, gripped as ``spec.grips`` says (:data:`GRIPS`), moved
    (or pulled) apart in tension and together otherwise; defines ``variable stress``
    (tension positive)."""
    ax, d = spec.axis, spec.d
    sign = 1.0 if spec.pulls else -1.0
    way = "apart" if sign > 0 else "together"
    if spec.grips == "traction":
        motion = f"ramped at {sign * spec.traction_rate:.6g} Pa/s"
    elif spec.schedule == "constant":
        motion = f"moving {way} at {spec.speed:g} m/s"
    else:
        motion = f"jumping {way} by {spec.step_size:g} m every {spec.relax_steps} steps"
    depth = grip_depth(spec.grips, spec.dim) * d
    text = f"""
# ---- loading: {grip_title(spec.grips, spec.grip_kn)}, {motion} ----
region          toplayer block {_slab(ax, f"$(v_hi0-{depth!r})", "INF")} units box
region          botlayer block {_slab(ax, "INF", f"$(v_lo0+{depth!r})")} units box
group           top region toplayer
group           bottom region botlayer
group           inner subtract all top bottom
velocity        all set 0 0 0 units box
variable        s0 equal $(step)
"""
    if spec.grips == "traction":
        return text + traction_grips(ax, sign * spec.traction_rate, spec.dt, sign * spec.speed,
                                     spec.eta, spec.area, spec.thermo_every)
    if spec.grips == "springs":
        plane = (f"{sign * spec.speed * spec.dt:.8g}*(step-v_s0)" if spec.schedule == "constant"
                 else f"{sign * spec.step_size:.6g}*ceil((step-v_s0)/{spec.relax_steps})")
        speed = sign * spec.speed if spec.schedule == "constant" else 0.0
        return text + spring_grips(ax, plane, spec.grip_kn, spec.eta, spec.area, speed)
    # held, wide or clamped: the end layers' motion prescribed (fix move); sideways free
    # (NULL, integrated with the forces on them) or fixed (0)
    lateral = "0" if spec.grips == "clamped" else "NULL"
    if spec.schedule == "constant":
        move_top = f"linear {_vector(ax, f'{sign * spec.speed:.6g}', lateral)}"
        move_bot = f"linear {_vector(ax, f'{-sign * spec.speed:.6g}', lateral)}"
        variables = ""
    else:
        # clamped: zero displacement across the load (z stays NULL in 2D, as fix move needs)
        fixed = "v_zero" if spec.grips == "clamped" else "NULL"
        variables = (f"variable        dtop equal {sign * spec.step_size:.6g}*ceil((step-v_s0)/{spec.relax_steps})\n"
                     f"variable        dbot equal -v_dtop\n"
                     + ("variable        zero equal 0\n" if spec.grips == "clamped" else ""))
        slots = {a: fixed for a in spec.lateral_axes}
        move_top, move_bot = (
            "variable " + " ".join(slots.get(a, var if a == ax else "NULL") for a in "xyz")
            + " NULL NULL NULL" for var in ("v_dtop", "v_dbot"))
    how = ("sideways they stay where they are (clamped)" if spec.grips == "clamped"
           else "sideways they move freely with the block")
    which = ("the two outermost\n# rows or layers" if spec.grips == "wide" else
             "the outermost row, or both\n# staggered rows of a rotated lattice")
    return text + f"""# the end layers (centres within {depth / d:.4g} d of the ends: {which}): their axial motion is prescribed (fix move);
# {how}
{variables}fix             ptop top move {move_top}
fix             pbot bottom move {move_bot}
{integrator("inner", spec.eta)}# stress (tension positive) from the force the block exerts on the end layers
compute         ftop top reduce sum f{ax}
compute         fbot bottom reduce sum f{ax}
variable        stress equal 0.5*(c_fbot-c_ftop)/{spec.area:.8g}
"""


def _slab(axis: str, lo: str, hi: str) -> str:
    """Region block bounds of a slab across the loading axis (INF along the others)."""
    return " ".join(f"{lo} {hi}" if a == axis else "INF INF" for a in "xyz")


def _vector(axis: str, value: str, other: str = "0") -> str:
    """'other value other' with value in the loading axis' slot."""
    return " ".join(value if a == axis else other for a in "xyz")
