"""A small library of rocks with their mechanical properties and sources.

Only the papers' rock is built in so far; every value here is quoted from
the source named beside it.  Add your own with :func:`register_rock`.
"""

from __future__ import annotations

from dataclasses import dataclass

from .conversion import RockProperties, validate_rock


@dataclass(frozen=True)
class Rock:
    """Mechanical properties (SI) of a rock, its density and where they come from."""

    name: str
    E: float      # Young's modulus (Pa)
    nu: float     # Poisson's ratio
    Tu: float     # uniaxial tensile strength (Pa)
    Cu: float     # uniaxial compressive strength (Pa)
    mu_i: float   # coefficient of internal friction
    rho: float    # density (kg/m^3)
    source: str

    @property
    def properties(self) -> RockProperties:
        return RockProperties(self.E, self.nu, self.Tu, self.Cu, self.mu_i)


_ROCKS: dict[str, Rock] = {}


def register_rock(rock: Rock, replace: bool = False) -> None:
    """Add a rock to the library; its properties must suit a 2D lattice."""
    key = rock.name.lower()
    if key in _ROCKS and not replace:
        raise ValueError(f"rock {rock.name!r} is already in the library: pass replace=True")
    validate_rock(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, 2)
    if not rock.rho > 0:
        raise ValueError(f"rho = {rock.rho} is out of range: need rho > 0")
    _ROCKS[key] = rock


def get_rock(name: str) -> Rock:
    """A rock of the library by (case-insensitive) name."""
    try:
        return _ROCKS[name.lower()]
    except KeyError:
        raise KeyError(f"unknown rock {name!r}: known rocks are {', '.join(list_rocks())}") from None


def list_rocks() -> list[str]:
    return sorted(rock.name for rock in _ROCKS.values())


register_rock(Rock("quartz", E=90e9, nu=0.16, Tu=25e6, Cu=252e6, mu_i=1.0, rho=2650.0,
                   source="Liu, Pollard & Shi 2013, Table 1 (after Pollard & Fletcher 2005)"))
register_rock(Rock("quartzite", E=90e9, nu=0.16, Tu=25e6, Cu=252e6, mu_i=1.0, rho=2650.0,
                   source="Liu et al. 2017, Table 1 (Pollard & Fletcher 2005, pp. 321, 343, 361)"))
