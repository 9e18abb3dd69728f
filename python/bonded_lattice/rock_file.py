"""The user's own rocks, read from a TOML or JSON file (``bonded-lattice ... --rock-file``).

A rock file holds one table per rock, named by its key; each table has exactly the keys of a
library rock (:class:`bonded_lattice.rocks.Rock`), in the library's SI units::

    [my-quartz]       # the library's quartz under another name (inputs/rocks/my-quartz.toml)
    E = 90e9          # Young's modulus, Pa
    nu = 0.16         # Poisson's ratio
    Tu = 25e6         # uniaxial tensile strength, Pa
    Cu = 252e6        # uniaxial compressive strength, Pa
    mu_i = 1.0        # coefficient of internal friction
    rho = 2650.0      # density, kg/m^3
    source = "Liu, Pollard & Shi (2013) J. Geophys. Res. 118, 71-82, Table 1 (...)"

(JSON: ``{"my-quartz": {"E": 90e9, ...}}``.)  The entries are checked as strictly as the
library's: a missing key (``source`` included) or an unknown one is an error naming it, a
value that is not a number (``source``: not a string) is an error, and the values go through
:class:`~bonded_lattice.rocks.Rock`'s own checks (the ValueError names the rock, the value and
its valid range).  A rock may not share its name with a library rock (names are compared
without case): the file is refused rather than one of the two silently winning.  A value the
user does not have is left out (in TOML, commented out with a note), and loading says which
value is missing and that it must be supplied; there is no placeholder number.

TOML needs Python >= 3.11 (``tomllib``) or the ``tomli`` package; JSON works everywhere.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from .rocks import ROCKS, Rock, get_rock

__all__ = ["ROCK_KEYS", "ROCK_UNITS", "choose_rock", "read_rock_file", "rock_from_entry",
           "rock_summary"]

ROCK_KEYS = ("E", "nu", "Tu", "Cu", "mu_i", "rho", "source")
"""The keys of every rock entry, all required (those of :class:`~bonded_lattice.rocks.Rock`)."""

ROCK_UNITS = {"E": "Pa", "nu": "", "Tu": "Pa", "Cu": "Pa", "mu_i": "", "rho": "kg/m^3"}
"""The unit of each number of an entry ('' for the dimensionless ones)."""

_MEANING = {"E": "Young's modulus", "nu": "Poisson's ratio",
            "Tu": "uniaxial tensile strength", "Cu": "uniaxial compressive strength",
            "mu_i": "coefficient of internal friction", "rho": "density",
            "source": "the reference of every value"}

_FORMATS = {".toml": "TOML", ".json": "JSON"}


def _describe(key: str) -> str:
    """``key`` with its meaning and unit, for messages."""
    unit = ROCK_UNITS.get(key, "")
    return f"{key} ({_MEANING[key]}{', ' + unit if unit else ''})"


def _load_toml(text: str, path: Path) -> Any:
    try:
        import tomllib  # Python >= 3.11
    except ImportError:  # Python 3.10
        try:
            import tomli as tomllib  # type: ignore[no-redef]
        except ImportError:
            raise ValueError(f"{path}: reading a TOML rock file needs Python >= 3.11 or the "
                             f"tomli package (pip install tomli); a JSON rock file works on "
                             f"any Python") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML: {exc}") from exc


def _no_duplicate_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """json's object hook: a key twice in one object is an error (as it is in TOML)."""
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise ValueError(f"key {key!r} appears twice in one object")
        out[key] = value
    return out


def _load_json(text: str, path: Path) -> Any:
    try:
        return json.loads(text, object_pairs_hook=_no_duplicate_keys)
    except ValueError as exc:  # json.JSONDecodeError is a ValueError
        raise ValueError(f"{path}: not valid JSON: {exc}") from exc


