"""Rock properties <-> bond parameters of the close-packed lattice (closed form).

2D hexagonal lattice: Liu, Pollard & Shi (2013), Appendix B/C; 3D close-packed
lattice: Liu et al. (2017), Appendix B.  Formulas as checked in REFERENCE.md
(the 2017 paper's Table 1 misprints Ks).  In 2D the lattice is one particle
thick and everything is per unit thickness: Kn, Ks in N/m per metre, Fs0 in
N per metre, exactly the numbers LAMMPS uses in a 2D simulation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

SQ2, SQ3 = math.sqrt(2.0), math.sqrt(3.0)


@dataclass(frozen=True)
class RockProperties:
    """E (Pa), nu, Tu and Cu (Pa, positive), mu_i (coefficient of internal friction)."""

    E: float
    nu: float
    Tu: float
    Cu: float
    mu_i: float


@dataclass(frozen=True)
class BondParameters:
    """Kn, Ks (N/m), Xb (m), Fs0 (N), mu_p of pair_style lattice/bond."""

    Kn: float
    Ks: float
    Xb: float
    Fs0: float
    mu_p: float

    def pair_coeff(self, i: str | int = "*", j: str | int = "*") -> str:
        """The LAMMPS line ``pair_coeff i j Kn Ks Xb Fs0 mu_p``."""
        values = " ".join(f"{v:.17g}" for v in (self.Kn, self.Ks, self.Xb, self.Fs0, self.mu_p))
        return f"pair_coeff      {i} {j} {values}"


def _check_dim(dim: int) -> None:
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim} is out of range: use 2 or 3")


def _positive(name: str, value: float) -> None:
    if not value > 0:
        raise ValueError(f"{name} = {value} is out of range: need {name} > 0")


def _nu_max(dim: int) -> float:
    return 0.25 if dim == 2 else 0.2


def _mu_p_max(dim: int) -> float:
    return 1 / SQ3 if dim == 2 else 1 / SQ2


def validate_rock(E: float, nu: float, Tu: float, Cu: float, mu_i: float, dim: int) -> None:
    """Raise ValueError naming the first property outside what the lattice can represent."""
    _check_dim(dim)
    for name, value in (("E", E), ("Tu", Tu), ("Cu", Cu)):
        _positive(name, value)
    nu_max = _nu_max(dim)
    if not 0.0 <= nu <= nu_max:
        raise ValueError(f"nu = {nu} is out of range for a {dim}D lattice: need 0 <= nu <= {nu_max} "
                         f"(the shear stiffness Ks must not be negative)")
    # mu_p >= 0 needs I >= 3 (2D) or I >= 2 (3D), I = (sqrt(1 + mu_i^2) + mu_i)^2
    i_min = 3.0 if dim == 2 else 2.0
    mu_i_min = (i_min - 1.0) / (2.0 * math.sqrt(i_min))
    if not mu_i >= mu_i_min - 1e-15:
        raise ValueError(f"mu_i = {mu_i} is out of range for a {dim}D lattice: need mu_i >= "
                         f"{mu_i_min:.6g} (the bond friction mu_p must not be negative)")


def validate_bond(Kn: float, Ks: float, Xb: float, Fs0: float, mu_p: float, dim: int) -> None:
    """Raise ValueError naming the first bond parameter outside the valid range."""
    _check_dim(dim)
    for name, value in (("Kn", Kn), ("Xb", Xb), ("Fs0", Fs0)):
        _positive(name, value)
    if not 0.0 <= Ks <= Kn:
        raise ValueError(f"Ks = {Ks} is out of range: need 0 <= Ks <= Kn = {Kn} "
                         f"(Poisson's ratio would leave 0 <= nu <= {_nu_max(dim)})")
    mu_max = _mu_p_max(dim)
    if not 0.0 <= mu_p < mu_max:
        raise ValueError(f"mu_p = {mu_p} is out of range for a {dim}D lattice: need 0 <= mu_p < "
                         f"{mu_max:.6g} (Cu would be infinite or negative)")


def rock_to_bond(E: float, nu: float, Tu: float, Cu: float, mu_i: float, d: float,
                 dim: int) -> BondParameters:
    """Bond parameters of a lattice of diameter-d particles with these rock properties."""
    validate_rock(E, nu, Tu, Cu, mu_i, dim)
    _positive("d", d)
    big_i = (math.sqrt(1.0 + mu_i**2) + mu_i) ** 2
    if dim == 2:
        kn = E / (SQ3 * (1 - 2 * nu) * (1 + nu))
        ks = E * (1 - 4 * nu) / (SQ3 * (1 - 2 * nu) * (1 + nu))
        xb = (2 * kn + ks) / (2 * SQ3 * kn * (kn + ks)) * Tu * d
        mu_p = (-3 * SQ3 + SQ3 * big_i) / (3 + 3 * big_i)
        fs0 = (0.25 - SQ3 / 4 * mu_p) * Cu * d
    else:
        kn = SQ2 * E * d / (4 * (1 - 2 * nu))
        ks = SQ2 * (1 - 5 * nu) * E * d / (4 * (1 + nu) * (1 - 2 * nu))
        xb = (3 * kn + ks) / (6 * SQ2 * kn * (kn + ks)) * Tu * d**2
        mu_p = (-2 * SQ2 + SQ2 * big_i) / (2 + 2 * big_i)
        fs0 = (1 - SQ2 * mu_p) / 6 * Cu * d**2
    return BondParameters(kn, max(ks, 0.0), xb, fs0, max(mu_p, 0.0))


def bond_to_rock(Kn: float, Ks: float, Xb: float, Fs0: float, mu_p: float, d: float,
                 dim: int) -> RockProperties:
    """Rock properties of a lattice with these bond parameters."""
    validate_bond(Kn, Ks, Xb, Fs0, mu_p, dim)
    _positive("d", d)
    if dim == 2:
        E = SQ3 * (Kn + Ks) * (5 * Kn - Ks) / (8 * Kn)
        nu = (1 - Ks / Kn) / 4
        Tu = 2 * SQ3 * Kn * (Kn + Ks) / (2 * Kn + Ks) * Xb / d
        Cu = 4 / (1 - SQ3 * mu_p) * Fs0 / d
        P = (3 + SQ3 * mu_p) / (1 - SQ3 * mu_p)
    else:
        E = 6 * SQ2 * Kn * (Kn + Ks) / (d * (5 * Kn + Ks))
        nu = (Kn - Ks) / (5 * Kn + Ks)
        Tu = 6 * SQ2 * Kn * (Kn + Ks) / (3 * Kn + Ks) * Xb / d**2
        Cu = 6 / (1 - SQ2 * mu_p) * Fs0 / d**2
        P = (2 + SQ2 * mu_p) / (1 - SQ2 * mu_p)
    mu_i = (P - 1) / (2 * math.sqrt(P))
    return RockProperties(E, nu, Tu, Cu, mu_i)


def lattice_mass(rho: float, d: float, dim: int) -> float:
    """Particle mass from the lattice's overall density (2D per unit thickness)."""
    _check_dim(dim)
    _positive("rho", rho)
    _positive("d", d)
    return rho * SQ3 * d**2 / 2 if dim == 2 else rho * SQ2 * d**3 / 2


def paper_damping_2d(m: float, Kn: float, n_across: int) -> float:
    """Liu 2013 eq. 34: eta = sqrt(8 m Kn) / N."""
    _positive("m", m)
    _positive("Kn", Kn)
    _positive("n_across", n_across)
    return math.sqrt(8 * m * Kn) / n_across


def paper_damping_3d(m: float, Kn: float, d: float, volume: float) -> float:
    """Liu 2017: eta = d / V^(1/3) * sqrt(8 m Kn)."""
    for name, value in (("m", m), ("Kn", Kn), ("d", d), ("volume", volume)):
        _positive(name, value)
    return d / volume ** (1.0 / 3.0) * math.sqrt(8 * m * Kn)
