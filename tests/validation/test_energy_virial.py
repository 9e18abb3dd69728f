"""thermo pe, compute pressure and compute stress/atom see the bond springs.

A single bond is stretched by delta along x and sheared by s along y; the
expected spring energy and virial follow directly from the force law:
Fn = Kn*delta, Fs = Ks*s, energy 0.5*Kn*delta^2 + 0.5*Ks*s^2, and the virial
W_ab = sum over pairs of (x_i - x_j)_a * F_i_b.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.decks import atoms_at, opening, pair_lines, sphere_props
from helpers.materials import D

KN, KS = 2.0e6, 5.0e5


def build(lmp, dimension: int) -> None:
    lmp.commands_string(opening(dimension, box="-0.01 0.01 -0.01 0.01 -0.01 0.01")
                        + atoms_at([(0, 0), (D, 0)]) + sphere_props(D, 1.0)
                        + pair_lines({"1 1": f"{KN} {KS} 1.0 1.0e6 0.0"}) + """\
compute vir all pressure NULL virial
compute sa all stress/atom NULL virial
compute sasum all reduce sum c_sa[1] c_sa[2] c_sa[4]
thermo_style custom step pe c_vir[1] c_vir[2] c_vir[4] c_sasum[1] c_sasum[2] c_sasum[3]
fix 1 all nve
run 0
""")


@pytest.mark.parametrize("dimension", [2, 3])
def test_bond_energy_and_virial(lmp_instance, dimension):
    lmp = lmp_instance
    build(lmp, dimension)
    delta, s = 2.0e-6, 1.0e-6
    # move particle 2 by (delta, s): the shear spring takes the tangential part
    lmp.commands_string(f"""
displace_atoms all move 0 0 0 units box
group two id 2
displace_atoms two move {delta} {s} 0 units box
run 0
""")
    x = lmp.numpy.extract_atom("x")
    ids = lmp.numpy.extract_atom("id")
    i1, i2 = int(np.where(ids == 1)[0][0]), int(np.where(ids == 2)[0][0])
    dx = x[i1, :3] - x[i2, :3]
    r = np.linalg.norm(dx)
    n = dx / r
    xn = r - D
    # the shear increment is the tangential part of the relative displacement
    ddx = np.array([-delta, -s, 0.0])
    shear = ddx - np.dot(ddx, n) * n
    if dimension == 2:
        # 2D takes it along the mid-step tangent: (t . u)(1 + n . u / 2r), to second order
        shear *= 1.0 + 0.5 * np.dot(ddx, n) / r
    f1 = -KN * xn * n - KS * shear
    energy = 0.5 * KN * xn**2 + 0.5 * KS * np.dot(shear, shear)
    pe = lmp.get_thermo("pe")
    assert pe == pytest.approx(energy, rel=1e-9)

    volume = 0.02**dimension  # LAMMPS uses the box area as volume in 2d
    w = np.outer(dx, f1)  # W_ab = dx_a * F1_b
    pxx, pyy, pxy = (lmp.numpy.extract_compute("vir", 0, 1)[k] for k in (0, 1, 3))
    assert pxx * volume == pytest.approx(w[0, 0], rel=1e-9)
    assert pyy * volume == pytest.approx(w[1, 1], rel=1e-9)
    assert pxy * volume == pytest.approx(w[0, 1], rel=1e-6)
    # per-atom stress (pressure*volume units, sign: -virial) sums to the same
    sums = lmp.numpy.extract_compute("sasum", 0, 1)
    assert -sums[0] == pytest.approx(w[0, 0], rel=1e-9)
    assert -sums[1] == pytest.approx(w[1, 1], rel=1e-9)
    assert -sums[2] == pytest.approx(w[0, 1], rel=1e-6)
