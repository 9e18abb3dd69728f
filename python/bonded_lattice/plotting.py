"""PNG figures: stress-strain curves and broken-bond maps."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .io.dump import read_atom_dump


def pyplot():
    """matplotlib.pyplot with the Agg backend (files only), for modules drawing their own
    figures."""
    return _pyplot()


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")  # files only, no screen needed
    import matplotlib.pyplot as plt

    return plt


def save_png(fig, path: str | Path, dpi: int = 130) -> None:
    """Lay the figure out tightly, write it as a PNG at ``dpi`` and close it."""
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    _pyplot().close(fig)


def stress_strain_png(path: str | Path, strain: np.ndarray, stress: np.ndarray, test: str,
                      E_target: float, strength_target: float | None = None,
                      title: str = "") -> None:
    """Measured curve with the theoretical elastic line and strength."""
    plt = _pyplot()
    sign = -1.0 if test in ("compression", "elastic", "confined") else 1.0
    eps, sig = sign * np.asarray(strain), sign * np.asarray(stress) / 1e6
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot(eps * 1e3, sig, lw=1.5, label="lattice (measured)")
    top = max(float(sig.max()), strength_target / 1e6 if strength_target else 0.0)
    line = np.linspace(0, top / (E_target / 1e6), 50)
    ax.plot(line * 1e3, line * E_target / 1e6, "k--", lw=1, label=f"E = {E_target / 1e9:.3g} GPa (theory)")
    if strength_target:
        name = {"tension": "Tu", "compression": "Cu"}.get(test, "sigma1")
        ax.axhline(strength_target / 1e6, color="r", ls=":", lw=1,
                   label=f"{name} = {strength_target / 1e6:.4g} MPa (theory)")
    kind = "compressive" if sign < 0 else "tensile"
    ax.set_xlabel(f"{kind} strain (1e-3)")
    ax.set_ylabel(f"{kind} stress (MPa)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.set_title(title)
    ax.legend(loc="best", fontsize=8)
    save_png(fig, path)


def damaged_particles(initial_dump: str | Path, final_dump: str | Path, dim: int) -> dict:
    """The particles that lost bonds between two dumps, for :func:`damage_map_png`.

    Returns ``{"bounds": [xlo, xhi, ylo, yhi], "x": [...], "y": [...], "panels": {label:
    [bonds lost per damaged particle]}}`` (m; in 3D the x-z projection).  With the decks'
    ``c_ntension`` and ``c_nshear`` columns two panels, bonds broken in tension (the
    micro-cracks across the load) and in shear (the shear zones); otherwise one panel of
    all bonds lost since the initial dump.
    """
    names, first = read_atom_dump(initial_dump)
    _, last = read_atom_dump(final_dump)
    x, y = last[:, names.index("x")], last[:, names.index("y" if dim == 2 else "z")]
    if "c_ntension" in names and "c_nshear" in names:
        lost = {"broken in tension": last[:, names.index("c_ntension")],
                "broken in shear": last[:, names.index("c_nshear")]}
    else:
        col = names.index("c_nbonds")
        lost = {"broken": first[:, col] - last[:, col]}
    damaged = np.zeros(len(x), dtype=bool)
    for values in lost.values():
        damaged |= values > 0
    return {"dim": dim, "bounds": [float(x.min()), float(x.max()), float(y.min()), float(y.max())],
            "x": [float(f"{v:.5g}") for v in x[damaged]],     # 1e-6 m on a 0.1 m block
            "y": [float(f"{v:.5g}") for v in y[damaged]],
            "panels": {k: [int(round(v)) for v in values[damaged]] for k, values in lost.items()}}


def damage_map_png(path: str | Path, damage: dict, title: str = "") -> int:
    """The damaged particles of :func:`damaged_particles` coloured by their broken bonds,
    over the block's outline; returns the number of broken bonds."""
    plt = _pyplot()
    panels = damage["panels"]
    x, y = np.asarray(damage["x"]) * 1e3, np.asarray(damage["y"]) * 1e3
    xlo, xhi, ylo, yhi = (1e3 * b for b in damage["bounds"])
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 5), squeeze=False)
    total = 0.0
    for ax, (label, values) in zip(axes[0], panels.items()):
        lost = np.asarray(values, dtype=float)
        total += lost.sum()
        ax.add_patch(plt.Rectangle((xlo, ylo), xhi - xlo, yhi - ylo, color="0.9", lw=0))
        hit = lost > 0
        order = np.argsort(lost[hit])   # most damaged drawn on top (3D projection)
        sc = ax.scatter(x[hit][order], y[hit][order], s=8, c=lost[hit][order],
                        cmap="inferno_r", vmin=0, vmax=max(1.0, float(lost.max(initial=0))),
                        lw=0)
        fig.colorbar(sc, ax=ax, label=f"bonds {label} per particle")
        ax.set_xlim(xlo - 0.5, xhi + 0.5)
        ax.set_ylim(ylo - 0.5, yhi + 0.5)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel(("y" if damage["dim"] == 2 else "z") + " (mm)")
        ax.set_title(f"{title}\n{label}" if title else label, fontsize=9)
    save_png(fig, path)
    return int(round(total / 2))


