"""The internal friction from confined tests, and the calibration of one block size."""

from __future__ import annotations

import json

from ..analysis import coulomb_envelope
from ..calibration import calibrate
from .doc import DocContext, pct
from .runner import Validation, rock_for
from .section import Section

__all__ = ["CALIBRATION", "ENVELOPE"]

CONFINED = {"dim": 2, "n": 15, "pressures": [0.0, 10e6, 20e6]}
CALIBRATION_SIZE = {2: 15, 3: 6}


def run_envelope(v: Validation) -> dict:
    c = CONFINED
    runs = [v.run(f"{c['dim']}d/confined_{p / 1e6:g}MPa", rock_for(c["dim"]), c["dim"],
                  "confined", c["n"], confining=p) for p in c["pressures"]]
    return {"dim": c["dim"], "n": c["n"], "runs": runs}


def doc_envelope(data: dict, ctx: DocContext) -> list[str]:
    runs = data["runs"]
    s3 = [r["confining_Pa"] for r in runs]
    s1 = [r["measured"]["sigma1"] for r in runs]
    cu, mu_i = coulomb_envelope(s3, s1)
    rock = rock_for(data["dim"])
    L = ["## Internal friction from confined tests", "",
         f"Biaxial tests of the 2D block (N = {data['n']}, {runs[0]['particles']} particles) "
         "with smooth side walls holding the confining stress (`fix lattice/wall ... servo`); "
         "the papers never measured mu_i.", "",
         "| sigma3 (MPa) | peak sigma1 (MPa) | Coulomb target Cu + I sigma3 (MPa) |",
         "|---|---|---|"]
    for r in runs:
        L.append(f"| {r['confining_Pa'] / 1e6:g} | {r['measured']['sigma1'] / 1e6:.1f} | "
                 f"{r['target']['sigma1'] / 1e6:.1f} |")
    L += ["", f"Fitted envelope: Cu = {cu / 1e6:.1f} MPa ({pct(cu / rock.Cu - 1, 1)} of the "
          f"rock's: the multi-unit deficit of the unconfined test), mu_i = {mu_i:.3f} against "
          f"the input {rock.mu_i:g} ({pct(mu_i / rock.mu_i - 1, 1)})."]
    return L


def run_calibration(v: Validation) -> dict:
    data = {}
    for dim in (2, 3):
        folder = v.folder(f"{dim}d/calibration")
        stored = folder / "calibration.json"
        if v.reuse and stored.exists():
            data[str(dim)] = json.loads(stored.read_text())
            continue
        if v.progress:
            print(f"validate: {dim}d/calibration", flush=True)
        cal = calibrate(rock_for(dim), dim, CALIBRATION_SIZE[dim], folder, np_=v.np_)
        data[str(dim)] = json.loads(cal.to_json())
    return data


def doc_calibration(data: dict, ctx: DocContext) -> list[str]:
    L = ["## Calibration for one block size", "",
         "`bonded-lattice calibrate` corrects the formulas' inputs until the measured E, nu, "
         "Tu and Cu of the user's block match the rock (1% tolerance):", "",
         "| dim | block | runs | E | nu | Tu | Cu | input corrections |",
         "|---|---|---|---|---|---|---|---|"]
    for dim, cal in data.items():
        e, c = cal["errors"], cal["corrections"]
        L.append(f"| {dim}D | {cal['particles']} particles | {len(cal['steps'])} | "
                 f"{pct(e['E'])} | {pct(e['nu'])} | {pct(e['Tu'])} | {pct(e['Cu'])} | "
                 f"E x {c['E']:.4f}, nu {c['nu']:+.4f}, Tu x {c['Tu']:.4f}, "
                 f"Cu x {c['Cu']:.4f} |")
    return L


ENVELOPE = Section("envelope", run_envelope, doc_envelope)
CALIBRATION = Section("calibration", run_calibration, doc_calibration)