def rock_from_entry(name: str, entry: Any, where: str = "the rock file") -> Rock:
    """The :class:`~bonded_lattice.rocks.Rock` of one entry (a mapping of :data:`ROCK_KEYS`).

    ``where`` names the entry's file in the messages.  Raises ValueError for a missing,
    unknown or mistyped key and for a value out of :class:`Rock`'s range.
    """
    if not isinstance(entry, dict):
        raise ValueError(f"rock {name!r} in {where} is a {type(entry).__name__}: need a table "
                         f"of {', '.join(ROCK_KEYS)}")
    unknown = sorted(set(entry) - set(ROCK_KEYS))
    if unknown:
        missing = [key for key in ROCK_KEYS if key not in entry]
        raise ValueError(f"rock {name!r} in {where} has unknown key(s) {', '.join(unknown)}: "
                         f"the keys are {', '.join(ROCK_KEYS)} (case-sensitive)"
                         + (f"; missing: {', '.join(missing)}" if missing else ""))
    for key in ROCK_KEYS:
        if key not in entry:
            raise ValueError(f"rock {name!r} in {where} has no {_describe(key)}: every rock "
                             f"needs {', '.join(ROCK_KEYS)}; supply the missing value (a "
                             f"measured one, cited in source)")
    for key in ROCK_KEYS[:-1]:
        value = entry[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ValueError(f"rock {name!r} in {where}: {key} = {value!r} is not a number "
                             f"(a {type(value).__name__}): need {_describe(key)} as a number")
    if not isinstance(entry["source"], str):
        raise ValueError(f"rock {name!r} in {where}: source = {entry['source']!r} is not a "
                         f"string: need the reference of every value as a string")
    values = {key: float(entry[key]) for key in ROCK_KEYS[:-1]}
    try:
        return Rock(name, source=entry["source"], **values)
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from exc


def read_rock_file(path: str | Path) -> dict[str, Rock]:
    """The rocks of a TOML (``*.toml``) or JSON (``*.json``) rock file, by name as written.

    Every entry is checked (:func:`rock_from_entry`); a name that a library rock has
    (:data:`bonded_lattice.rocks.ROCKS`, without case), two names that differ only in case,
    and a file with no rock are errors (ValueError naming them).  The library is not changed:
    pass the rocks to :func:`bonded_lattice.rocks.register_rock` to add them to it.
    """
    path = Path(path)
    kind = _FORMATS.get(path.suffix.lower())
    if kind is None:
        raise ValueError(f"rock file {path}: suffix {path.suffix!r} is not one of "
                         f"{', '.join(_FORMATS)} (TOML or JSON)")
    text = path.read_text(encoding="utf-8")
    data = _load_toml(text, path) if kind == "TOML" else _load_json(text, path)
    if not isinstance(data, dict) or not data:
        raise ValueError(f"{path}: need one or more rocks, each a table named by the rock "
                         f"(keys {', '.join(ROCK_KEYS)}); found "
                         f"{'nothing' if not data else type(data).__name__}")
    rocks: dict[str, Rock] = {}
    seen: dict[str, str] = {}
    for name, entry in data.items():
        key = name.strip().lower()
        if not key:
            raise ValueError(f"{path}: a rock's name is empty")
        if key in ROCKS:
            raise ValueError(f"rock {name!r} in {path} has the name of the library's rock "
                             f"{ROCKS[key].name!r}: rename it (library rocks: "
                             f"{', '.join(sorted(r.name for r in ROCKS.values()))})")
        if key in seen:
            raise ValueError(f"{path}: rocks {seen[key]!r} and {name!r} differ only in case "
                             f"(rock names are case-insensitive)")
        seen[key] = name
        rocks[name] = rock_from_entry(name, entry, str(path))
    return rocks


def choose_rock(name: str | None, rock_file: str | Path | None = None,
                default: str = "quartz") -> Rock:
    """The rock the command line names: ``name`` among the library's and the rock file's
    rocks (case-insensitive); without ``name``, the file's rock if it has only one, else the
    library's ``default``.  The file is read and checked whenever it is given."""
    file_rocks = read_rock_file(rock_file) if rock_file is not None else {}
    if name is None:
        if len(file_rocks) == 1:
            return next(iter(file_rocks.values()))
        if file_rocks:
            raise ValueError(f"{rock_file} has {len(file_rocks)} rocks: choose one with --rock "
                             f"({', '.join(file_rocks)})")
        return get_rock(default)
    for rock_name, rock in file_rocks.items():
        if rock_name.strip().lower() == name.strip().lower():
            return rock
    try:
        return get_rock(name)
    except KeyError:
        known = sorted(r.name for r in ROCKS.values()) + list(file_rocks)
        raise KeyError(f"unknown rock {name!r}: known rocks are {', '.join(known)}"
                       + ("" if rock_file is None else f" (library and {rock_file})")) from None


def rock_summary(rock: Rock) -> list[str]:
    """Lines describing a rock for ``bonded-lattice rocks``: values with units, the lattice
    dimensions that reproduce it (or why none does) and the source."""
    def g(x: float) -> str:
        return f"{x:.6g}"

    lines = [f"  E = {g(rock.E / 1e9)} GPa, nu = {g(rock.nu)}, Tu = {g(rock.Tu / 1e6)} MPa, "
             f"Cu = {g(rock.Cu / 1e6)} MPa, mu_i = {g(rock.mu_i)}, rho = {g(rock.rho)} kg/m^3"]
    dims = rock.dims
    why = "; ".join(f"not {d}D: {rock.why_not(d)}" for d in (2, 3) if d not in dims)
    lines.append(f"  lattice: {', '.join(f'{d}D' for d in dims) or 'none'}"
                 + (f" ({why})" if why else ""))
    lines.append(f"  source: {rock.source}")
    return lines
