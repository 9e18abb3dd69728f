"""Where a block's tensile deficit comes from: Tu of the tension test (the end layers held
and pulled apart) against Tu of a periodic cell in uniaxial tension (``test="periodic"``: no
ends, no free faces, the lateral faces at zero stress), at the papers' sizes.

The papers do not say how they pulled their blocks; the periodic cell is the limit of grips that
do not concentrate stress, the held end layers one that does.
"""

from __future__ import annotations

import numpy as np

from .doc import DocContext, paper_pct, pct
from .runner import Validation, rock_for
from .section import Section

__all__ = ["GRIPS"]

SIZES = {2: [8, 15, 30], 3: [6, 12]}


def run_grips(v: Validation) -> dict:
    data = {}
    for dim in (2, 3):
        rock, rows = rock_for(dim), []
        for n in SIZES[dim]:
            rows.append({"n": n,
                         "periodic": v.run(f"{dim}d/grips_n{n}_periodic", rock, dim, "periodic",
                                           n),
                         "held": v.run(f"{dim}d/n{n}_tension", rock, dim, "tension", n)})
        data[str(dim)] = rows
    return data


def doc_grips(data: dict, ctx: DocContext) -> list[str]:
    L = ["## Where the tensile deficit comes from: grips and free faces", "",
         "Tu of the tension test (the end layers held and pulled apart, constant loading at the "
         "papers' damping) against Tu of a periodic cell pulled uniaxially with its lateral "
         "faces at zero stress: no ends and no free faces, so no grip and no boundary layer.  "
         "The section 'Anisotropy' locates the tension blocks' damage next to the held ends.",
         "",
         "| dim | size | particles, block / cell | held end layers | periodic cell |",
         "|---|---|---|---|---|"]
    for dim in ("2", "3"):
        for r in data[dim]:
            L.append(f"| {dim}D | {'N' if dim == '2' else 'n_y'} = {r['n']} | "
                     f"{r['held']['particles']} / {r['periodic']['particles']} | "
                     f"{pct(r['held']['relative_error']['Tu'])} | "
                     f"{pct(r['periodic']['relative_error']['Tu'])} |")
    for dim in ("2", "3"):
        held = float(np.mean([r["held"]["relative_error"]["Tu"] for r in data[dim]]))
        cell = float(np.mean([r["periodic"]["relative_error"]["Tu"] for r in data[dim]]))
        L += ["", f"{dim}D, mean over these sizes: held end layers {pct(held)}, periodic cell "
              f"{pct(cell)}; the paper's multi-unit mean {paper_pct(f'{dim}d.multi.Tu')}."]
    return L


GRIPS = Section("grips", run_grips, doc_grips)