def broken_bond_map_png(path: str | Path, initial_dump: str | Path, final_dump: str | Path,
                        dim: int, title: str = "") -> int:
    """:func:`damage_map_png` of the bonds lost between two dumps; returns their number."""
    return damage_map_png(path, damaged_particles(initial_dump, final_dump, dim), title)


def convergence_png(path: str | Path, dim: int, series: list[dict],
                    paper_multi: dict[str, float] | None = None) -> None:
    """Errors of E, nu, Tu and Cu against particle count (the papers' Figs. 6/8 and 4).

    series: rows ``{"n": ..., "elastic": summary, "tension": summary,
    "compression": summary}`` of :func:`bonded_lattice.experiment.run_test`;
    paper_multi: the papers' average multi-unit errors of Tu and Cu, drawn as lines.
    """
    plt = _pyplot()
    count = np.array([row["elastic"]["particles"] for row in series])
    panels = [("E", "elastic", "Young's modulus E"), ("nu", "elastic", "Poisson's ratio nu"),
              ("Tu", "tension", "tensile strength Tu"), ("Cu", "compression",
                                                        "compressive strength Cu")]
    fig, axes = plt.subplots(2, 2, figsize=(8.5, 6.5))
    for ax, (key, test, label) in zip(axes.ravel(), panels):
        err = np.array([100 * row[test]["relative_error"][key] for row in series])
        ax.semilogx(count, err, "o-", label="bonded-lattice")
        if key == "nu":
            nu_all = np.array([100 * (row["elastic"]["nu_all_particles"] /
                                      row["elastic"]["target"]["nu"] - 1) for row in series])
            ax.semilogx(count, nu_all, "s--", color="0.5", ms=4, label="all-particle fit")
        if paper_multi and key in paper_multi:
            ax.axhline(100 * paper_multi[key], color="r", ls=":",
                       label=f"paper, multi-unit mean {100 * paper_multi[key]:+.1f}%")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_title(label, fontsize=10)
        ax.set_xlabel("particles" if dim == 2 else "elements")
        ax.set_ylabel("error against the formula (%)")
        ax.legend(fontsize=7, loc="best")
    fig.suptitle(f"{dim}D quartz: convergence with model size", fontsize=11)
    save_png(fig, path, dpi=120)


