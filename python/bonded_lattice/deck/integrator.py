"""The integrator of a deck: velocity Verlet (``fix lattice/nve``) and viscous damping."""

from __future__ import annotations


def integrator(group: str, eta: float, damp_group: str | None = None, note: str = "") -> str:
    """``fix integrate`` (lattice/nve) of ``group`` and ``fix damp`` (lattice/viscous, coefficient
    eta in N s/m) of ``damp_group`` (default: the same group); note: comment lines (each
    ending in a newline) on the damping."""
    return (f"fix             integrate {group} lattice/nve    # velocity Verlet; in 2D x and y only\n"
            f"{note}fix             damp {damp_group or group} lattice/viscous {eta:.6g}\n")
