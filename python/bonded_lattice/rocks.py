"""A small library of rocks: laboratory properties, density and where they come from.

Each value is quoted from the source named in the entry; where a source gives no value for
one property (density, often the friction of the same specimen), the entry says what was used.
The lattice cannot represent every rock: Poisson's ratio must lie in [0, 1/4] (2D) or [0, 1/5]
(3D), mu_i must not be too small, and the papers' unit must reach Cu (see
:mod:`bonded_lattice.conversion`).  ``Rock.dims`` lists the dimensions in which all five
properties are reproduced and ``Rock.why_not(dim)`` says why a dimension is missing.  Many
real rocks (basalt here; many marbles and sandstones, with nu > 0.2) have no supported
dimension; such entries are kept so that the reason is one call away.

Add your own rocks with :func:`register_rock`, or from a TOML or JSON file with
:func:`bonded_lattice.rock_file.read_rock_file` (the command line's ``--rock-file``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType

from .conversion import RockProperties, compressive_strength_caveat, validate_rock

__all__ = ["ROCKS", "Rock", "get_rock", "list_rocks", "register_rock"]


@dataclass(frozen=True)
class Rock:
    """Mechanical properties (SI) of a rock, its density and where they come from.

    E: Young's modulus (Pa); nu: Poisson's ratio; Tu, Cu: uniaxial tensile and compressive
    strengths (Pa, positive); mu_i: coefficient of internal friction; rho: density (kg/m^3);
    source: the reference of each value.  Construction checks that the values describe an
    isotropic elastic solid (-1 < nu < 1/2); whether the lattice can represent the rock is
    ``dims``.
    """

    name: str
    E: float
    nu: float
    Tu: float
    Cu: float
    mu_i: float
    rho: float
    source: str

    def __post_init__(self) -> None:
        for name in ("name", "source"):
            value = getattr(self, name)
            if not (isinstance(value, str) and value.strip()):
                raise ValueError(f"{name} = {value!r} is out of range: need a non-empty string")
        for name in ("E", "Tu", "Cu", "rho"):
            value = float(getattr(self, name))
            if not (value > 0.0 and math.isfinite(value)):
                raise ValueError(f"{name} = {value} is out of range for rock {self.name!r}: "
                                 f"need 0 < {name} < inf")
        if not -1.0 < float(self.nu) < 0.5:
            raise ValueError(f"nu = {self.nu} is out of range for rock {self.name!r}: need "
                             f"-1 < nu < 0.5 (an isotropic elastic solid)")
        if not (float(self.mu_i) >= 0.0 and math.isfinite(float(self.mu_i))):
            raise ValueError(f"mu_i = {self.mu_i} is out of range for rock {self.name!r}: "
                             f"need 0 <= mu_i < inf")

    @property
    def properties(self) -> RockProperties:
        """E, nu, Tu, Cu, mu_i as the conversion functions take them."""
        return RockProperties(self.E, self.nu, self.Tu, self.Cu, self.mu_i)

    def why_not(self, dim: int) -> str | None:
        """None if a dim-D lattice reproduces all five properties, else the reason."""
        try:
            validate_rock(self.E, self.nu, self.Tu, self.Cu, self.mu_i, dim)
        except ValueError as exc:
            return str(exc)
        return compressive_strength_caveat(self.nu, self.Tu, self.Cu, self.mu_i, dim)

    @property
    def dims(self) -> tuple[int, ...]:
        """The lattice dimensions (2, 3) that reproduce this rock."""
        return tuple(dim for dim in (2, 3) if self.why_not(dim) is None)


_ROCKS: dict[str, Rock] = {}
ROCKS = MappingProxyType(_ROCKS)
"""Read-only view of the library, keyed by lower-case name; add rocks with register_rock."""


def register_rock(rock: Rock, replace: bool = False) -> Rock:
    """Add a rock to the library (names are case-insensitive); returns it.

    Refuses a name already in the library unless ``replace=True``.  The rock's values are
    checked when the Rock is built; a rock the lattice cannot represent (``rock.dims == ()``)
    is accepted, and ``rock.why_not(dim)`` tells why.
    """
    if not isinstance(rock, Rock):
        raise TypeError(f"register_rock needs a Rock, got {type(rock).__name__}")
    key = rock.name.strip().lower()
    if key in _ROCKS and not replace:
        raise ValueError(f"rock {rock.name!r} is already in the library: pass replace=True "
                         f"to replace it")
    _ROCKS[key] = rock
    return rock


def get_rock(name: str) -> Rock:
    """The library's rock of this name (case-insensitive)."""
    try:
        return _ROCKS[name.strip().lower()]
    except KeyError:
        raise KeyError(f"unknown rock {name!r}: known rocks are "
                       f"{', '.join(list_rocks())}") from None


def list_rocks(dim: int | None = None) -> list[str]:
    """Names of the library's rocks, sorted; with ``dim``, only those a dim-D lattice fits."""
    return sorted(rock.name for rock in _ROCKS.values() if dim is None or dim in rock.dims)


# the papers' rock (both papers use the same values; the 2013 paper calls it quartz)
register_rock(Rock(
    "quartz", E=90e9, nu=0.16, Tu=25e6, Cu=252e6, mu_i=1.0, rho=2650.0,
    source="Liu, Pollard & Shi (2013) J. Geophys. Res. 118, 71-82, Table 1 (after Pollard & "
           "Fletcher 2005, Fundamentals of Structural Geology, pp. 321, 343, 361); rho: sec. 5.1"))
register_rock(Rock(
    "quartzite", E=90e9, nu=0.16, Tu=25e6, Cu=252e6, mu_i=1.0, rho=2650.0,
    source="Liu et al. (2017) Comput. Geosci. 103, 12-20, Table 1 (after Pollard & Fletcher "
           "2005, pp. 321, 343, 361); rho: sec. 5.1"))

# a real rock the lattice cannot represent (nu = 0.25 gives Ks = 0 in 2D and exceeds the 3D
# limit 0.2): kept so that why_not() explains the limitation
register_rock(Rock(
    "basalt", E=78e9, nu=0.25, Tu=14.5e6, Cu=266e6,
    # Coulomb: Cu = 2 S0 (sqrt(1 + mu_i^2) + mu_i) with the cohesion S0 = 66 MPa
    mu_i=((266.0 / 132.0) ** 2 - 1.0) / (2.0 * 266.0 / 132.0),
    rho=2900.0,
    source="intact basalt, mean laboratory values of Schultz (1995) Rock Mech. Rock Eng. 28, "
           "1-15 (E 78 +- 19 GPa, nu 0.25 +- 0.05, Tu 14.5 +- 3.3 MPa, Cu 266 +- 98 MPa, "
           "cohesion S0 66 MPa); mu_i from Cu and S0 (Coulomb); rho: typical basalt, not from "
           "Schultz"))
