"""What the 3D part of the speed-against-error study runs (3D quartzite, block sizes n_y):
its full and quick modes, :class:`~.settings.Settings` with ``dim = 3``.

The 2D study found the constant schedule's defaults for 2D; in 3D the papers' damping is
part of the set-up (docs/validation.md, "3D compression: how slow constant loading must be":
a quarter of it converges to a lower Cu), so the grid reaches slow loading (3000 crossings)
at dampings around the papers' eta.  The references are the closed-form formulas for E and
nu and the papers' 3D stepwise schedule (PAPER_SCHEDULES[3]: 100 relaxation steps) at the
same size for Tu and Cu; the stepwise variants with 4x fewer relaxation steps and 4x larger
steps show how converged that reference is.  The transfer check runs on a larger block
against the papers' stepwise schedule at that size.  No lattice time-step scan (2D part)
and no time-step variants: the same time step as in 2D, 0.1 sqrt(m/Kn).
"""

from __future__ import annotations

import dataclasses

from .settings import FULL, QUICK, Settings

FULL_3D: Settings = dataclasses.replace(
    FULL, dim=3, n_elastic=10, n_strength=6, n_check=10,
    crossings=(30, 100, 300, 1000, 3000), dampings=(0.25, 0.5, 1.0, 2.0),
    slow_crossings=(), dt_fractions=(), relax=(100, 25), step_factors=(1, 4),
    check_reference_crossings=None, stability=False)

QUICK_3D: Settings = dataclasses.replace(
    QUICK, dim=3, n_elastic=4, n_strength=4, n_check=6,
    crossings=(100, 1000), dampings=(0.5, 1.0), slow_crossings=(), dt_fractions=(),
    relax=(100, 25), step_factors=(1,), check_reference_crossings=None, stability=False)
