"""Number formats of the speed-against-error report."""

from __future__ import annotations


def pct(x: float | None, digits: int = 2) -> str:
    """A relative error as a signed percentage, or "failed" for a run without one."""
    return "failed" if x is None else f"{100 * x:+.{digits}f}%"


def cost(r: dict) -> str:
    """The cost columns of a run: time steps | particle-steps | wall seconds."""
    return f"{r['steps']} | {r['particle_steps']:.3g} | {r['wall_s']:.1f}"
