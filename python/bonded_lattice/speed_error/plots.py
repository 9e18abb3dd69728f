"""The figures of the speed-against-error report (PNG, matplotlib's Agg backend)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plotting import save_png
from .fitting import pareto_front, within
from .lattice_runs import points
from .settings import DEFAULT, DT_BASE, QUANTITIES, TEST_OF, TOLERANCE

def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


FAMILY_STYLE = {"constant": ("o", "C0", "constant speed (grid)"),
                "slow": ("D", "C2", "constant speed, slow"),
                "dt": ("v", "C4", "constant speed, other dt"),
                "stepwise": ("s", "C1", "stepwise (relax, step size varied)"),
                "paper": ("*", "r", "papers' stepwise schedule")}


def _save(fig, path: Path, title: str | None = None) -> None:
    """Title (if any), tight layout, PNG at 120 dpi, and close the figure."""
    if title:
        fig.suptitle(title, fontsize=11)
    save_png(fig, path, dpi=120)


def _axes_text(ax, title: str, fontsize: float, xlabel: str, ylabel: str) -> None:
    """An axes' title (at ``fontsize``) and axis labels."""
    ax.set_title(title, fontsize=fontsize)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)


def plot_contact(res: dict, path: Path) -> None:
    """Part 1: error against dt of the single-contact tests, and the stability of the
    contact spring (bonded T1 against Verlet's amplitude; T1's exit speed error)."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    ax = axes[0]
    for i, (test, rows) in enumerate(res["sweep"].items()):
        dts = np.array([r["dt"] for r in rows])
        for kind, style in (("max", "-"), ("smooth", ":")):
            err = np.array([r[kind] for r in rows])
            order = res["orders"][test][kind]["fit"]
            lab = f"{test} {'whole run' if kind == 'max' else 'first phase'} (order {order:.2f})"
            ax.loglog(dts, err, style, marker="o" if kind == "max" else ".", color=f"C{i}",
                      label=lab, ms=4)
    ax.set_xlabel("time step dt (s)")
    ax.set_ylabel("max |y - analytic| (m)")
    ax.set_title("single-contact tests: error against dt", fontsize=10)
    ax.legend(fontsize=7)
    ax = axes[1]
    st = res["stability"]
    pts = sorted(st["scan"] + st["bisection"], key=lambda p: p["frac"])
    fr = np.array([p["frac"] for p in pts])
    amp = np.array([p["amplitude"] for p in pts])
    stable = np.array([p["stable"] for p in pts])
    ax.semilogy(fr[stable], amp[stable], "o", color="C0", label="bonded T1, stable")
    ax.semilogy(fr[~stable], amp[~stable], "x", color="r", ms=8,
                label="bonded T1, unstable (stopped at |y| > 100 m)")
    h = np.linspace(0.05, 0.99995, 400)
    ax.semilogy(h, 1 / np.sqrt(1 - h**2), "k-", lw=0.8,
                label="Verlet amplitude 1/sqrt(1 - h^2/4), h = k dt")
    ax.axvline(1.0, color="0.5", ls="--", lw=0.8)
    ax.text(1.0, ax.get_ylim()[0] * 3, " dt_c = 2 sqrt(m/Kn)", fontsize=7)
    ax2 = ax.twinx()
    cs = st["contact"]
    ax2.plot([c["frac"] for c in cs], [100 * abs(c["exit_v"] / c["exit_v_exact"] - 1) for c in cs],
             "s--", color="C1", ms=4, label="T1 contact (no bond): exit speed error")
    ax2.set_ylabel("T1 exit speed error (%)", color="C1")
    ax.set_xlabel("dt / dt_c")
    ax.set_ylabel("max |y| / (v0/k)")
    ax.set_title("stability of the contact spring", fontsize=10)
    lines = ax.get_legend_handles_labels()
    lines2 = ax2.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], fontsize=7, loc="upper left")
    _save(fig, path)


def _per_test(default: dict | None) -> dict[str, tuple[float, float]] | None:
    """A default setting as {test: (crossings, damping)}: ``default`` is one setting
    ({"crossings", "damping"}) for every test, or already such a mapping."""
    if default is None:
        return None
    if "crossings" in default:
        return {t: (default["crossings"], default["damping"]) for t in set(TEST_OF.values())}
    return default


def plot_constant(lat: dict, path: Path, default: dict = DEFAULT,
                  title: str = "constant schedule: error against loading rate and damping"
                  ) -> None:
    """The constant schedule's error in E, nu, Tu and Cu against crossings, per damping
    (dashed: the ``default`` setting's crossings, one for all tests or per test kind)."""
    per_test = _per_test(default)
    plt = _plt()
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    dampings = sorted({k[1] for k in lat["grid"]})
    cmap = plt.get_cmap("viridis")
    for ax, q in zip(axes.ravel(), QUANTITIES):
        for j, f in enumerate(dampings):
            cs = sorted(c for c, g in lat["grid"] if g == f)
            e = [lat["grid"][(c, f)][q] for c in cs]
            ok = [(c, 100 * v) for c, v in zip(cs, e) if v is not None]
            if ok:
                ax.semilogx(*zip(*ok), "o-", ms=3.5, color=cmap(j / max(1, len(dampings) - 1)),
                            label=f"damping {f:g}")
        pe = 100 * lat["paper_err"][q]
        ax.axhline(pe, color="r", ls=":", lw=1.2, label=f"papers' schedule ({pe:+.2f}%)")
        band = 100 * TOLERANCE[q]
        ax.axhspan(pe - band, pe + band, color="r", alpha=0.07,
                   label=f"papers' accuracy (their value +-{band:g}%)")
        ax.axvline(per_test[TEST_OF[q]][0], color="0.6", lw=0.8, ls="--")
        ref = "formula" if q in ("E", "nu") else "papers' schedule"
        ax.set_title(f"{q}: error against the {ref}", fontsize=10)
        ax.set_xlabel("elastic-wave crossings to failure (constant speed)")
        ax.set_ylabel("error (%)")
        lo = min(-abs(pe) - 4 * band, -1.5)
        ax.set_ylim(max(ax.get_ylim()[0], lo * 4), min(ax.get_ylim()[1], -lo * 4))
    axes[0, 0].legend(fontsize=6.5, ncol=2)
    _save(fig, path, title)


def plot_pareto(lat: dict, path: Path, floor: float = 1e-5,
                default: dict | None = None,
                title: str = "error against cost: all runs, Pareto front, the papers' schedule"
                ) -> None:
    """Error against time steps of every run, with the Pareto fronts (|errors| below
    ``floor`` drawn at it) and, if given, the runs of the ``default`` setting marked (one
    setting for all tests, or {test: (crossings, damping)})."""
    per_test = _per_test(default)
    plt = _plt()
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 8))
    for ax, q in zip(axes.ravel(), QUANTITIES):
        pts = points(lat["results"], q)
        if not pts:
            continue
        for fam, (marker, color, label) in FAMILY_STYLE.items():
            sel = [p for p in pts if p["case"]["family"] == fam]
            if sel:
                ax.loglog([p["steps"] for p in sel],
                          [max(abs(p["errors"][q]), floor) for p in sel], marker, color=color,
                          ms=12 if fam == "paper" else 5, ls="none", label=label,
                          alpha=1.0 if fam == "paper" else 0.75, zorder=3 if fam == "paper" else 2)
        front = [pts[i] for i in pareto_front([p["steps"] for p in pts],
                                              [abs(p["errors"][q]) for p in pts])]
        ax.step([p["steps"] for p in front], [max(abs(p["errors"][q]), floor) for p in front],
                "k-", where="post", lw=1, label="Pareto front")
        if q in ("E", "nu"):
            pe_q = lat["paper_err"][q]
            dev = [pts[i] for i in pareto_front([p["steps"] for p in pts],
                                                [abs(p["errors"][q] - pe_q) for p in pts])]
            ax.step([p["steps"] for p in dev],
                    [max(abs(p["errors"][q] - pe_q), floor) for p in dev], "k--", where="post",
                    lw=0.8, label="front of |error - papers' error|")
        if TEST_OF[q] in lat["paper"]:
            ps = lat["paper"][TEST_OF[q]]["steps"]
            ax.axvline(ps / 10, color="r", ls="--", lw=0.8, label="10x fewer steps than the papers'")
        good = [p for p in pts if within(p["errors"][q], lat["paper_err"][q], TOLERANCE[q])]
        ax.loglog([p["steps"] for p in good], [max(abs(p["errors"][q]), floor) for p in good],
                  "o", mfc="none", mec="k", ms=9, ls="none", label="at the papers' accuracy")
        if per_test is not None:
            mine = [p for p in pts if p["case"]["family"] in ("constant", "slow") and
                    (p["case"]["crossings"], p["case"]["damping"]) == per_test[TEST_OF[q]]]
            ax.loglog([p["steps"] for p in mine], [max(abs(p["errors"][q]), floor) for p in mine],
                      "s", mfc="none", mec="b", ms=12, mew=1.5, ls="none",
                      label="the package's default")
        pe = abs(lat["paper_err"][q])
        ax.axhspan(max(pe - TOLERANCE[q], floor), pe + TOLERANCE[q], color="r", alpha=0.07)
        ref = "formula" if q in ("E", "nu") else "papers' schedule (its own point: 0)"
        _axes_text(ax, f"{q}: |error| against the {ref}", 9.5, "time steps", "|error|")
    axes[0, 0].legend(fontsize=6.5)
    _save(fig, path, title)


