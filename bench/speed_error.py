"""Speed against error: how many time steps the tests need for a given accuracy.

One command runs the whole study and writes a Markdown report with PNG plots:

    python bench/speed_error.py                 # full study, about 30-35 min on one core
    python bench/speed_error.py --quick         # small blocks, a few minutes
    python bench/speed_error.py --reuse         # rewrite the report from the cached runs

1. Single-contact tests T1-T4 of Li et al. (2018), set up exactly as in
   tests/validation/test_single_contact.py (whose decks and analytic solutions this script
   imports): error against the time step over eight values a factor 2 apart, the
   fitted convergence order, and the largest stable time step of the contact
   spring found by bisection, against Verlet's limit dt_c = 2 sqrt(m/k).
2. The 2D quartz lattice: E and nu (elastic test) and Tu, Cu (strength tests)
   against the number of time steps, over the constant schedule's loading rate
   (--crossings) and damping (--damping), its time step, and the papers' stepwise
   schedule's relaxation steps and step size; the papers' schedule is the
   reference point; Pareto fronts of error against time steps; the largest stable
   time step of the lattice.
3. From the fronts: the cheapest constant-schedule setting (crossings, damping)
   that keeps all four quantities at the papers' accuracy, checked on a block of
   another size; written into the report as the recommended defaults.
4. The same for the 3D quartzite lattice (elastic n_y = 10, strength n_y = 6, check
   n_y = 10 against the papers' 3D stepwise schedule): the 3D defaults.  --no-3d skips it.

Every simulation runs on one MPI rank, one at a time.  The runs are cached as JSON
in --out (default validation-runs/speed-error, git-ignored); --reuse keeps the
cached ones.  This script is the command-line driver; the analysis (runs, fits,
plots, report) is the package's ``bonded_lattice.speed_error``, whose pure
functions (Pareto front, convergence order, Verlet's discrete solution,
bisection, the tolerance test, the recommendation rule) are tested by
tests/unit/test_speed_error.py.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import shlex
import sys
import time
from pathlib import Path
from types import ModuleType

from bonded_lattice.speed_error import (FULL, FULL_3D, QUICK, QUICK_3D, run_contact,
                                        run_lattice, write_doc)

ROOT = Path(__file__).resolve().parent.parent


def contact_module() -> ModuleType:
    """tests/.../test_single_contact.py as a module: its decks, constants and solutions."""
    path = next(ROOT.glob("tests/**/test_single_contact.py"))
    spec = importlib.util.spec_from_file_location("_single_contact_tests", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


def _json_ready(lat: dict) -> dict:
    """A run_lattice result with its grid's (crossings, damping) keys as strings."""
    return ({k: v for k, v in lat.items() if k != "grid"} |
            {"grid": {f"{c:g},{f:g}": e for (c, f), e in lat["grid"].items()}})


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="small blocks and grids, a few minutes (writes into --out unless "
                        "--doc is given)")
    parser.add_argument("--out", default=None,
                        help="cache folder (default validation-runs/speed-error, "
                        "validation-runs/speed-error-quick with --quick)")
    parser.add_argument("--doc", default=None,
                        help="report to write (default docs/speed_error.md; with --quick "
                        "<out>/speed_error.md); plots go to img/ beside it")
    parser.add_argument("--reuse", action="store_true", help="keep cached runs")
    parser.add_argument("--no-3d", action="store_true", help="skip the 3D part (part 4)")
    args = parser.parse_args(argv)
    settings = QUICK if args.quick else FULL
    settings_3d = None if args.no_3d else (QUICK_3D if args.quick else FULL_3D)
    out = Path(args.out) if args.out else ROOT / "validation-runs" / (
        "speed-error-quick" if args.quick else "speed-error")
    doc = Path(args.doc) if args.doc else (out / "speed_error.md" if args.quick
                                           else ROOT / "docs" / "speed_error.md")
    out.mkdir(parents=True, exist_ok=True)
    cmd = shlex.join(["python", *([sys.argv[0]] if argv is None else ["bench/speed_error.py"]),
                      *(sys.argv[1:] if argv is None else argv)])
    start = time.perf_counter()
    contact = run_contact(settings, out, args.reuse, contact_module)
    lat = run_lattice(settings, out, args.reuse)
    lat3 = run_lattice(settings_3d, out, args.reuse) if settings_3d else None
    (out / "study.json").write_text(json.dumps(
        {"2": _json_ready(lat)} | ({"3": _json_ready(lat3)} if lat3 else {}), indent=1,
        default=str))
    write_doc(doc, cmd, settings, args.quick, contact, lat, time.perf_counter() - start, ROOT,
              settings_3d, lat3)
    print(f"wrote {doc} and its plots in {doc.parent / 'img'}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
