"""Confined compression far beyond failure: a bonded 2D block (179 particles) squeezed
between platens closing at 5 m/s each, inside fixed side walls, until particles overlap by
more than half a diameter.  No atom is lost, nothing becomes NaN, the record store grows for
the new contacts within the default maxslot, and the energy budget still closes against
the platens' work (docs/robustness.md)."""

from __future__ import annotations

import numpy as np
from bonded_lattice.io import read_atom_dump
from helpers.decks import block_2d_deck, run_deck

D = 1.0e-3
DECK = block_2d_deck("-1 11 -1 9", "0 10 0 8", boundary="s s p") + """
neigh_modify    every 1 delay 0 check yes
variable        ylo equal $(bound(all,ymin)-0.5e-3)
variable        yhi equal $(bound(all,ymax)+0.5e-3)
variable        xlo equal $(bound(all,xmin)-0.5e-3)
variable        xhi equal $(bound(all,xmax)+0.5e-3)
fix             nve all nve
fix             damp all lattice/viscous 10.0
fix             bottom all lattice/wall ylo ${ylo} 1.3175e11 0 0 vel 5.0
fix             top all lattice/wall yhi ${yhi} 1.3175e11 0 0 vel -5.0
fix             left all lattice/wall xlo ${xlo} 1.3175e11 0 0
fix             right all lattice/wall xhi ${xhi} 1.3175e11 0 0
compute         e all lattice/energy
compute         b all lattice/bonds
thermo_style    custom step atoms ke c_e[1] c_e[8] c_e[9] c_e[10] c_b[1] c_b[4]
thermo_modify   lost error
thermo          2000
timestep        2.0e-8
run             48000
write_dump      all custom final.dump id x y modify sort id format float %.17g
"""


def test_compression_to_overlaps_beyond_half_a_diameter(tmp_path):
    res = run_deck(DECK, tmp_path)
    assert res.returncode == 0, res.output[-2000:]
    t = res.thermo[0]
    for col in t:
        assert np.all(np.isfinite(t[col])), col
    assert np.all(t["Atoms"] == 179)
    # the closest pair overlaps by more than half a diameter (measured: 0.56 d)
    names, rows = read_atom_dump(tmp_path / "final.dump")
    p = rows[:, [names.index("x"), names.index("y")]]
    dist = np.sqrt(((p[:, None, :] - p[None, :, :]) ** 2).sum(-1))
    np.fill_diagonal(dist, np.inf)
    assert dist.min() < 0.5 * D
    # many new contacts (more than the lattice had bonds per particle)
    assert t["c_b[4]"][-1] > 400
    # the budget closes against the platens' work (measured 3e-5 at the end)
    work = t["c_e[8]"]
    rows = work > 0.01 * work[-1]
    assert np.max(np.abs(t["c_e[10]"][rows]) / work[rows]) < 2e-4