def plot_stepwise(lat: dict, path: Path) -> None:
    """The stepwise schedule's error against time steps, by relaxation steps and step size."""
    plt = _plt()
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    for ax, q in zip(axes.ravel(), QUANTITIES):
        pts = [p for p in points(lat["results"], q) if p["case"]["schedule"] == "stepwise"]
        relax = sorted({p["case"]["relax_steps"] for p in pts}, reverse=True)
        for j, r in enumerate(relax):
            sel = sorted((p for p in pts if p["case"]["relax_steps"] == r),
                         key=lambda p: p["steps"])
            ax.semilogx([p["steps"] for p in sel], [100 * p["errors"][q] for p in sel], "s-",
                        color=f"C{j}", ms=4, label=f"{r} relaxation steps")
            for p in sel:
                ax.annotate(f"x{p['case']['step_factor']:g}", (p["steps"], 100 * p["errors"][q]),
                            fontsize=6, xytext=(2, 2), textcoords="offset points")
        const = [p for p in points(lat["results"], q) if p["case"]["family"] in ("constant", "slow")
                 and p["case"]["damping"] == 1.0]
        const.sort(key=lambda p: p["steps"])
        ax.semilogx([p["steps"] for p in const], [100 * p["errors"][q] for p in const], "o--",
                    color="0.5", ms=3, label="constant speed, damping 1")
        if TEST_OF[q] in lat["paper"]:
            p = lat["paper"][TEST_OF[q]]
            ax.semilogx([p["steps"]], [100 * p["errors"].get(q, 0.0)], "r*", ms=13,
                        label="papers' schedule")
        ref = "formula" if q in ("E", "nu") else "papers' schedule"
        _axes_text(ax, f"{q}: error against the {ref} (labels: step size x the papers')", 9,
                   "time steps", "error (%)")
    axes[0, 0].legend(fontsize=7)
    _save(fig, path, "the papers' stepwise schedule: relaxation steps and step size")