def energy_png(path: str | Path, thermo: dict, title: str = "") -> None:
    """Energy and heat curves of a run with compute lattice/energy (Liu 2017, Fig. 6).

    Left: elastic and kinetic energy, heat (4-7 summed), external work and the
    total; right: the heat by kind.  Against time in microseconds.
    """
    plt = _pyplot()
    t = np.asarray(thermo["Time"]) * 1e6
    col = {k: np.asarray(thermo[f"c_energy[{k}]"]) for k in range(1, 11)}
    heat = col[4] + col[5] + col[6] + col[7]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    ax = axes[0]
    for y, label, style in [(col[1], "elastic", "-"), (col[2], "kinetic", "-"), (heat, "heat", "-"),
                            (col[8], "external work", "k--"), (col[9], "total", "r:")]:
        ax.plot(t, y, style, lw=1.3, label=label)
    ax.set_title(f"{title}\nenergy" if title else "energy", fontsize=9)
    ax = axes[1]
    for k, label in [(4, "viscous"), (5, "breaking (normal springs)"),
                     (6, "breaking (shear springs)"), (7, "friction")]:
        ax.plot(t, col[k], lw=1.3, label=label)
    ax.set_title("heat", fontsize=9)
    for ax in axes:
        ax.set_xlabel("time (us)")
        ax.set_ylabel("energy (J)")
        ax.legend(fontsize=8, loc="upper left")
    save_png(fig, path)


def scene_bonds_png(path: str | Path, positions: np.ndarray, grain: np.ndarray,
                    records: np.ndarray, d: float, broken_at: dict | None = None,
                    step_label: str = "strain step", title: str = "",
                    highlight: np.ndarray | None = None, method: str = "auto",
                    period: tuple[float, float] | None = None) -> int:
    """Map of the broken bonds of a scene; returns their number.

    positions: (n, 2+) initial particle centres (ids 1..n); grain: their grain
    ids; records: rows (id1, id2, state, ...) of ``compute lattice/bond/local``
    (all records of the final state).  Each broken bond is a crack segment of
    length d across the bond at its midpoint
    (:func:`bonded_lattice.crack_raster.crack_segments`): black for tension,
    red for shear, or coloured by the step at which it broke (``broken_at``:
    {(id1, id2): step}).  method (:func:`bonded_lattice.crack_raster.choose_method`):
    ``"segments"`` draws them as lines over the grain (or layer) boundaries,
    drawn faintly as the midpoints of the bonds that join two grains;
    ``"raster"`` accumulates them into a raster of the figure's resolution over
    a faint raster of the grains (:func:`bonded_lattice.crack_raster.draw_scene_raster`),
    legible at tens of thousands of breaks; ``"auto"`` (default) segments up to
    :data:`bonded_lattice.crack_raster.SEGMENT_LIMIT` broken bonds, the raster
    above.  ``highlight`` marks particles (e.g. the growing grains) in light blue.
    period: the (x, y) lengths of a periodic box, whose bonds across the seam are
    drawn at their minimum-image midpoints.
    """
    from matplotlib.collections import LineCollection

    from .crack_raster import choose_method, crack_segments, draw_scene_raster

    plt = _pyplot()
    p = np.asarray(positions, dtype=float)[:, :2] * 1e3
    rec = np.asarray(records, dtype=float).reshape(-1, records.shape[1] if len(records) else 3)
    i = rec[:, 0].astype(np.int64) - 1
    j = rec[:, 1].astype(np.int64) - 1
    state = rec[:, 2].astype(int)
    broken = (state == 1) | (state == 2)
    method = choose_method(int(broken.sum()), method)
    fig, ax = plt.subplots(figsize=(6.4, 6.4 * (np.ptp(p[:, 1]) + 1) / (np.ptp(p[:, 0]) + 1) + 0.6))
    ax.set_xlim(p[:, 0].min() - 1e3 * d, p[:, 0].max() + 1e3 * d)
    ax.set_ylim(p[:, 1].min() - 1e3 * d, p[:, 1].max() + 1e3 * d)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(title, fontsize=9)
    length = None if period is None else np.asarray(period, dtype=float) * 1e3
    sep = p[j] - p[i]
    if length is not None:
        sep -= length * np.round(sep / length)
    mid = p[i] + 0.5 * sep
    segments = crack_segments(p, i[broken], j[broken], d * 1e3, length)
    steps = None
    if broken_at:
        steps = np.array([broken_at.get((int(a) + 1, int(b) + 1), np.nan)
                          for a, b in zip(i[broken], j[broken])], dtype=float)
        steps = np.nan_to_num(steps, nan=np.nanmax(steps) if np.isfinite(steps).any() else 0)
    if method == "raster":
        draw_scene_raster(fig, ax, p, grain, segments, state[broken] == 2, steps=steps,
                          highlight=highlight, reach=0.75e3 * d, step_label=step_label)
        save_png(fig, path)
        return int(broken.sum())
    if highlight is not None and np.any(highlight):
        h = np.asarray(highlight, dtype=bool)
        ax.scatter(p[h, 0], p[h, 1], s=2, c="#9ecae1", lw=0, zorder=0)
    across = (grain[i] != grain[j]) & (state != 3)
    ax.scatter(mid[across, 0], mid[across, 1], s=1.0, c="0.6", lw=0, zorder=1)
    if steps is not None:
        lc = LineCollection(segments, array=steps, cmap="viridis", linewidths=1.2, zorder=2)
        ax.add_collection(lc)
        fig.colorbar(lc, ax=ax, label=f"broken by {step_label}", shrink=0.8)
    else:
        colours = np.where(state[broken] == 2, "tab:red", "k")
        ax.add_collection(LineCollection(segments, colors=colours, linewidths=1.2, zorder=2))
        ax.plot([], [], "k-", label=f"tension ({int((state == 1).sum())})")
        ax.plot([], [], "-", color="tab:red", label=f"shear ({int((state == 2).sum())})")
        ax.legend(loc="upper right", fontsize=7)
    save_png(fig, path)
    return int(broken.sum())


