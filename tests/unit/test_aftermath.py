"""The energy decks' aftermath: how long a run goes on after the failure halt's condition.

Liu 2017 Fig. 6a reads the compression failure from the elastic energy's decline (A2 to A3),
which takes longer than the 20 us the energy decks run on by default; ``aftermath`` sets it.
"""

from __future__ import annotations

import math

import pytest
from bonded_lattice.experiment import (AFTERMATH_MAX, ENERGY_AFTERMATH, RockTest,
                                       check_aftermath, deck_spec)
from bonded_lattice.rocks import get_rock


@pytest.mark.parametrize("bad", [0.0, -1e-6, AFTERMATH_MAX * 1.01])
def test_an_aftermath_out_of_range_is_refused_with_the_range(bad):
    with pytest.raises(ValueError, match=r"aftermath = .* is out of range: need 0 < aftermath"):
        check_aftermath(bad)
    with pytest.raises(ValueError, match="aftermath"):
        RockTest(get_rock("quartz"), 2, "compression", 4, "unused", aftermath=bad)


@pytest.mark.parametrize("aftermath", [ENERGY_AFTERMATH, 3.0e-4])
def test_the_deck_runs_on_for_the_aftermath_in_time_steps(tmp_path, aftermath):
    test = RockTest(get_rock("quartz"), 2, "compression", 4, tmp_path, np_=1, progress=False,
                    energy=True, aftermath=aftermath)
    test._plan()
    spec = deck_spec(test.plan, "compression", 2, test.bond, energy=True, aftermath=aftermath)
    # whole time steps covering the aftermath: ceil(aftermath / dt)
    assert spec.halt_delay == math.ceil(aftermath / test.plan.dt)
    # without the energy budget there is no aftermath: the halt stops the run at once
    assert deck_spec(test.plan, "compression", 2, test.bond, aftermath=aftermath).halt_delay == 0
