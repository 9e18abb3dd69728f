"""Speed against error: how many time steps the tests need for a given accuracy.

The analysis of ``bench/speed_error.py`` (which only parses its command line and calls
these), one concern per module:

- :mod:`.settings`: the tolerances, the full and quick modes (:class:`Settings`), the lattice
  runs (:class:`Case`, :func:`lattice_cases`);
- :mod:`.fitting`: the pure functions (Pareto front, convergence order, Verlet's discrete
  oscillator, bisection, the tolerance test, the recommendation rule);
- :mod:`.contact`: part 1, the single-contact tests T1-T4 against the time step and the
  stability limit of a contact spring;
- :mod:`.settings_3d`: the 3D part's modes (:data:`FULL_3D`, :data:`QUICK_3D`);
- :mod:`.lattice_runs`: parts 2 and 4, the 2D quartz and 3D quartzite lattice runs
  (:class:`SpeedErrorRun`, a :class:`bonded_lattice.study.Study`), their errors, the
  stability scan, the recommendation and its check;
- :mod:`.plots`, :mod:`.report`, :mod:`.report_lattice`, :mod:`.report_fronts`,
  :mod:`.recommendation`, :mod:`.report_defaults` (the references' convergence, the
  defaults on the Pareto front), :mod:`.report_3d` (part 4), :mod:`.text`: the figures and
  the Markdown report (docs/speed_error.md).
"""

from __future__ import annotations

from .contact import CONTACT, run_contact
from .fitting import (bisect_limit, convergence_order, grid_front, local_orders,
                      oscillator_stable, pareto_front, recommend, robust_shares, speedup,
                      verlet_growth, verlet_oscillator, within, worst_share)
from .lattice_runs import SpeedErrorRun, premature_halt, run_case, run_lattice
from .report import write_doc
from .settings import (DEFAULT, FULL, LEVELS, QUANTITIES, QUICK, TEST_OF, TOLERANCE, Case,
                       Settings, grid_case, lattice_cases, paper_relax)
from .settings_3d import FULL_3D, QUICK_3D

__all__ = ["CONTACT", "DEFAULT", "FULL", "FULL_3D", "LEVELS", "QUANTITIES", "QUICK",
           "QUICK_3D", "TEST_OF", "TOLERANCE", "Case", "Settings", "SpeedErrorRun",
           "bisect_limit", "convergence_order", "grid_case", "grid_front",
           "lattice_cases", "local_orders", "oscillator_stable", "paper_relax",
           "pareto_front", "premature_halt", "recommend", "robust_shares", "run_case",
           "run_contact", "run_lattice", "speedup", "verlet_growth",
           "verlet_oscillator", "within", "worst_share", "write_doc"]
