"""Grips of the end layers when a rock test loads its block through them (tension, an elastic
test in tension, compression with ``ends="layers"``; :data:`bonded_lattice.decks.GRIPS`).

- :func:`grip_title`: what holds the end layers, for a deck's comments;
- :func:`spring_grips`: each end-layer particle tied to a moving smooth plane by an axial
  spring (``fix addforce`` of an atom-style variable), free sideways: the 2013 paper's
  "lattice bonded by two smooth planes" (para. 42) with a finite stiffness, like its
  platens'.  The held and clamped grips (the end layers' motion prescribed by ``fix move``)
  are written by :func:`bonded_lattice.decks.deck_text` itself.

Needs the groups ``top`` and ``bottom`` (the end layers), ``compute disp`` (displace/atom),
``variable s0`` (the step the loading starts at) and the block's extent ``v_lo0``, ``v_hi0``,
``v_H0`` along the loading axis.
"""

from __future__ import annotations

from .integrator import integrator

__all__ = ["grip_title", "spring_grips"]


def grip_title(grips: str, kn: float) -> str:
    """A phrase naming the grips ``grips`` (held, clamped, springs of ``kn`` N/m)."""
    titles = {"held": "end layers held by smooth planes",
              "clamped": "end layers clamped (axial and lateral motion prescribed)",
              "springs": f"end layers tied by axial springs of {kn:.6g} N/m to smooth planes"}
    if grips not in titles:
        raise ValueError(f"grips = {grips!r} is not known: use one of {', '.join(titles)}")
    return titles[grips]


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
    start = ""
    if speed != 0.0:
        rate = " ".join(f"v_vstart" if a == axis else "NULL" for a in "xyz")
        start = (f"# start at the planes' uniform strain rate\n"
                 f"variable        vstart atom {speed:.8g}*({axis}-0.5*(v_lo0+v_hi0))/(0.5*v_H0)\n"
                 f"velocity        all set {rate} units box\n")
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
