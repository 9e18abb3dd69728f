"""The tests' materials: the papers' quartz, taken from the package's conversion.

The coefficients are :func:`bonded_lattice.conversion.rock_to_bond` of the library's quartz
(:func:`bonded_lattice.rocks.get_rock`) for particles of diameter ``D`` = 1 mm, rounded to
5 significant digits: the precision the tests, the data files in tests/data and the
force-style YAML files were written with (docs/theory.md, "Worked values").  The rounded
values are exactly the floats the tests typed before (6.5874e10, ...), so every assertion
sees the same numbers.

``WORKED`` is the reference those values are checked against: the worked values of
docs/theory.md, typed once, here, for the tests of the conversion itself.
"""

from __future__ import annotations

from dataclasses import astuple, replace

from bonded_lattice.conversion import BondParameters, lattice_mass, rock_to_bond_props
from bonded_lattice.rocks import Rock, get_rock

__all__ = ["D", "QUARTZ_ROCK", "QUARTZ", "QUARTZ_2D", "QUARTZ_3D", "QUARTZ_MASS", "QUARTZITE_3D", "QUARTZITE_3D_BOND", "WEAK_SHEAR",
           "WORKED", "coeffs", "exact_quartz", "number", "rounded"]

D = 1.0e-3
"""Particle diameter of the tests' lattices (m)."""

QUARTZ_ROCK: Rock = get_rock("quartz")
"""The papers' quartz (E 90 GPa, nu 0.16, Tu 25 MPa, Cu 252 MPa, mu_i 1, rho 2650 kg/m^3)."""

DIGITS = 5
"""Significant digits of the tests' coefficients."""


def number(value: float, digits: int = DIGITS) -> float:
    """``value`` rounded to ``digits`` significant digits."""
    return float(f"{value:.{digits - 1}e}")


def rounded(bond: BondParameters, digits: int = DIGITS) -> BondParameters:
    """The five coefficients of ``bond``, each rounded to ``digits`` significant digits."""
    return BondParameters(*(number(v, digits) for v in astuple(bond)))


def exact_quartz(dim: int, d: float = D) -> BondParameters:
    """The conversion's quartz coefficients for diameter-d particles, unrounded."""
    return rock_to_bond_props(QUARTZ_ROCK.properties, d, dim)


QUARTZ: dict[int, BondParameters] = {dim: rounded(exact_quartz(dim)) for dim in (2, 3)}
"""Quartz, d = 1 mm, 5 significant digits: 2D per metre of thickness (N/m/m, m, N/m),
3D in N/m, m, N."""

QUARTZ_MASS: dict[int, float] = {dim: number(lattice_mass(QUARTZ_ROCK.rho, D, dim), 4)
                                 for dim in (2, 3)}
"""Particle mass of the quartz lattice (2013 eq. 33, 2017 eq. 27), 4 significant digits:
2.295e-3 kg per metre of thickness (2D), 1.874e-6 kg (3D)."""


def _text(value: float | str) -> str:
    """A coefficient as the decks write it: ``6.5874e10``, ``18.452``, ``0.23915``; a string
    (a LAMMPS variable such as ``${ks}``) as it is."""
    if isinstance(value, str):
        return value
    if value == 0.0 or 1e-2 <= abs(value) < 1e3:
        return f"{value:.{DIGITS}g}"
    mantissa, exponent = f"{value:.{DIGITS - 1}e}".split("e")
    if "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    return f"{mantissa}e{int(exponent)}"


def coeffs(bond: BondParameters, **changes: float | str) -> str:
    """``Kn Ks Xb Fs0 mu_p`` of ``bond`` for a ``pair_coeff`` line, with ``changes`` (for
    example ``Fs0=1.1e4``, or ``Ks="${ks}"``) replacing single coefficients."""
    return " ".join(_text(v) for v in astuple(replace(bond, **changes)))


QUARTZ_2D = coeffs(QUARTZ[2])
"""``6.5874e10 2.3715e10 1.9011e-7 3.6905e4 0.23915``: quartz in 2D, for pair_coeff."""
QUARTZ_3D = coeffs(QUARTZ[3])
"""``4.6794e7 8.0679e6 1.7037e-7 18.452 0.39645``: quartz in 3D, for pair_coeff."""
QUARTZITE_3D_BOND = rounded(rock_to_bond_props(get_rock("quartzite").properties, D, 3))
"""The 2017 paper's quartzite in 3D, d = 1 mm, 5 significant digits (the same properties as
quartz, so the same coefficients)."""
QUARTZITE_3D = coeffs(QUARTZITE_3D_BOND)
"""The 2017 paper's quartzite in 3D, for pair_coeff."""

WEAK_SHEAR: dict[int, BondParameters] = {
    dim: replace(QUARTZ[dim], Fs0=number(0.3 * QUARTZ[dim].Fs0, 2)) for dim in (2, 3)}
"""Quartz with 0.3 of its shear strength, to two digits (Fs0 = 1.1e4 N/m in 2D, 5.5 N in
3D), so that the bonds of a shaken or fracturing block fail in shear as well as in tension."""

# docs/theory.md "Worked values: the papers' quartz" (5 significant digits; the 3D Ks is
# 8.0679e6: the 2017 paper's Table 1 misprints 8.068e5).  The reference of the conversion
# tests (tests/unit/test_conversion.py, tests/validation/test_single_unit.py,
# tests/integration/test_workflow.py), so it is typed, not computed.
WORKED = {
    2: {"Kn": 6.5874e10, "Ks": 2.3715e10, "Xb": 1.9011e-7, "Fs0": 3.6905e4, "mu_p": 0.23915,
        "mass": 2.295e-3},
    3: {"Kn": 4.6794e7, "Ks": 8.0679e6, "Xb": 1.7037e-7, "Fs0": 18.452, "mu_p": 0.39645,
        "mass": 1.874e-6},
}
