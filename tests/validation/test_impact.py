"""A bonded 2D block (179 particles, quartz) hits a rough fixed wall at 100 m/s and
shatters: every bond breaks (in tension and in shear), no atom is lost, no value is NaN,
and the energy budget of compute lattice/energy still closes: the balance error stays
below 1e-3 of the impact's kinetic energy and falls with the time step (docs/robustness.md)."""

from __future__ import annotations

import numpy as np
from helpers.decks import block_2d_deck, run_deck

DECK = block_2d_deck("-1 11 -1 9", "0 10 0 8", boundary="s s p") + """
neigh_modify    every 1 delay 0 check yes
velocity        all set 0 -100 0 units box
fix             nve all nve
# a rough floor just below the bottom row: 2 Kn, a shear spring and friction 0.3
fix             floor all lattice/wall ylo -0.51e-3 1.3175e11 4.743e10 0.3
compute         e all lattice/energy
compute         b all lattice/bonds
thermo_style    custom step atoms ke c_e[5] c_e[6] c_e[7] c_e[9] c_e[10] c_b[1] c_b[2] c_b[3]
thermo_modify   lost error
thermo          1000
timestep        ${dt}
run             ${steps}
"""


def run(tmp_path, dt, steps):
    res = run_deck(DECK, tmp_path, args=["-var", "dt", repr(dt), "-var", "steps", str(steps)])
    assert res.returncode == 0, res.output[-2000:]
    return res.thermo[0]


def test_impact_at_100_m_per_s_shatters_the_block_and_the_budget_closes(tmp_path):
    rows = {dt: run(tmp_path / f"dt{dt}", dt, int(6e-4 / dt)) for dt in (2e-8, 1e-8)}
    errors = {}
    for dt, t in rows.items():
        for col in t:
            assert np.all(np.isfinite(t[col])), col
        assert np.all(t["Atoms"] == 179)                    # nothing lost
        assert t["c_b[1]"][-1] == 0                          # every bond broke ...
        assert t["c_b[2]"][-1] > 0 and t["c_b[3]"][-1] > 0   # ... in tension and in shear
        ke0 = t["KinEng"][0]
        assert ke0 > 2000.0                                  # 179 x 2.295e-3 kg at 100 m/s
        assert t["c_e[7]"][-1] > 0.1 * ke0                   # friction took a good part
        errors[dt] = np.max(np.abs(t["c_e[10]"])) / ke0
        assert errors[dt] < 1e-3                             # measured 2.7e-4, 8.5e-5
    # smaller time step, smaller error (about second order through the impact)
    assert errors[2e-8] / errors[1e-8] > 2.0
