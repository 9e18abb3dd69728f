"""Reproduce the numerical tests of Liu et al. (2013, 2017): ``bonded-lattice validate``.

The validation is a list of sections (:data:`SECTIONS`, :mod:`.sections`), each a set of
runs and the part of docs/validation.md made from them.  :func:`validate` runs the chosen
sections, stores every number they measured in the results file (``docs/validation.json``,
:mod:`.results`) and writes docs/validation.md from that file alone (:mod:`.doc`);
``doc_only`` rewrites the page from the results file without running anything.

Modules: :mod:`.runner` (where runs go, compact summaries), :mod:`.papers` (the papers'
numbers and where they state them), :mod:`.geometry` (the two stress areas), and one module
per group of sections.
"""

from __future__ import annotations

import time
from pathlib import Path

from .doc import write_doc
from .results import load_results, save_results, store_section
from .runner import Validation, rock_for
from .sections import SECTIONS, section_names

__all__ = ["SECTIONS", "Validation", "rock_for", "section_names", "validate"]


def validate(out: str | Path = "validation-runs", doc: str | Path = "docs/validation.md",
             np_: int = 2, slow: bool = False, reuse: bool = False, progress: bool = True,
             sections: list[str] | None = None, results: str | Path | None = None,
             doc_only: bool = False) -> Path:
    """Run ``sections`` (all by default; those marked slow only with ``slow``), store their
    data in ``results`` (default: ``doc`` with the suffix .json) and write ``doc`` from it.

    doc_only: run nothing, rewrite ``doc`` from ``results``.  A ValueError names unknown
    sections and the known ones.
    """
    doc = Path(doc)
    results_path = Path(results) if results is not None else doc.with_suffix(".json")
    known = section_names()
    chosen = known if sections is None else list(sections)
    unknown = [s for s in chosen if s not in known]
    if unknown:
        raise ValueError(f"unknown validation section(s) {', '.join(unknown)}: known are "
                         f"{', '.join(known)}")
    data = load_results(results_path)
    if not doc_only:
        v = Validation(Path(out), np_=np_, slow=slow, reuse=reuse, progress=progress)
        root = Path(__file__).resolve().parents[3]
        for section in SECTIONS:
            if section.name not in chosen or (section.slow and not slow):
                continue
            start = time.perf_counter()
            section_result = section.run(v)
            store_section(data, section.name, section_result, root, np_, slow,
                          _run_seconds(section_result), reuse)
            save_results(data, results_path)
            if progress:
                print(f"validate: section {section.name} done in "
                      f"{time.perf_counter() - start:.0f} s", flush=True)
    write_doc(data, doc, SECTIONS)
    return doc


def _run_seconds(node) -> float:
    """Sum of the runs' wall times in a section's data (each run once, even if listed in
    two places)."""
    seen: dict[int, float] = {}

    def walk(x) -> None:
        if isinstance(x, dict):
            if "wall_time_s" in x and isinstance(x["wall_time_s"], (int, float)):
                seen[id(x)] = x["wall_time_s"]
            for k, y in x.items():
                if k != "wall_time_s":
                    walk(y)
        elif isinstance(x, list):
            for y in x:
                walk(y)
    walk(node)
    return sum(seen.values())
