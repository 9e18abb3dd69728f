"""The checks against the 2013 and 2017 papers, on the results file docs/validation.md is made
from, and a rerun of its small blocks showing that today's code still gives that file's numbers.

The checks themselves (which number of ours meets which paper result, and the tolerance with its
reason: the papers' scatter, their load step or printed digits, never what we happen to get) are
defined once, in ``bonded_lattice.validation.checks``, and printed on the page ("Checks against
the papers").  The results file holds runs up to the papers' largest blocks (2D 16,611 particles,
3D 37,681 elements, hours of runs), made by ``bonded-lattice validate --slow``; this suite cannot
repeat them, so it asserts the checks on the file and reruns the blocks that take seconds with
the same options, which must reproduce the file's numbers: a change to the physics that moves a
result fails here until the file (and with it the page and the checks) is made again.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from bonded_lattice.validation.checks import CHECKS, evaluate
from bonded_lattice.validation.results import load_results, section_data
from bonded_lattice.validation.runner import Validation, rock_for

RESULTS = Path(__file__).resolve().parents[2] / "docs" / "validation.json"


@pytest.fixture(scope="module")
def results() -> dict:
    return load_results(RESULTS)


@pytest.fixture(scope="module")
def evaluated(results) -> dict:
    return {row["check"].name: row for row in evaluate(results)}


@pytest.mark.parametrize("name", [c.name for c in CHECKS])
def test_paper_result(evaluated, name):
    row = evaluated[name]
    check = row["check"]
    assert row["ours"] is not None, f"{name}: the results file has no data for this check"
    if check.open:
        # a known, not yet explained difference: it must still be one; once it is within its
        # tolerance, record the explanation and drop 'open' in validation/checks.py
        assert not row["within"], (name, row["ours"], row["paper"])
    else:
        assert row["within"], (name, row["ours"], row["paper"], check.tolerance, check.why)


# Reruns: (section, where the run sits in the section's data, folder, dim, test, n, options),
# the same folder names and options as the sections' own runs (validation/blocks.py, ladder.py,
# platens.py), at sizes that take seconds.
def _series(dim: int, n: int, key: str):
    return lambda data: next(r for r in data[str(dim)] if r["n"] == n)[key]


def _ladder(dim: int, n: int, test: str, rung: str):
    return lambda data: next(r for r in data[str(dim)]
                             if r["n"] == n and r["test"] == test)["rungs"][rung]


def _unit(dim: int, test: str):
    return lambda data: data[str(dim)][test]


RERUNS = [
    ("units", _unit(2, "tension"), "2d/unit_tension", 2, "tension", 2, {"schedule": "stepwise"}),
    ("units", _unit(3, "compression"), "3d/unit_compression", 3, "compression", 2,
     {"schedule": "stepwise"}),
    ("series", _series(2, 4, "elastic"), "2d/n4_elastic", 2, "elastic", 4, {}),
    ("series", _series(2, 8, "tension"), "2d/n8_tension", 2, "tension", 8, {}),
    ("series", _series(2, 8, "compression"), "2d/n8_compression", 2, "compression", 8, {}),
    ("series", _series(3, 4, "elastic"), "3d/n4_elastic", 3, "elastic", 4, {}),
    ("series", _series(3, 4, "tension"), "3d/n4_tension", 3, "tension", 4, {}),
    ("series", _series(3, 4, "compression_slow"), "3d/n4_compression_c1000", 3, "compression",
     4, {"crossings": 1000.0}),
    ("like_for_like", _ladder(2, 4, "compression", "paper"), "2d/paper_n4_compression", 2,
     "compression", 4, {"schedule": "stepwise"}),
]


@pytest.mark.parametrize("section,where,folder,dim,test,n,options", RERUNS,
                         ids=[r[2] for r in RERUNS])
def test_todays_code_gives_the_results_files_numbers(tmp_path, results, section, where, folder,
                                                      dim, test, n, options):
    stored = where(section_data(results, section))
    run = Validation(tmp_path, np_=1, progress=False).run(folder, rock_for(dim), dim, test, n,
                                                          **options)
    assert run["particles"] == stored["particles"]
    for key, value in stored["relative_error"].items():
        if value is None:
            continue
        # the file's runs were made on 2 ranks, these on 1: the same results to round-off
        # (docs/design.md); a strength read at the peak after the first bonds broke can carry
        # that round-off through the breaking, so 1e-4 of the value, a thousandth of the
        # smallest difference the page discusses (0.1 points of a strength)
        assert run["relative_error"][key] == pytest.approx(value, rel=1e-4, abs=1e-7), key
