"""PNG figures: stress-strain curves and broken-bond maps."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")  # files only, no screen needed
    import matplotlib.pyplot as plt

    return plt


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
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def read_dump(path: str | Path) -> tuple[list[str], np.ndarray]:
    """Column names and rows (sorted by id) of a single-frame LAMMPS text dump."""
    lines = Path(path).read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    names = lines[k].split()[2:]
    rows = np.array([[float(v) for v in line.split()] for line in lines[k + 1:]])
    return names, rows[np.argsort(rows[:, 0])]


def broken_bond_map_png(path: str | Path, initial_dump: str | Path, final_dump: str | Path,
                        dim: int, title: str = "") -> int:
    """Particles coloured by how many of their bonds broke; returns that total / 2."""
    plt = _pyplot()
    names, first = read_dump(initial_dump)
    _, last = read_dump(final_dump)
    col = names.index("c_nbonds")
    lost = first[:, col] - last[:, col]
    x, y = last[:, names.index("x")], last[:, names.index("y" if dim == 2 else "z")]
    fig, ax = plt.subplots(figsize=(5.2, 5))
    intact = lost == 0
    ax.scatter(x[intact] * 1e3, y[intact] * 1e3, s=4, c="0.8", lw=0)
    sc = ax.scatter(x[~intact] * 1e3, y[~intact] * 1e3, s=8, c=lost[~intact], cmap="inferno_r",
                    vmin=0, vmax=max(1.0, float(lost.max())), lw=0)
    fig.colorbar(sc, ax=ax, label="broken bonds per particle")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel(("y" if dim == 2 else "z") + " (mm)")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return int(round(lost.sum() / 2))
