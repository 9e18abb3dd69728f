"""E and nu against the strain magnitude, in compression and in tension, for the papers'
block sizes (Liu 2013, paras. 45-47 and Fig. 6 a/b; Liu 2017, section 5.2 and Fig. 4 a/b).

Each point is one elastic test (unbreakable bonds) to the strain magnitude ``s``, pressed
between the platens (compression) or pulled by its end layers (tension,
``elastic_load="tension"``).  E and nu are the secants at the strain ``s`` itself, as the
papers evaluate them (Liu 2013, para. 47: the unit's E and nu "when the vertical strain is
-1e-3"): :func:`secant_moduli` fits stress and lateral strain against the axial strain with
quadratics over the elastic test's window and evaluates ``sigma / s`` and ``-lateral / s`` of
the fits at ``s``.  The fits' constant terms take up the offset that the platens' constant
speed and the damping add to the stress (about 0.3% of it at 100 crossings), which a secant
read straight off a thermo row would carry.
"""

from __future__ import annotations

import numpy as np

from ..analysis import ELASTIC_WINDOW, plane_strain_from_in_plane
from ..io import read_thermo
from ..plotting import pyplot, save_png
from .doc import DocContext, paper_pct, pct
from .papers import PAPER
from .runner import Validation, rock_for
from .section import Section

__all__ = ["ELASTIC_STRAIN", "LOADS", "SIZES", "STRAINS", "secant_moduli"]

STRAINS = [1e-6, 1e-5, 1e-4, 1e-3, 2e-3, 3e-3]
SIZES = {2: [2, 4, 8, 15, 30], 3: [2, 4, 6]}     # 2D: N particles across; 3D: n_y
LOADS = ("compression", "tension")
# elastic-wave crossings of the block during the loading.  A single unit is one row high: 100
# crossings are about 1200 time steps, and in tension its base particles slide sideways with
# no damping (the end layers are moved by fix move, outside the damped integrator), so their
# ringing stays in the lateral strain.  Measured on the 2D unit in tension at 1e-3: the secant
# nu is off the exact quasi-static path by 0.018 percentage points at 1e4 crossings and by
# 0.0001 at 3e4 and 1e5 (1e5 crossings: 1.2e6 time steps of 3 particles, a few seconds).
CROSSINGS = {"unit": 1e5, "block": 100.0}


def secant_moduli(thermo: dict, strain: float, dim: int,
                  window: tuple[float, float] = ELASTIC_WINDOW) -> tuple[float, float]:
    """E and nu as secants at the axial strain ``strain`` (signed, tension positive) of an
    elastic test's thermo table (columns v_strain, v_stress, v_gauge).

    Stress and gauge lateral strain are fitted with quadratics in the axial strain over the
    rows whose |stress| lies within ``window`` (fractions of the largest |stress|); the secants
    are fit(strain) - fit(0) over ``strain``.  In 2D the in-plane secants are turned into the
    plane-strain E and nu of the conversion formulas
    (:func:`bonded_lattice.analysis.plane_strain_from_in_plane`).
    """
    if dim not in (2, 3):
        raise ValueError(f"dim = {dim} is out of range: use 2 or 3")
    if not (strain != 0 and abs(strain) < 0.01):
        raise ValueError(f"strain = {strain} is out of range: need 0 < |strain| < 0.01")
    eps = np.asarray(thermo["v_strain"], dtype=float)
    sig = np.asarray(thermo["v_stress"], dtype=float)
    lat = np.asarray(thermo.get("v_gauge", thermo["v_lateral"]), dtype=float)
    mag = np.abs(sig)
    rows = (mag >= window[0] * mag.max()) & (mag <= window[1] * mag.max())
    if rows.sum() < 5:
        raise ValueError(f"only {int(rows.sum())} thermo rows in the window {window}: need 5")
    if not (eps[rows].min() <= strain <= eps[rows].max()):
        raise ValueError(f"strain = {strain} lies outside the fitted rows' strains "
                         f"[{eps[rows].min():.4g}, {eps[rows].max():.4g}]")
    # scaled abscissa: a quadratic in strain / |strain| is well conditioned
    x = eps[rows] / abs(strain)
    t = strain / abs(strain)
    ps, pl = np.polyfit(x, sig[rows], 2), np.polyfit(x, lat[rows], 2)
    e_sec = (np.polyval(ps, t) - ps[-1]) / strain
    nu_sec = -(np.polyval(pl, t) - pl[-1]) / strain
    if dim == 2:
        return plane_strain_from_in_plane(float(e_sec), float(nu_sec))
    return float(e_sec), float(nu_sec)


