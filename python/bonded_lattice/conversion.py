"""Rock properties <-> bond parameters of the bonded close-packed lattice (closed form).

Sources (the formulas are derived and checked in docs/theory.md):

- 2D hexagonal lattice: Liu, Pollard & Shi (2013), J. Geophys. Res. 118, 71-82,
  Appendix B (rock -> bond, eqs. B1-B5) and Appendix C (bond -> rock, eqs. C1-C5).
- 3D close-packed lattice: Liu et al. (2017), Comput. Geosci. 103, 12-20, Appendix B
  (rock -> bond, eqs. B1-B5) and eqs. 4, 6, 7, 14, 15 (bond -> rock).  Its Table 1
  misprints Ks as 8.068e5 N/m; the formulas give 8.0679e6 N/m.

Units (SI).  Stresses E, Tu, Cu in Pa; lengths d, Xb in m.  In 3D, Kn and Ks are in N/m,
Fs0 in N and the particle mass in kg.  In 2D the lattice is a slab one metre thick, so Kn and
Ks are in N/m per metre of thickness (N/m^2), Fs0 in N per metre and the mass in kg per metre:
the numbers the 2013 paper prints ("Kn = 65.87 GN/m", "Fs0 = 36.90 kN").  Use them unchanged
in a LAMMPS ``dimension 2`` run: with masses per metre, every force LAMMPS reports is per metre
of thickness, and a stress is a force divided by a width times 1 m.  In 2D, E and nu are the
rock's constants in plane strain (2013 eq. 14).

Valid ranges (checked by every public function; ValueError names the value and the range):

============  ==============================  ==============================  =================
quantity      2D                              3D                              because
============  ==============================  ==============================  =================
nu            0 <= nu <= 1/4                  0 <= nu <= 1/5                  Ks >= 0; Ks <= Kn
mu_i          mu_i >= 1/sqrt3 (0.5774)        mu_i >= 1/(2 sqrt2) (0.3536)    mu_p >= 0
Ks            0 <= Ks <= Kn                   0 <= Ks <= Kn                   0 <= nu <= max
mu_p          0 <= mu_p < 1/sqrt3             0 <= mu_p < 1/sqrt2             0 < Cu < inf
E, Tu, Cu,    > 0 and finite                  > 0 and finite
d, Kn, Xb,
Fs0
============  ==============================  ==============================  =================

nu < 0 is excluded although the elastic formulas allow it (down to -1): then Ks > Kn, the
horizontal bonds of the papers' unit are compressed in uniaxial compression and never open,
while the compressive-strength formulas assume they carry no force (2013 sec. 4.2, 2017
sec. 3.4).

Within these ranges the formulas are exact inverses, but the papers' unit reaches Cu only if
its horizontal bonds open (at C_open, 2013 eq. 22, 2017 eq. 8) before the inclined bonds slide,
and if the bonds can slide at all (Ks > 0).  ``rock_to_bond`` and ``bond_to_rock`` warn
(UserWarning, text from :func:`compressive_strength_caveat`) when C_open > Cu with nu > 0 (the
unit is then stronger than Cu) or when Ks = 0.  Close to the largest nu, Ks is small and the
compressive failure strain (2013 eq. 32) large, so Cu loses accuracy before that point.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import astuple, dataclass

__all__ = [
    "MU_I_MIN",
    "MU_P_MAX",
    "NU_MAX",
    "BondParameters",
    "RockProperties",
    "bond_to_rock",
    "c_open",
    "compressive_strength_caveat",
    "critical_time_step",
    "lame_lambda_2d",
    "lattice_mass",
    "paper_damping_2d",
    "paper_damping_3d",
    "rock_to_bond",
    "rock_to_bond_props",
    "shear_modulus_2d",
    "tensile_failure_strain_2d",
    "validate_bond",
    "validate_rock",
]

SQ2 = math.sqrt(2.0)
SQ3 = math.sqrt(3.0)

NU_MAX = {2: 0.25, 3: 0.2}                      # Ks >= 0 (2013 eq. B2, 2017 eq. B2)
MU_I_MIN = {2: 1.0 / SQ3, 3: 1.0 / (2.0 * SQ2)}   # mu_p >= 0 (eqs. B5)
# internal friction at most 100 (friction angle 89.4 degrees): far beyond any rock, and
# above it Fs0 = (1 - sqrt2 mu_p) ... loses digits to rounding as mu_p nears its limit
# (relative error about 1e-16 mu_i^2)
MU_I_MAX = 100.0
MU_P_MAX = {2: 1.0 / SQ3, 3: 1.0 / SQ2}         # Cu finite (2013 eq. 29, 2017 eq. 14)
_COORDINATION = {2: 6, 3: 12}                   # bonds per particle, close packing
# relative slack on the closed bounds, so that values which went through a conversion and
# back (or sqrt3/3 typed for 1/sqrt3) are not rejected for a rounding error
_SLACK = 1e-12
_MU_I_TEXT = {2: "1/sqrt3", 3: "1/(2 sqrt2)"}
_MU_P_TEXT = {2: "1/sqrt3", 3: "1/sqrt2"}


@dataclass(frozen=True)
class RockProperties:
    """Rock properties the lattice reproduces (SI).

    E: Young's modulus (Pa); nu: Poisson's ratio; Tu, Cu: uniaxial tensile and compressive
    strengths (Pa, both positive); mu_i: coefficient of internal friction (Coulomb criterion,
    2013 eq. 28).  In 2D, E and nu are plane-strain constants (2013 eq. 14).
    """

    E: float
    nu: float
    Tu: float
    Cu: float
    mu_i: float


@dataclass(frozen=True)
class BondParameters:
    """The five coefficients of ``pair_style lattice/bond`` (SI).

    Kn, Ks: normal and shear spring stiffness; Xb: breaking displacement in tension (m);
    Fs0: shear resistance of an intact bond; mu_p: inter-particle friction coefficient.
    3D: Kn, Ks in N/m and Fs0 in N.  2D: per metre of thickness, Kn, Ks in N/m/m and Fs0 in
    N/m, used unchanged in LAMMPS (see the module docstring).
    """

    Kn: float
    Ks: float
    Xb: float
    Fs0: float
    mu_p: float

    def pair_coeff(self, i: int | str = "*", j: int | str = "*", bond: bool = True) -> str:
        """The LAMMPS line ``pair_coeff i j Kn Ks Xb Fs0 mu_p`` (17 significant digits).

        The command name is padded to 16 columns, like the other commands of the decks;
        ``bond=False`` appends the keyword ``bond no`` (contacts only, never bonded).
        """
        values = " ".join(f"{v:.17g}" for v in astuple(self))
        return f"pair_coeff      {i} {j} {values}" + ("" if bond else " bond no")


# ------------------------------------------------------------------------------------------------
# validation
# ------------------------------------------------------------------------------------------------

def _check_dim(dim: int) -> int:
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim!r} is out of range: use 2 or 3")
    return int(dim)


def _positive(name: str, value: float) -> float:
    value = float(value)
    if not (value > 0.0 and math.isfinite(value)):
        raise ValueError(f"{name} = {value} is out of range: need 0 < {name} < inf")
    return value


def _check_nu(nu: float, dim: int) -> float:
    nu = float(nu)
    nu_max = NU_MAX[dim]
    if 0.0 <= nu <= nu_max * (1.0 + _SLACK):
        return min(nu, nu_max)
    if nu > nu_max:
        why = ("Ks = E(1-4nu)/(sqrt3(1-2nu)(1+nu)) must be >= 0" if dim == 2 else
               "Ks = sqrt2(1-5nu)E d/(4(1+nu)(1-2nu)) must be >= 0")
    elif nu < 0.0:
        why = ("nu < 0 means Ks > Kn: the horizontal bonds stay compressed, which the "
               "Cu formula leaves out")
    else:
        why = "not a number"
    raise ValueError(f"nu = {nu} is out of range for a {dim}D lattice: need "
                     f"0 <= nu <= {nu_max:g} ({why})")


def _check_mu_i(mu_i: float, dim: int) -> float:
    mu_i = float(mu_i)
    mu_min = MU_I_MIN[dim]
    if mu_min * (1.0 - _SLACK) <= mu_i <= MU_I_MAX * (1.0 + 1e-9):
        return min(max(mu_i, mu_min), MU_I_MAX)
    raise ValueError(f"mu_i = {mu_i} is out of range for a {dim}D lattice: need "
                     f"{_MU_I_TEXT[dim]} = {mu_min:.6g} <= mu_i <= {MU_I_MAX:g} (the bond "
                     f"friction mu_p must be >= 0; above {MU_I_MAX:g}, a friction angle of "
                     f"89.4 degrees, Fs0 is lost to rounding)")


def _check_stiffness(Kn: float, Ks: float, dim: int) -> tuple[float, float]:
    Kn = _positive("Kn", Kn)
    Ks = float(Ks)
    if not 0.0 <= Ks <= Kn * (1.0 + _SLACK):
        raise ValueError(f"Ks = {Ks} is out of range for a {dim}D lattice: need "
                         f"0 <= Ks <= Kn = {Kn} (otherwise nu leaves 0 <= nu <= "
                         f"{NU_MAX[dim]:g})")
    return Kn, min(Ks, Kn)


def _check_mu_p(mu_p: float, dim: int) -> float:
    mu_p = float(mu_p)
    mu_max = MU_P_MAX[dim]
    if 0.0 <= mu_p < mu_max:
        return mu_p
    raise ValueError(f"mu_p = {mu_p} is out of range for a {dim}D lattice: need "
                     f"0 <= mu_p < {_MU_P_TEXT[dim]} = {mu_max:.6g} (Cu would be infinite or "
                     f"negative)")


def validate_rock(E: float, nu: float, Tu: float, Cu: float, mu_i: float, dim: int) -> None:
    """Raise ValueError naming the first rock property the lattice cannot represent."""
    dim = _check_dim(dim)
    for name, value in (("E", E), ("Tu", Tu), ("Cu", Cu)):
        _positive(name, value)
    _check_nu(nu, dim)
    _check_mu_i(mu_i, dim)


def validate_bond(Kn: float, Ks: float, Xb: float, Fs0: float, mu_p: float, dim: int) -> None:
    """Raise ValueError naming the first bond parameter outside the valid range."""
    dim = _check_dim(dim)
    _check_stiffness(Kn, Ks, dim)
    _positive("Xb", Xb)
    _positive("Fs0", Fs0)
    _check_mu_p(mu_p, dim)


def compressive_strength_caveat(nu: float, Tu: float, Cu: float, mu_i: float,
                                dim: int) -> str | None:
    """Why the papers' unit with these (valid) properties does not fail at Cu, or None.

    The Cu formulas (2013 eqs. 24-29, 2017 eqs. 9-14) let the inclined bonds slide once the
    horizontal bonds have opened at C_open.  If C_open > Cu and nu > 0, the intact horizontal
    bonds are in tension when the Cu load is reached and confine the unit.  With them intact,
    eq. 25 (2013) or eq. 10 (2017), with the horizontal force taken from the bond stretch
    (eq. 13a, eq. 2d), gives sliding at Cu / (1 - c), c = 2 nu I / (3 (1 - 2nu)) in 2D and
    3 nu I / (2 (1 - 2nu)) in 3D (I as in eq. B5; never for c >= 1); the unit fails at the
    lower of that and C_open.  If Ks = 0 (nu at its largest), the bonds never slide: the unit
    opens at C_open and collapses.
    """
    dim = _check_dim(dim)
    Tu, Cu = _positive("Tu", Tu), _positive("Cu", Cu)
    nu, mu_i = _check_nu(nu, dim), _check_mu_i(mu_i, dim)
    opening = c_open(Tu, nu, dim)
    if nu >= NU_MAX[dim] * (1.0 - _SLACK):
        return (f"nu = {nu:g} gives Ks = 0 in {dim}D: the bonds cannot fail in sliding, so the "
                f"lattice does not fail at Cu = {Cu:.6g} Pa in compression (its base bonds "
                f"open at C_open = {opening:.6g} Pa, then the unit collapses)")
    if nu == 0.0 or opening <= Cu:
        return None
    big_i = (math.sqrt(1.0 + mu_i * mu_i) + mu_i) ** 2
    c = (2.0 * nu * big_i / (3.0 * (1.0 - 2.0 * nu)) if dim == 2 else
         3.0 * nu * big_i / (2.0 * (1.0 - 2.0 * nu)))
    strength = min(opening, Cu / (1.0 - c)) if c < 1.0 else opening
    return (f"C_open = {opening:.6g} Pa exceeds Cu = {Cu:.6g} Pa in {dim}D: the horizontal "
            f"bonds are still intact at the Cu load and confine the unit, which fails at "
            f"{strength:.6g} Pa instead (the Cu formula assumes they opened first)")


# ------------------------------------------------------------------------------------------------
# conversions
# ------------------------------------------------------------------------------------------------

def rock_to_bond(E: float, nu: float, Tu: float, Cu: float, mu_i: float, d: float,
                 dim: int) -> BondParameters:
    """Bond parameters of a lattice of diameter-d particles with these rock properties.

    2D: Liu, Pollard & Shi 2013, eqs. B1-B5.  3D: Liu et al. 2017, eqs. B1-B5.
    Warns (UserWarning) when the lattice cannot reach Cu: see
    :func:`compressive_strength_caveat`.
    """
    validate_rock(E, nu, Tu, Cu, mu_i, dim)
    dim, d = _check_dim(dim), _positive("d", d)
    E, Tu, Cu = float(E), float(Tu), float(Cu)
    nu, mu_i = _check_nu(nu, dim), _check_mu_i(mu_i, dim)
    kn, ks, xb, fs0, mu_p = _closed_forms(_rock_to_bond, (E, nu, Tu, Cu, mu_i, d, dim),
                                          ("Kn", "Ks", "Xb", "Fs0", "mu_p"), ("Kn", "Xb", "Fs0"),
                                          "these properties and d")
    if not math.isfinite(ks):
        raise ValueError(f"Ks = {ks} follows from these properties and d: not finite")
    _warn_caveat(nu, Tu, Cu, mu_i, dim)
    return BondParameters(kn, ks, xb, fs0, mu_p)


def _closed_forms(formulas, args: tuple, names: tuple[str, ...], positive: tuple[str, ...],
                  source: str) -> tuple[float, ...]:
    """formulas(*args) for checked inputs; the results named in ``positive`` must be
    positive and finite (inputs spanning too many orders of magnitude over- or underflow)."""
    try:
        values = formulas(*args)
    except (ZeroDivisionError, OverflowError):
        values = (math.nan,) * len(names)
    for name, value in zip(names, values):
        if name in positive and not (value > 0.0 and math.isfinite(value)):
            raise ValueError(f"{name} = {value} follows from {source}, out of range: need "
                             f"0 < {name} < inf (the values over- or underflow)")
    return values


def _rock_to_bond(E: float, nu: float, Tu: float, Cu: float, mu_i: float, d: float,
                  dim: int) -> tuple[float, float, float, float, float]:
    """The closed forms of :func:`rock_to_bond`, for checked inputs."""
    big_i = (math.sqrt(1.0 + mu_i * mu_i) + mu_i) ** 2
    if dim == 2:
        kn = E / (SQ3 * (1.0 - 2.0 * nu) * (1.0 + nu))                          # B1
        ks = E * (1.0 - 4.0 * nu) / (SQ3 * (1.0 - 2.0 * nu) * (1.0 + nu))       # B2
        mu_p = (-3.0 * SQ3 + SQ3 * big_i) / (3.0 + 3.0 * big_i)                 # B5
    else:
        kn = SQ2 * E * d / (4.0 * (1.0 - 2.0 * nu))                             # B1
        ks = SQ2 * (1.0 - 5.0 * nu) * E * d / (4.0 * (1.0 + nu) * (1.0 - 2.0 * nu))  # B2
        mu_p = (-2.0 * SQ2 + SQ2 * big_i) / (2.0 + 2.0 * big_i)                 # B5
    # at the ends of the ranges the formulas give zero up to rounding
    ks = 0.0 if nu == NU_MAX[dim] else max(ks, 0.0)
    mu_p = 0.0 if mu_i == MU_I_MIN[dim] else max(mu_p, 0.0)
    if dim == 2:
        xb = (2.0 * kn + ks) / (2.0 * SQ3 * kn * (kn + ks)) * Tu * d              # B3
        fs0 = (0.25 - SQ3 / 4.0 * mu_p) * Cu * d                                # B4
    else:
        xb = (3.0 * kn + ks) / (6.0 * SQ2 * kn * (kn + ks)) * Tu * d * d         # B3
        fs0 = (1.0 - SQ2 * mu_p) / 6.0 * Cu * d * d                             # B4
    return kn, ks, xb, fs0, mu_p


def rock_to_bond_props(props: RockProperties, d: float, dim: int) -> BondParameters:
    """:func:`rock_to_bond` for a :class:`RockProperties`."""
    return rock_to_bond(props.E, props.nu, props.Tu, props.Cu, props.mu_i, d, dim)


def bond_to_rock(Kn: float, Ks: float, Xb: float, Fs0: float, mu_p: float, d: float,
                 dim: int) -> RockProperties:
    """Rock properties of a lattice of diameter-d particles with these bond parameters.

    2D: Liu, Pollard & Shi 2013, eqs. C1-C5 (= eqs. 17, 18, 20, 29, 30).
    3D: Liu et al. 2017, eqs. 6, 4, 7, 14, 15.
    """
    validate_bond(Kn, Ks, Xb, Fs0, mu_p, dim)
    dim, d = _check_dim(dim), _positive("d", d)
    kn, ks = _check_stiffness(Kn, Ks, dim)
    xb, fs0, mu_p = float(Xb), float(Fs0), float(mu_p)
    E, nu, Tu, Cu, mu_i = _closed_forms(_bond_to_rock, (kn, ks, xb, fs0, mu_p, d, dim),
                                        ("E", "nu", "Tu", "Cu", "mu_i"), ("E", "Tu", "Cu"),
                                        "Kn, Ks, Xb, Fs0, mu_p and d")
    _warn_caveat(nu, Tu, Cu, mu_i, dim)
    return RockProperties(E, nu, Tu, Cu, mu_i)


def _bond_to_rock(kn: float, ks: float, xb: float, fs0: float, mu_p: float, d: float,
                  dim: int) -> tuple[float, float, float, float, float]:
    """The closed forms of :func:`bond_to_rock`, for checked inputs."""
    if dim == 2:
        E = SQ3 * (kn + ks) * (5.0 * kn - ks) / (8.0 * kn)                     # C1
        nu = 0.25 * (1.0 - ks / kn)                                              # C2
        Tu = 2.0 * SQ3 * kn * (kn + ks) / (2.0 * kn + ks) * xb / d               # C3
        Cu = 4.0 / (1.0 - SQ3 * mu_p) * fs0 / d                                  # C4
        big_p = (3.0 + SQ3 * mu_p) / (1.0 - SQ3 * mu_p)                          # C5
    else:
        E = 6.0 * SQ2 * kn * (kn + ks) / (d * (5.0 * kn + ks))                   # eq. 6
        nu = (kn - ks) / (5.0 * kn + ks)                                         # eq. 4
        Tu = 6.0 * SQ2 * kn * (kn + ks) / (3.0 * kn + ks) * xb / (d * d)         # eq. 7
        Cu = 6.0 / (1.0 - SQ2 * mu_p) * fs0 / (d * d)                            # eq. 14
        big_p = (2.0 + SQ2 * mu_p) / (1.0 - SQ2 * mu_p)                          # eq. 15
    mu_i = (big_p - 1.0) / (2.0 * math.sqrt(big_p))
    return E, nu, Tu, Cu, mu_i


def _warn_caveat(nu: float, Tu: float, Cu: float, mu_i: float, dim: int) -> None:
    caveat = compressive_strength_caveat(nu, Tu, Cu, mu_i, dim)
    if caveat is not None:
        warnings.warn(caveat, UserWarning, stacklevel=3)


# ------------------------------------------------------------------------------------------------
# other closed-form results
# ------------------------------------------------------------------------------------------------

def c_open(Tu: float, nu: float, dim: int) -> float:
    """Compressive stress at which the horizontal bonds open (micro-cracks), in Pa.

    2D: C_open = Tu (0.75/nu - 1) (2013 eq. 23).  3D: C_open = Tu (2 - nu) / (3 nu), which is
    2017 eq. 8 divided by eq. 7 with Ks/Kn from eq. 4.  Infinite for nu = 0 (Ks = Kn: the
    lattice does not dilate laterally).
    """
    dim = _check_dim(dim)
    Tu = _positive("Tu", Tu)
    nu = _check_nu(nu, dim)
    if nu == 0.0:
        return math.inf
    return Tu * (0.75 / nu - 1.0) if dim == 2 else Tu * (2.0 - nu) / (3.0 * nu)


def shear_modulus_2d(Kn: float, Ks: float) -> float:
    """Plane-strain shear modulus G = sqrt3/4 (Kn + Ks) of the 2D lattice (2013 eq. 15), Pa."""
    kn, ks = _check_stiffness(Kn, Ks, 2)
    return SQ3 / 4.0 * (kn + ks)


def lame_lambda_2d(Kn: float, Ks: float) -> float:
    """Lame's constant lambda = sqrt3/4 (Kn - Ks) of the 2D lattice, Pa.

    2013 eq. 16 prints sqrt(3/4) (Kn - Ks); only sqrt3/4 gives eqs. 17 and 18 from eq. 14.
    """
    kn, ks = _check_stiffness(Kn, Ks, 2)
    return SQ3 / 4.0 * (kn - ks)


def tensile_failure_strain_2d(Kn: float, Ks: float, Xb: float, d: float) -> float:
    """Axial strain of the 2D lattice at Tu: (3Kn + Ks)/(2Kn + Ks) Xb/d (2013 eq. 21)."""
    kn, ks = _check_stiffness(Kn, Ks, 2)
    xb, d = _positive("Xb", Xb), _positive("d", d)
    return (3.0 * kn + ks) / (2.0 * kn + ks) * xb / d


def lattice_mass(rho: float, d: float, dim: int) -> float:
    """Particle mass from the lattice's overall density rho (kg/m^3).

    2D: rho sqrt3 d^2 / 2 in kg per metre of thickness (2013 eq. 33);
    3D: rho sqrt2 d^3 / 2 in kg (2017 eq. 27).
    """
    dim = _check_dim(dim)
    rho, d = _positive("rho", rho), _positive("d", d)
    return rho * SQ3 * d * d / 2.0 if dim == 2 else rho * SQ2 * d ** 3 / 2.0


def paper_damping_2d(m: float, Kn: float, n_across: float) -> float:
    """Viscous damping eta = sqrt(8 m Kn) / N of the 2013 tests (eq. 34), N s/m.

    N is the number of particles across the (square) lattice.
    """
    m, Kn = _positive("m", m), _positive("Kn", Kn)
    n_across = float(n_across)
    if not (n_across >= 1.0 and math.isfinite(n_across)):
        raise ValueError(f"n_across = {n_across} is out of range: need 1 <= n_across < inf")
    return math.sqrt(8.0 * m * Kn) / n_across


def paper_damping_3d(m: float, Kn: float, d: float, volume: float) -> float:
    """Viscous damping eta = d / V^(1/3) sqrt(8 m Kn) of the 2017 tests (eq. 28), N s/m."""
    m, Kn = _positive("m", m), _positive("Kn", Kn)
    d, volume = _positive("d", d), _positive("volume", volume)
    return d / volume ** (1.0 / 3.0) * math.sqrt(8.0 * m * Kn)


def critical_time_step(m: float, Kn: float, Ks: float, dim: int) -> float:
    """A time step below which velocity Verlet is stable for the undamped lattice, s.

    dt = sqrt(2 m / (z k)), z = 6 (2D) or 12 (3D) bonds per particle, k = max(Kn, Ks).
    Why: the elastic energy of the linearised lattice is sum over bonds of
    u^T K_b u <= k |u|^2 (u = x_i - x_j, K_b = Kn nn^T + Ks (1 - nn^T)), and
    |x_i - x_j|^2 <= 2 |x_i|^2 + 2 |x_j|^2, so the largest eigenvalue of the stiffness
    matrix is at most 2 z k, omega_max^2 <= 2 z k / m, and Verlet needs dt < 2 / omega_max.
    It is 0.71-0.87 (2D) and 0.58-0.82 (3D, fcc or hcp) of the exact limit of the periodic
    lattice (0 <= Ks <= Kn).  Stiffer walls or strong damping lower the limit: keep a margin (the
    papers run at 0.11 (2D) and 0.05 (3D) of sqrt(m/Kn)).
    """
    dim = _check_dim(dim)
    m, Kn = _positive("m", m), _positive("Kn", Kn)
    Ks = float(Ks)
    if not (Ks >= 0.0 and math.isfinite(Ks)):
        raise ValueError(f"Ks = {Ks} is out of range: need 0 <= Ks < inf")
    return math.sqrt(2.0 * m / (_COORDINATION[dim] * max(Kn, Ks)))
