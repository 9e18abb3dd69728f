"""The analogues of Liu et al. (2017) Fig. 6, drawn from the energy section's stored data:
the energy curves of a whole run with the failure in an inset (Fig. 6a, b) and the heat
curves at every step of the failure window with its start and end marked (Fig. 6c, d)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plotting import _pyplot, save_png

__all__ = ["energy_curves_png", "heat_window_png"]

# compute lattice/energy's elements (docs/compute_lattice_energy.rst) by name
ELASTIC, KINETIC, VISCOUS, BREAK_N, BREAK_S, FRICTION, WORK, BALANCE = (
    "c_energy[1]", "c_energy[2]", "c_energy[4]", "c_energy[5]", "c_energy[6]", "c_energy[7]",
    "c_energy[8]", "c_energy[10]")


def _columns(curves: dict, time_key: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    t = np.asarray(curves[time_key], dtype=float)
    return t, {k: np.asarray(v, dtype=float) for k, v in curves.items()
               if k.startswith(("c_", "v_"))}


def _energy_lines(ax, t: np.ndarray, c: dict[str, np.ndarray], scale: float, legend: bool) -> None:
    heat = c[VISCOUS] + c[BREAK_N] + c[BREAK_S] + c[FRICTION]
    for y, label, style in [(c[ELASTIC], "elastic $E_e$", "-"), (c[KINETIC], "kinetic $E_k$", "-"),
                            (heat, "heat $Q$", "-"), (c[WORK], "external work $W_e$", "k--"),
                            (c[BALANCE], "balance error", ":")]:
        ax.plot(t * scale, y, style, lw=1.2, label=label if legend else None)


def energy_curves_png(path: str | Path, whole: dict, window: dict, title: str = "",
                      inset_kinetic_only: bool = False) -> None:
    """Fig. 6a/b: elastic and kinetic energy, heat, external work and the balance error
    over the whole run (thermo rows: ``whole`` with ``Time``), and in an inset the same at
    every step of the failure window (``window`` with ``time_s``), or with
    ``inset_kinetic_only`` the kinetic energy alone (Fig. 6a: it is too small to see
    beside the others)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    t, c = _columns(whole, "Time")
    _energy_lines(ax, t, c, 1e3, legend=True)
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("energy (J)")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=5)
    ax.set_title(title, fontsize=9)
    inset = ax.inset_axes([0.08, 0.5, 0.38, 0.42])
    tw, cw = _columns(window, "time_s")
    if inset_kinetic_only:
        inset.plot(tw * 1e6, cw[KINETIC], color="C1", lw=1.2)
        inset.set_title("kinetic energy (J)", fontsize=7)
    else:
        _energy_lines(inset, tw, cw, 1e6, legend=False)
    stride = window.get("stride", 1)
    inset.set_xlabel("time (us), " + ("every step" if stride == 1 else f"every {stride} steps"),
                     fontsize=7)
    inset.tick_params(labelsize=7)
    save_png(fig, path)


def heat_window_png(path: str | Path, window: dict, event: dict,
                    marks: tuple[str, str] = ("D1", "D2"), title: str = "") -> None:
    """Fig. 6c/d: viscous, breaking (normal, shear, total) and frictional heat at every step
    of the failure window, the failure's start and end (``event``) marked ``marks``."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    t, c = _columns(window, "time_s")
    t = t * 1e6
    for y, label, style in [(c[VISCOUS], "viscous $Q_v$", "-"),
                            (c[BREAK_N], "breaking, normal $Q_{b,n}$", "-"),
                            (c[BREAK_S], "breaking, shear $Q_{b,s}$", "-"),
                            (c[BREAK_N] + c[BREAK_S], "breaking $Q_b$", "k-"),
                            (c[FRICTION], "frictional $Q_f$", "-")]:
        ax.plot(t, y, style, lw=1.2, label=label)
    for name, key in zip(marks, ("start_s", "end_s")):
        x = 1e6 * event[key]
        ax.axvline(x, color="grey", lw=0.8, ls="--")
        ax.annotate(name, (x, 0.97), xycoords=("data", "axes fraction"), ha="left",
                    va="top", fontsize=9, xytext=(3, 0), textcoords="offset points")
    ax.set_xlabel("time (us)")
    ax.set_ylabel("heat (J)")
    stride = window.get("stride", 1)
    every = "every step" if stride == 1 else f"every {stride} steps"
    ax.set_title(f"{title}\n{every}; {marks[0]} to {marks[1]}: "
                 f"{1e6 * event['duration_s']:.2f} us", fontsize=9)
    ax.legend(fontsize=8, loc="center right")
    save_png(fig, path)
