"""A layered model with a 1000:1 stiffness contrast (a stiff layer under a soft one, the
interface bonds at the mean stiffness) stays stable at the recommended time step, half the
critical time step the pair style reports (set by the stiff layer), and conserves energy
over a long undamped vibration."""

from __future__ import annotations

import re

import numpy as np
import pytest
from bonded_lattice.conversion import critical_time_step
from helpers.decks import block_2d_deck, run_deck
from helpers.materials import QUARTZ, QUARTZ_MASS

MASS = QUARTZ_MASS[2]
KN, KS, MU = QUARTZ[2].Kn, QUARTZ[2].Ks, QUARTZ[2].mu_p   # the stiff layer (quartz, 2D); the
                                                          # soft one has 1/1000
CONTRAST = 1000.0
DECK = block_2d_deck("-2 14 -2 14", "0 10 0 10", types=2, coeffs=None) + f"""
region          upper block INF INF 4.5 INF INF INF
set             region upper type 2
pair_style      lattice/bond
pair_coeff      1 1 {KN} {KS} 1.0e-5 1.0e6 {MU}
pair_coeff      2 2 {KN / CONTRAST} {KS / CONTRAST} 1.0e-2 1.0e6 {MU}
pair_coeff      1 2 {0.5 * (KN + KN / CONTRAST)} {0.5 * (KS + KS / CONTRAST)} 1.0e-5 1.0e6 {MU}
variable        vx atom 0.01*normal(0,1,5531)
variable        vy atom 0.01*normal(0,1,9127)
velocity        all set v_vx v_vy NULL units box
velocity        all zero linear
fix             nve all nve
thermo_style    custom step ke pe etotal
thermo          1000
timestep        ${{dt}}
run             40000
"""


def test_layered_1000_to_1_contrast_is_stable_at_the_recommended_time_step(tmp_path):
    dt = 0.5 * critical_time_step(MASS, KN, KS, 2)
    result = run_deck(DECK, tmp_path, args=["-var", "dt", repr(dt)])
    assert result.returncode == 0, result.output[-2000:]
    reported = float(re.search(r"critical time step ([0-9.eE+-]+)", result.output).group(1))
    # the stiff layer sets it: the interior particles of the stiff layer have 6 stiff bonds
    assert reported == pytest.approx(critical_time_step(MASS, KN, KS, 2), rel=1e-5)
    assert "WARNING: Time step" not in result.output
    thermo = result.thermo[0]
    e = np.asarray(thermo["TotEng"])
    assert np.all(np.isfinite(e))
    # undamped and stable: the total energy fluctuates (Verlet at half the critical step:
    # a few per cent) around a constant mean, without growth
    mean = e[1:].mean()
    assert np.max(np.abs(e / mean - 1.0)) < 0.05
    half = len(e) // 2
    assert abs(e[half:].mean() / e[1:half].mean() - 1.0) < 2e-3
    # both layers move: the soft layer's slow modes carry energy too
    assert max(thermo["KinEng"]) > 0 and max(thermo["PotEng"]) > 0
