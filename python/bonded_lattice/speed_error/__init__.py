"""Speed against error: how many time steps the tests need for a given accuracy.

The analysis of ``bench/speed_error.py`` (which only parses its command line and calls
these), one concern per module:

- :mod:`.settings`: the tolerances, the full and quick modes (:class:`Settings`), the lattice
  runs (:class:`Case`, :func:`lattice_cases`);
- :mod:`.fitting`: the pure functions (Pareto front, convergence order, Verlet's discrete
  oscillator, bisection, the tolerance test, the recommendation rule);
- :mod:`.contact`: part 1, the single-contact tests T1-T4 against the time step and the
  stability limit of a contact spring;
- :mod:`.lattice_runs`: part 2, the 2D quartz lattice runs (:class:`SpeedErrorRun`, a
  :class:`bonded_lattice.study.Study`), their errors, the stability scan, the
  recommendation and its check;
- :mod:`.plots`, :mod:`.report`, :mod:`.report_lattice`, :mod:`.report_fronts`,
  :mod:`.recommendation`, :mod:`.text`: the figures and the Markdown report
  (docs/speed_error.md).
"""

from __future__ import annotations

from .contact import CONTACT, run_contact
from .fitting import (bisect_limit, convergence_order, local_orders, oscillator_stable,
                      pareto_front, recommend, speedup, verlet_growth, verlet_oscillator,
                      within)
from .lattice_runs import SpeedErrorRun, premature_halt, run_case, run_lattice
from .report import write_doc
from .settings import (DEFAULT, FULL, LEVELS, QUANTITIES, QUICK, TEST_OF, TOLERANCE, Case,
                       Settings, lattice_cases)

__all__ = ["CONTACT", "DEFAULT", "FULL", "LEVELS", "QUANTITIES", "QUICK", "TEST_OF",
           "TOLERANCE", "Case", "Settings", "SpeedErrorRun", "bisect_limit",
           "convergence_order", "lattice_cases", "local_orders", "oscillator_stable",
           "pareto_front", "premature_halt", "recommend", "run_case", "run_contact",
           "run_lattice", "speedup", "verlet_growth", "verlet_oscillator", "within",
           "write_doc"]
