"""A new contact forms at the step the closed form gives, however large the neighbour skin.

Unbonded pairs within touching distance + skin are contact candidates, collected at each
reneighbouring.  A candidate is tested only once the displacements since the collection
could have closed its gap (twice the largest displacement of any local or ghost atom,
summed over the steps, reaches the smallest gap); with a large skin the atoms then go
hundreds of steps without a rebuild, so a bound that missed a displacement would let
the pair pass through each other unseen.

The set-up: particle 1 at rest at the origin, particle 2 approaching along x at v from a
gap g (centres d + g apart), no other force.  Verlet moves particle 2 by v dt per step, so
the distance after n steps is d + g - n v dt, and the contact (distance < d) exists from
step n* = floor(g / (v dt)) + 1 on.  The skin (2 d) keeps LAMMPS from reneighbouring for
1000 steps, well past n*.  Checked with the pair style's own displacement pass (fix nve)
and with the displacements measured by fix lattice/nve, on 1 rank and on 2 ranks with the
two particles on different ranks (the moving one a ghost on the resting one's rank), and in
a periodic box that fix deform shrinks, where the remap alone brings the pair together.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers.decks import atoms_at, opening, pair_lines, run_deck, sphere_props
from helpers.materials import D, QUARTZ_3D, QUARTZ_MASS

V = 1.0        # m/s, approach speed
DT = 1.0e-6    # s: v dt = 1e-3 d per step
GAP = 0.205 * D    # beyond any bonding tolerance; n v dt never equals it (no tie at n*)
ONSET = math.floor(GAP / (V * DT)) + 1    # 206


def deck(integrator: str) -> str:
    return opening(3, box="-0.002 0.004 -0.002 0.002 -0.002 0.002") + f"""
{atoms_at([(0.0, 0.0, 0.0), (D + GAP, 0.0, 0.0)], units="units box")}
{sphere_props(D, QUARTZ_MASS[3])}
{pair_lines(QUARTZ_3D)}
neighbor        {2 * D} bin
velocity        all set 0 0 0 units box
group           mover id 2
velocity        mover set {-V} 0 0 units box
fix             move all {integrator}
compute         b all lattice/bonds
variable        x2 equal x[2]
variable        v2 equal vx[2]
thermo_style    custom step c_b[1] c_b[4] v_x2 v_v2
thermo_modify   format float %.17g
thermo          1
timestep        {DT}
run             {ONSET + 20}
"""


@pytest.mark.parametrize("integrator", ["nve", "lattice/nve"])
@pytest.mark.parametrize("np_", [1, pytest.param(2, marks=pytest.mark.mpi)])
def test_contact_forms_at_the_closed_form_step(tmp_path, integrator, np_):
    text = deck(integrator)
    if np_ == 2:
        # x split at 1 mm: particle 1 (at rest) on rank 0, particle 2 on rank 1
        text = text.replace("newton          on\n", "newton          on\nprocessors      2 1 1\n")
    res = run_deck(text, tmp_path, np=np_)
    assert res.returncode == 0, res.error
    assert "Neighbor list builds = 0" in res.output, "a rebuild would collect the pair anew"
    th = res.last_thermo()
    steps = th["Step"].astype(int)
    contacts = th["c_b[4]"]
    assert np.all(th["c_b[1]"] == 0)    # never bonded
    # no contact before n*, one from n* on
    np.testing.assert_array_equal(contacts[steps < ONSET], 0)
    assert contacts[steps == ONSET][0] == 1
    # until n* particle 2 moved freely (Verlet with no force: x = d + g - n v dt, exactly
    # up to the rounding of the sum); from n* on the contact pushes it back
    free = steps < ONSET
    np.testing.assert_allclose(th["v_x2"][free], D + GAP - steps[free] * V * DT, rtol=0,
                               atol=1e-15)
    assert np.all(th["v_v2"][steps > ONSET] > -V)


# A box that deforms: particles at rest, carried together by `fix deform ... remap x` alone.
# Their centres sit symmetric about the box centre, so the distance scales with the box
# length, s L(n) / L0 with L(n) = L0 - n V dt, and the contact exists from the first step
# with s L(n) / L0 < d: n* = floor(L0 (1 - d / s) / (V dt)) + 1.  fix deform changes the box
# at the end of a step, after the forces, so the force evaluation that sees those positions
# is step n* + 1's: the contact record exists from there on (the thermo row of step n*
# shows the box and positions after the change, and no contact yet).  Every displacement
# here is the remap's; a bound that left it out would miss the contact.
L0 = 6.0e-3
SEP = D + GAP
DEFORM_ONSET = math.floor(L0 * (1 - D / SEP) / (V * DT)) + 1    # 1021


@pytest.mark.parametrize("np_", [1, pytest.param(2, marks=pytest.mark.mpi)])
def test_contact_forms_when_the_box_brings_the_pair_together(tmp_path, np_):
    text = opening(3, box=f"{-L0 / 2} {L0 / 2} -0.002 0.002 -0.002 0.002", boundary="p f f",
                   settings="processors 2 1 1" if np_ == 2 else "") + f"""
{atoms_at([(-SEP / 2, 0.0, 0.0), (SEP / 2, 0.0, 0.0)], units="units box")}
{sphere_props(D, QUARTZ_MASS[3])}
{pair_lines(QUARTZ_3D)}
neighbor        {2 * D} bin
fix             squeeze all deform 1 x vel {-V} remap x
compute         b all lattice/bonds
variable        x2 equal x[2]
thermo_style    custom step c_b[1] c_b[4] lx v_x2
thermo_modify   format float %.17g
thermo          1
timestep        {DT}
run             {DEFORM_ONSET + 20}
"""
    res = run_deck(text, tmp_path, np=np_)
    assert res.returncode == 0, res.error
    assert "Neighbor list builds = 0" in res.output, "a rebuild would collect the pair anew"
    th = res.last_thermo()
    steps = th["Step"].astype(int)
    # the box and the particle follow the closed form (the remap's arithmetic: 1e-15 m)
    np.testing.assert_allclose(th["Lx"], L0 - steps * V * DT, rtol=0, atol=1e-15)
    free = steps < DEFORM_ONSET
    np.testing.assert_allclose(th["v_x2"][free], SEP / 2 * (L0 - steps[free] * V * DT) / L0,
                               rtol=0, atol=1e-15)
    assert np.all(th["c_b[1]"] == 0)
    np.testing.assert_array_equal(th["c_b[4]"][steps <= DEFORM_ONSET], 0)
    assert th["c_b[4]"][steps == DEFORM_ONSET + 1][0] == 1