def scene_stress_png(path: str | Path, curves: list[dict], xlabel: str = "strain e_xx (1e-3)",
                     title: str = "") -> None:
    """Wall stresses against strain, and broken bonds, for one or more runs.

    curves: dicts with ``label``, ``strain`` (x values), ``sxx``, ``syy`` (Pa) and
    ``broken`` (counts).  Left: sigma_xx (solid) and sigma_yy (dashed); right:
    broken bonds.
    """
    plt = _pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    for k, c in enumerate(curves):
        colour = f"C{k}"
        x = np.asarray(c["strain"]) * 1e3
        ax.plot(x, np.asarray(c["sxx"]) / 1e6, "-", color=colour, lw=1.3,
                label=f"{c['label']}: sigma_xx")
        ax.plot(x, np.asarray(c["syy"]) / 1e6, "--", color=colour, lw=1.0,
                label=f"{c['label']}: sigma_yy")
        bx.plot(x, c["broken"], "-", color=colour, lw=1.3, label=c["label"])
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("wall stress, tension positive (MPa)")
    ax.legend(fontsize=7)
    bx.set_xlabel(xlabel)
    bx.set_ylabel("broken bonds")
    bx.legend(fontsize=7)
    fig.suptitle(title, fontsize=9)
    save_png(fig, path)


def angle_histogram_png(path: str | Path, series: list[tuple[str, np.ndarray]],
                        title: str = "") -> None:
    """Histograms of broken-bond orientations (degrees from x) for several runs."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6, 3.8))
    bins = np.arange(-15, 181, 30)
    width = 30.0 / (len(series) + 1)
    for k, (label, a) in enumerate(series):
        a = np.asarray(a, dtype=float)
        a = np.where(a >= 165, a - 180, a)
        h, _ = np.histogram(a, bins=bins)
        frac = h / max(1, len(a))
        # the runs side by side within each 30-degree bin
        ax.bar(bins[:-1] + width * (k + 0.5), frac, width=width, label=f"{label} ({len(a)})",
               align="edge")
    ax.set_xticks([0, 30, 60, 90, 120, 150])
    ax.set_xlabel("broken-bond orientation (degrees from x, the extension axis)")
    ax.set_ylabel("fraction of broken bonds")
    ax.legend(fontsize=7)
    ax.set_title(title, fontsize=9)
    save_png(fig, path)
