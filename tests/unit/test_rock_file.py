"""The user's own rocks (bonded_lattice.rock_file, ``--rock-file``, ``bonded-lattice rocks``).

A good file holds the library's quartz under another name, so its bond parameters must equal
the library quartz's exactly (the same floats through the same formulas: compared with ==).
Each bad file breaks one rule, and its ValueError must name what is wrong.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from bonded_lattice.cli import main
from bonded_lattice.conversion import rock_to_bond
from bonded_lattice.rock_file import ROCK_KEYS, choose_rock, read_rock_file
from bonded_lattice.rocks import ROCKS, get_rock

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "inputs" / "rocks"
QUARTZ = get_rock("quartz")
GOOD = {key: getattr(QUARTZ, key) for key in ROCK_KEYS}


def _toml_value(value: object) -> str:
    # JSON's spelling of strings and booleans is TOML's too; floats as Python writes them
    return json.dumps(value) if isinstance(value, (str, bool)) else repr(value)


def write_toml(path: Path, rocks: dict[str, dict]) -> Path:
    lines = []
    for name, entry in rocks.items():
        lines.append(f'["{name}"]')
        lines += [f"{key} = {_toml_value(value)}" for key, value in entry.items()]
    path.write_text("\n".join(lines) + "\n")
    return path


def write_json(path: Path, rocks: dict[str, dict]) -> Path:
    path.write_text(json.dumps(rocks))
    return path


@pytest.mark.parametrize("suffix", ["toml", "json"])
def test_good_file_converts_like_the_library_rock(tmp_path: Path, suffix: str) -> None:
    write = write_toml if suffix == "toml" else write_json
    path = write(tmp_path / f"rocks.{suffix}", {"my-quartz": GOOD})
    rock = read_rock_file(path)["my-quartz"]
    assert rock.name == "my-quartz" and rock.source == QUARTZ.source
    for dim in (2, 3):
        assert (rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, 1e-3, dim)
                == rock_to_bond(QUARTZ.E, QUARTZ.nu, QUARTZ.Tu, QUARTZ.Cu, QUARTZ.mu_i, 1e-3,
                                dim))
    assert rock.rho == QUARTZ.rho and rock.dims == (2, 3)


@pytest.mark.parametrize("name", ["my-quartz.toml", "my-quartz.json"])
def test_example_files_equal_the_library_quartz(name: str) -> None:
    rock = read_rock_file(EXAMPLES / name)["my-quartz"]
    assert [getattr(rock, k) for k in ROCK_KEYS] == [getattr(QUARTZ, k) for k in ROCK_KEYS]


def test_granite_example_fails_naming_the_missing_friction(tmp_path: Path) -> None:
    with pytest.raises(ValueError) as info:
        read_rock_file(EXAMPLES / "lac-du-bonnet-granite.toml")
    message = str(info.value)
    assert "lac-du-bonnet-granite" in message and "has no mu_i" in message
    assert "supply the missing value" in message
    # the other five values are present: with a friction supplied the file loads, and
    # its numbers are the cited ones
    text = (EXAMPLES / "lac-du-bonnet-granite.toml").read_text()
    assert "\nmu_i" not in text  # the key is only in a comment
    completed = tmp_path / "granite.toml"
    completed.write_text(text.replace("# mu_i = ...", "mu_i = 1.0"))
    granite = read_rock_file(completed)
    rock = granite["lac-du-bonnet-granite"]
    assert (rock.E, rock.nu, rock.Tu, rock.Cu, rock.rho) == (66.5e9, 0.31, 6.9e6, 200e6, 2638.0)
    assert rock.dims == ()  # nu = 0.31 > 1/4 (2D) and > 1/5 (3D)


BAD = {
    "missing source": ({k: v for k, v in GOOD.items() if k != "source"}, ["has no source"]),
    "missing value": ({k: v for k, v in GOOD.items() if k != "Cu"}, ["has no Cu"]),
    "nu out of range": ({**GOOD, "nu": 0.6}, ["nu = 0.6", "need -1 < nu < 0.5", "'bad'"]),
    "negative E": ({**GOOD, "E": -1e9}, ["E = -1000000000.0", "need 0 < E < inf", "'bad'"]),
    "unknown key": ({**GOOD, "mu": 0.5}, ["unknown key(s) mu"]),
    "misspelt key": ({**{k: v for k, v in GOOD.items() if k != "mu_i"}, "mu_I": 1.0},
                     ["unknown key(s) mu_I", "missing: mu_i"]),
    "wrong type": ({**GOOD, "E": "90e9"}, ["E = '90e9' is not a number", "Young's modulus, Pa"]),
    "boolean": ({**GOOD, "mu_i": True}, ["mu_i = True is not a number (a bool)"]),
    "source not a string": ({**GOOD, "source": 3}, ["source = 3 is not a string"]),
    "empty source": ({**GOOD, "source": " "}, ["source = ' '", "need a non-empty string"]),
}


@pytest.mark.parametrize("suffix", ["toml", "json"])
@pytest.mark.parametrize("case", list(BAD))
def test_bad_entry_is_refused_with_its_reason(tmp_path: Path, suffix: str, case: str) -> None:
    entry, words = BAD[case]
    write = write_toml if suffix == "toml" else write_json
    path = write(tmp_path / f"rocks.{suffix}", {"bad": entry})
    with pytest.raises(ValueError) as info:
        read_rock_file(path)
    for word in words:
        assert word in str(info.value), (case, str(info.value))


@pytest.mark.parametrize("name", ["quartz", "Quartzite"])
def test_name_of_a_library_rock_is_refused(tmp_path: Path, name: str) -> None:
    path = write_json(tmp_path / "rocks.json", {name: GOOD})
    with pytest.raises(ValueError, match="has the name of the library's rock"):
        read_rock_file(path)
    assert ROCKS["quartz"] is QUARTZ  # the library is untouched


def test_names_differing_in_case_are_refused(tmp_path: Path) -> None:
    path = write_json(tmp_path / "rocks.json", {"Granite": GOOD, "granite": GOOD})
    with pytest.raises(ValueError, match="differ only in case"):
        read_rock_file(path)


@pytest.mark.parametrize("name, text, words", [
    ("rocks.toml", '[a]\nE = 90e9\nnu = = 0.16\n', "not valid TOML"),
    ("rocks.toml", '[a]\nE = 1\n[a]\nE = 2\n', "not valid TOML"),
    ("rocks.json", '{"a": {"E": 90e9,}}', "not valid JSON"),
    ("rocks.json", '{"a": {"E": 1, "E": 2}}', "key 'E' appears twice"),
    ("rocks.json", '[]', "need one or more rocks"),
    ("rocks.json", '{"a": 3}', "rock 'a' in"),
    ("rocks.yaml", 'a: 1', "is not one of .toml, .json"),
])
def test_malformed_file_is_refused(tmp_path: Path, name: str, text: str, words: str) -> None:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(".", r"\.")):
        read_rock_file(path)


def test_choose_rock(tmp_path: Path) -> None:
    one = write_json(tmp_path / "one.json", {"mine": GOOD})
    two = write_json(tmp_path / "two.json", {"a": GOOD, "b": GOOD})
    assert choose_rock(None, None) is QUARTZ                   # the default
    assert choose_rock(None, one).name == "mine"               # the file's only rock
    assert choose_rock("MINE", one).name == "mine"             # names without case
    assert choose_rock("basalt", one) is get_rock("basalt")   # the library's still
    with pytest.raises(ValueError, match="has 2 rocks: choose one with --rock"):
        choose_rock(None, two)
    with pytest.raises(KeyError, match="unknown rock 'c'"):
        choose_rock("c", two)


def test_cli_rocks_lists_library_and_file(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rocks", "--rock-file", str(EXAMPLES / "my-quartz.json")]) == 0
    out = capsys.readouterr().out
    for rock in ROCKS.values():
        assert f"{rock.name} (library)" in out and f"source: {rock.source}" in out
    assert f"my-quartz ({EXAMPLES / 'my-quartz.json'})" in out
    assert out.count(f"source: {QUARTZ.source}") == 2  # quartz and my-quartz
    assert "E = 90 GPa, nu = 0.16, Tu = 25 MPa, Cu = 252 MPa, mu_i = 1, rho = 2650 kg/m^3" in out


def test_cli_convert_with_rock_file(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["convert", "--rock", "quartz", "--dim", "2"]) == 0
    library = capsys.readouterr().out.splitlines()[-1]
    assert main(["convert", "--rock-file", str(EXAMPLES / "my-quartz.toml"), "--dim", "2"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == library  # the same pair_coeff line
    assert main(["convert", "--rock-file",
                 str(EXAMPLES / "lac-du-bonnet-granite.toml")]) == 2
    assert "has no mu_i" in capsys.readouterr().err


def test_toml_without_tomllib_or_tomli_says_so(tmp_path: Path,
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    # Python 3.10 without tomli: both imports fail (None in sys.modules makes import raise
    # ImportError); a TOML file is refused with the advice, a JSON file still loads
    monkeypatch.setitem(sys.modules, "tomllib", None)
    monkeypatch.setitem(sys.modules, "tomli", None)
    with pytest.raises(ValueError, match="needs Python >= 3.11 or the tomli package"):
        read_rock_file(EXAMPLES / "my-quartz.toml")
    assert read_rock_file(EXAMPLES / "my-quartz.json")["my-quartz"].E == QUARTZ.E