def plot_lattice_dt(lat: dict, path: Path) -> None:
    """E and nu against the time step, and the lattice's time-step scan (peak kinetic energy)."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    ax = axes[0]
    for q, color in (("E", "C0"), ("nu", "C1")):
        rows = [r for r in lat["results"] if r["case"]["test"] == "elastic" and r["ok"]
                and ((r["case"]["family"] == "dt") or (r["case"]["family"] == "constant" and
                     (r["case"]["crossings"], r["case"]["damping"]) ==
                     (DT_BASE["crossings"], DT_BASE["damping"])))]
        rows.sort(key=lambda r: r["plan"]["dt"])
        fr = [r["case"]["dt_fraction"] or 0.1 for r in rows]
        ax.semilogx(fr, [100 * r["errors"][q] for r in rows], "o-", color=color,
                    label=f"{q}, N = {rows[0]['case']['n'] if rows else ''}")
    for q, color in (("E", "C0"), ("nu", "C1")):
        rows = [r for r in lat["stability"]["rows"] if r["ok"] and abs(r["errors"]["E"]) < 0.05]
        ax.semilogx([r["case"]["dt_fraction"] for r in rows],
                    [100 * r["errors"][q] for r in rows], "x:", color=color,
                    label=f"{q}, stability scan N = {lat['stability']['rows'][0]['case']['n']}")
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("dt / sqrt(m/Kn)")
    ax.set_ylabel("error against the formula (%)")
    ax.set_title(f"elastic test, {DT_BASE['crossings']:g} crossings: error against dt "
                 "(stable runs)", fontsize=10)
    ax.legend(fontsize=7)
    ax = axes[1]
    rows = lat["stability"]["rows"]
    fr = [r["case"]["dt_fraction"] for r in rows]
    ke = [r.get("ke_max", np.nan) if r["ok"] else np.nan for r in rows]
    ax.semilogy(fr, ke, "o-", label="peak kinetic energy (J/m)")
    for r in rows:
        if not (r["ok"] and abs(r["errors"]["E"]) < 0.05):
            ax.axvline(r["case"]["dt_fraction"], color="r", lw=0.8, alpha=0.6)
    ax.axvline(lat["stability"]["formula"], color="k", ls="--", lw=0.8,
               label="critical_time_step bound sqrt(2m/(6 Kn))")
    ax.axvline(0.10715, color="C2", ls=":", lw=1, label="papers' dt (0.107)")
    ax.set_xlabel("dt / sqrt(m/Kn)")
    ax.set_title("lattice time-step scan (red: unstable)", fontsize=10)
    ax.legend(fontsize=7)
    _save(fig, path)