def _folder(dim: int, n: int, load: str, strain: float) -> str:
    return f"{dim}d/estrain_n{n}_{load}_{strain:g}"


def run_elastic_strain(v: Validation) -> dict:
    """One elastic test per dimension, size, load and strain; its compact summary with the
    secant E and nu at the strain (relative errors against the rock)."""
    data: dict = {"strains": STRAINS, "crossings": CROSSINGS}
    for dim, sizes in SIZES.items():
        rock = rock_for(dim)
        per_dim: dict = {"sizes": sizes}
        for load in LOADS:
            table = []
            for n in sizes:
                row = []
                for s in STRAINS:
                    name = _folder(dim, n, load, s)
                    run = v.run(name, rock, dim, "elastic", n, elastic_strain=s,
                                elastic_load=load,
                                crossings=CROSSINGS["unit" if n == 2 else "block"])
                    thermo = read_thermo(v.folder(name) / "log.lammps")[-1]
                    signed = -s if load == "compression" else s
                    e_sec, nu_sec = secant_moduli(thermo, signed, dim)
                    run["secant"] = {"E": e_sec / rock.E - 1.0, "nu": nu_sec / rock.nu - 1.0}
                    row.append(run)
                table.append(row)
            per_dim[load] = table
        data[str(dim)] = per_dim
    return data


def elastic_strain_png(path, data: dict, dim: str) -> None:
    """E and nu (secants, relative to the rock) against the strain magnitude, one curve per
    block size, compression solid and tension dashed (the style of Liu 2013, Fig. 6)."""
    plt = pyplot()
    strains = np.asarray(data["strains"])
    d = data[dim]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(d["sizes"])))
    for ax, key, label in ((axes[0], "E", "Young's modulus E"),
                           (axes[1], "nu", "Poisson's ratio nu")):
        for k, n in enumerate(d["sizes"]):
            particles = d["compression"][k][0]["particles"]
            for load, style in (("compression", "-"), ("tension", "--")):
                err = [100 * r["secant"][key] for r in d[load][k]]
                ax.plot(strains, err, style, marker="o", ms=3, color=colours[k],
                        label=f"{particles} {_things(dim)}" if load == "compression" else None)
        ax.set_xscale("log")
        ax.axhline(0, color="k", lw=0.6)
        ax.set_xlabel("axial strain magnitude (solid: compression, dashed: tension)")
        ax.set_ylabel(f"{label}: error (%)")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(("2D quartz" if dim == "2" else "3D quartzite")
                 + ": secant E and nu against the strain magnitude")
    save_png(fig, path)


def _things(dim: str) -> str:
    return "particles" if dim == "2" else "elements"


def _table(d: dict, strains: list[float], key: str, dim: str) -> list[str]:
    size = "N" if dim == "2" else "n_y"
    L = [f"| {size} | {_things(dim)} | load | " + " | ".join(f"{s:g}" for s in strains) + " |",
         "|---|---|---|" + "---|" * len(strains)]
    for k, n in enumerate(d["sizes"]):
        for load in LOADS:
            runs = d[load][k]
            L.append(f"| {n} | {runs[0]['particles']} | {load} | "
                     + " | ".join(pct(r["secant"][key], 3) for r in runs) + " |")
    return L


