"""Helpers shared by the test modules (tests/unit, tests/integration, tests/validation).

- :mod:`helpers.materials`: the papers' quartz as bond coefficients, from the package's own
  conversion (no coefficient is typed in a test);
- :mod:`helpers.decks`: the openings of the LAMMPS decks the tests write, and ``run_deck``.

Readers of dumps and thermo output are the package's (:mod:`bonded_lattice.io`).
The folder ``tests`` is on ``sys.path`` (pytest puts the folder of ``tests/conftest.py``
there), so the test modules import ``helpers.materials`` and ``helpers.decks``.
"""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
"""The repository's root folder."""
INPUTS = REPO / "inputs"
"""The example decks (inputs/in.tension2d, ...)."""
DATA = REPO / "tests" / "data"
"""Files the tests read: restart files of older formats, the force-style YAML files."""
