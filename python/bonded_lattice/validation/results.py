"""The results file of the validation: every number behind every table and figure.

``bonded-lattice validate`` stores what each section measured in one JSON file (by default
``docs/validation.json``, kept in the repository) and writes docs/validation.md from that
file alone, so the document can be checked against its data and rewritten without a run.
A section run again replaces its own entry only; each entry carries the commit, date,
machine and ranks it was made with::

    {"format": 1,
     "sections": {"series": {"commit": "...", "date": "2026-12-03", "machine": "...",
                             "ranks": 2, "slow": true, "run_seconds": 1234.5,
                             "data": {...}}, ...}}
"""

from __future__ import annotations

import json
import time
from pathlib import Path

from ..provenance import git_commit, machine

__all__ = ["RESULTS_FORMAT", "load_results", "save_results", "section_data", "store_section"]

RESULTS_FORMAT = 1


def load_results(path: str | Path) -> dict:
    """The results file at ``path``, or an empty one if there is none; a ValueError if the
    file is not a results file of this format."""
    path = Path(path)
    if not path.exists():
        return {"format": RESULTS_FORMAT, "sections": {}}
    results = json.loads(path.read_text())
    if not isinstance(results, dict) or results.get("format") != RESULTS_FORMAT:
        raise ValueError(f"{path} is not a validation results file of format "
                         f"{RESULTS_FORMAT} (its 'format' is "
                         f"{results.get('format') if isinstance(results, dict) else None!r})")
    return results


def store_section(results: dict, name: str, data: dict, root: Path, ranks: int, slow: bool,
                  run_seconds: float, reuse: bool = False) -> None:
    """Put one section's ``data`` into ``results`` with where and when it was made (``reuse``:
    runs whose folders held a summary were read, not run again)."""
    results["sections"][name] = {
        "commit": git_commit(root, mark_changes=True), "date": time.strftime("%Y-%m-%d"),
        "machine": machine(), "ranks": ranks, "slow": slow, "reuse": reuse,
        "run_seconds": round(run_seconds, 1), "data": data}


def section_data(results: dict, name: str) -> dict | None:
    """The data of section ``name``, or None if the results file has none."""
    entry = results["sections"].get(name)
    return None if entry is None else entry["data"]


def save_results(results: dict, path: str | Path) -> None:
    """Write ``results`` (sections in a fixed order, one level of indentation)."""
    Path(path).write_text(json.dumps(results, indent=1, sort_keys=True) + "\n")