def _change(runs: list[dict], key: str) -> str:
    """Secant error at the largest strain minus that at the smallest, in percentage points."""
    return f"{100 * (runs[-1]['secant'][key] - runs[0]['secant'][key]):+.3f}"


def doc_elastic_strain(data: dict, ctx: DocContext) -> list[str]:
    strains = data["strains"]
    L = ["## E and nu against the strain magnitude, compression and tension "
         "(Liu 2013 Fig. 6, Liu 2017 Fig. 4 a/b)", "",
         "Elastic tests (bonds unbreakable: Xb and Fs0 x 100) to each strain magnitude, "
         "pressed between the platens or pulled by their end layers (`--elastic-load "
         "tension`), constant loading at the papers' damping taking "
         f"{data['crossings']['block']:g} elastic-wave crossings (single units "
         f"{data['crossings']['unit']:g}).  E and nu are the secants at the strain itself, as "
         "the papers give them: quadratic fits of stress and gauge lateral strain against "
         "the axial strain, evaluated at the strain, so that the offset the moving platens "
         "and the damping add to the stress drops out.  Errors relative to the rock's E and "
         "nu (2D: plane strain, as the conversion formulas)."]
    for dim, label in (("2", "2D quartz"), ("3", "3D quartzite")):
        d = data.get(dim)
        if d is None:
            continue
        L += ["", f"### {label}", "", "Secant E, error:", ""] + _table(d, strains, "E", dim)
        L += ["", "Secant nu, error:", ""] + _table(d, strains, "nu", dim)
        unit_c, unit_t = d["compression"][0], d["tension"][0]
        k3 = strains.index(1e-3) if 1e-3 in strains else None
        if dim == "2" and k3 is not None:
            c3, t3 = unit_c[k3]["secant"], unit_t[k3]["secant"]
            L += ["", f"Single unit ({unit_c[0]['particles']} {_things(dim)}) at "
                  f"-{strains[k3]:g}: E {pct(c3['E'], 4)}, nu {pct(c3['nu'], 4)}; the paper "
                  f"(Liu 2013, para. 47): E {paper_pct('2d.unit.E_1e-3', 3)}, nu "
                  f"{paper_pct('2d.unit.nu_1e-3', 3)}.  In tension at +{strains[k3]:g}: E "
                  f"{pct(t3['E'], 4)}, nu {pct(t3['nu'], 4)}."]
        signs = []
        for k, n in enumerate(d["sizes"]):
            dc = {key: _change(d["compression"][k], key) for key in ("E", "nu")}
            dt = {key: _change(d["tension"][k], key) for key in ("E", "nu")}
            signs.append(f"{d['compression'][k][0]['particles']} {_things(dim)}: compression E "
                         f"{dc['E']}, nu {dc['nu']}; tension E {dt['E']}, nu {dt['nu']}")
        L += ["", f"Change of the secant errors from {strains[0]:g} to {strains[-1]:g} "
              "(percentage points): " + "; ".join(signs) + "."]
        if dim == "2":
            L += ["", "The paper (Liu 2013, para. 46): under compression E decreases and nu "
                  "increases with the strain magnitude, under tension the reverse; and "
                  f"{PAPER['2d.elastic.strain_constant'].source}.  Here every size changes by "
                  "about the single unit's amount, in the paper's senses, and linearly in the "
                  "strain (the unit's geometric nonlinearity, para. 47); the differences "
                  "between sizes and between the two loads at small strain come from the "
                  "blocks' ends, which the two loads hold differently (platens pressing "
                  "through springs; end layers moved rigidly along the load by smooth "
                  "planes)."]
        else:
            L += ["", f"The paper: {PAPER['3d.elastic.strain_growth'].source}."]
        elastic_strain_png(ctx.img / f"elastic_strain_{dim}d.png", data, dim)
        L += ["", f"![E and nu against the strain magnitude, {label}]"
              f"(img/elastic_strain_{dim}d.png)"]
    return L


ELASTIC_STRAIN = Section("elastic_strain", run_elastic_strain, doc_elastic_strain)
