"""Walls: smooth walls of ``fix lattice/wall`` and rows of wall particles.

- :func:`smooth_wall`: a frictionless plane (``Ks = 0``, ``mu = 0``) that pushes the
  particles it touches; fixed, moving (``vel``), following a variable, or servo-controlled
  to a stress (``servo``): the rock tests' platens and confining side walls;
- :func:`wall_rows`: the outermost row of particles on each side of a 2D box, held
  perpendicular to its side by ``fix setforce`` and free to slide along it (frictionless
  walls made of particles): the scenes' deformation box.
"""

from __future__ import annotations


def smooth_wall(fix_id: str, face: str, position: str, kn: float, keywords: str = "") -> str:
    """``fix ID all lattice/wall FACE POSITION Kn 0 0 [keywords]``: a smooth wall of
    stiffness kn (N/m) on face (e.g. ``ylo``) at position (a number, ``$(...)`` or
    ``v_name``); keywords: e.g. ``vel 0.05`` or ``servo 5e6 AREA``."""
    tail = f" {keywords}" if keywords else ""
    return f"fix             {fix_id} all lattice/wall {face} {position} {kn:.6g} 0 0{tail}\n"


def wall_rows() -> str:
    """The groups ``left``, ``right``, ``bottom``, ``top`` (the wall rows), ``walls`` and
    ``inner``, and the fixes ``wleft`` ... ``wtop`` that hold each row perpendicular to
    its side (their global vectors: the force removed, the wall's reaction).

    Needs ``variable d`` (the particle diameter).  Left and right: centres within 0.6 d of
    the outermost x; bottom and top: the outermost rows in y (within 0.1 d).
    """
    return """# ---- the deformation box: one row of wall particles per side ----
# held perpendicular to its wall (fix setforce zeroes that force component:
# the force it removes, its global vector, is the wall's reaction), free to
# slide along it: frictionless walls.  Corner particles belong to two walls.
region          rleft block INF $(bound(all,xmin)+0.6*v_d) INF INF INF INF units box
region          rright block $(bound(all,xmax)-0.6*v_d) INF INF INF INF INF units box
region          rbottom block INF INF INF $(bound(all,ymin)+0.1*v_d) INF INF units box
region          rtop block INF INF $(bound(all,ymax)-0.1*v_d) INF INF INF units box
group           left region rleft
group           right region rright
group           bottom region rbottom
group           top region rtop
group           walls union left right bottom top
group           inner subtract all walls
fix             wleft left setforce 0.0 NULL NULL
fix             wright right setforce 0.0 NULL NULL
fix             wbottom bottom setforce NULL 0.0 NULL
fix             wtop top setforce NULL 0.0 NULL
"""
