"""The validation's results file and the page written from it (bonded_lattice.validation).

docs/validation.md must be what `bonded-lattice validate --doc-only` writes from
docs/validation.json: a page edited by hand, or a results file that no longer matches its page,
fails here.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from bonded_lattice.validation import SECTIONS, section_names, validate
from bonded_lattice.validation.results import (load_results, save_results, section_data,
                                                store_section)

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "validation.md"
RESULTS = ROOT / "docs" / "validation.json"


def test_the_page_is_written_from_the_results_file(tmp_path: Path) -> None:
    doc = tmp_path / "docs" / "validation.md"
    doc.parent.mkdir()
    validate(doc=doc, results=RESULTS, doc_only=True)
    assert doc.read_text() == DOC.read_text()
    # every figure the page shows was drawn from the results file
    for line in doc.read_text().splitlines():
        for part in line.split("](img/")[1:]:
            assert (doc.parent / "img" / part.split(")")[0]).exists()


def test_every_section_of_the_results_file_has_its_provenance() -> None:
    results = load_results(RESULTS)
    assert set(results["sections"]) <= set(section_names())
    for entry in results["sections"].values():
        assert entry["commit"] and entry["date"] and entry["machine"]
        assert entry["ranks"] >= 1 and entry["run_seconds"] >= 0


def test_a_section_run_again_replaces_only_its_own_entry(tmp_path: Path) -> None:
    path = tmp_path / "r.json"
    results = load_results(path)
    assert results == {"format": 1, "sections": {}}
    store_section(results, "units", {"a": 1}, tmp_path, 2, False, 3.0)
    store_section(results, "series", {"b": 2}, tmp_path, 2, True, 4.0)
    save_results(results, path)
    again = load_results(path)
    store_section(again, "units", {"a": 5}, tmp_path, 1, False, 1.0)
    assert section_data(again, "units") == {"a": 5}
    assert section_data(again, "series") == {"b": 2}
    assert section_data(again, "energy") is None


def test_a_file_of_another_format_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "r.json"
    path.write_text(json.dumps({"format": 99, "sections": {}}))
    with pytest.raises(ValueError, match="format 1"):
        load_results(path)


def test_an_unknown_section_is_named_with_the_known_ones(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="unknown validation section.*nonsense.*known are "
                       + SECTIONS[0].name):
        validate(doc=tmp_path / "v.md", sections=["nonsense"], doc_only=True)
