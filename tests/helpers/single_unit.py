"""The single lattice unit of the papers (Liu, Pollard & Shi 2013, Fig. 2; Liu et al. 2017,
Fig. 3): its geometry, its stress and strain definitions and an exact-geometry quasi-static
reference of its loading path, independent of LAMMPS.  Used by
tests/validation/test_single_unit.py (the unit simulated in LAMMPS) and
tests/unit/test_conversion.py (the strength the conversion's warning names)."""

from __future__ import annotations

import math

S3 = math.sqrt(3.0)


# ----------------------------------------------------------------------------------------------
# unit geometry and the unit's stress / strain definitions (module docstring)
# ----------------------------------------------------------------------------------------------

def unit_geometry(dim: int, d: float) -> dict[str, float]:
    """Base-particle distance from the load axis, apex height, number of base particles."""
    if dim == 2:
        return {"rho0": d / 2.0, "h0": S3 / 2.0 * d, "nbase": 2}
    return {"rho0": d / S3, "h0": math.sqrt(2.0 / 3.0) * d, "nbase": 3}


def unit_stress(dim: int, force: float, d: float) -> float:
    """Vertical stress of the unit from the vertical force on the apex (eq. 12 / eq. 5)."""
    return force / d if dim == 2 else 2.0 * S3 * force / (3.0 * d * d)


def elastic_constants_2d(sig_yy: float, eps_xx: float, eps_yy: float) -> tuple[float, float]:
    """E, nu of the triangle unit through eq. 14 (plane strain, sigma_xx = 0), as the paper."""
    # [eps_xx eps_yy; eps_yy eps_xx] [2G + lam; lam] = [0; sig_yy]
    det = eps_xx * eps_xx - eps_yy * eps_yy
    m = -eps_yy * sig_yy / det
    lam = eps_xx * sig_yy / det
    g = 0.5 * (m - lam)
    return g * (3.0 * lam + 2.0 * g) / (lam + g), lam / (2.0 * (lam + g))


# ----------------------------------------------------------------------------------------------
# independent reference: exact-geometry quasi-static path of the symmetric unit
# ----------------------------------------------------------------------------------------------

def finite_strain_unit(dim: int, p: dict[str, float], d: float, sign: int,
                       eps_max: float, nstep: int = 2000) -> dict[str, float]:
    """The failure of the unit on its exact quasi-static path (:func:`unit_path`): the
    failure stress of the inclined bonds, its strain, the mode, and (when base bonds open
    first) C_open, each located by linear interpolation between load steps."""
    out: dict[str, float] = {}
    prev = {"eps": 0.0, "sig": 0.0, "open": -1.0, "tension": -1.0, "shear": -1.0}

    def interpolate(a: dict, b: dict, key: str) -> tuple[float, float]:
        t = (0.0 - a[key]) / (b[key] - a[key])
        return a["sig"] + t * (b["sig"] - a["sig"]), a["eps"] + t * (b["eps"] - a["eps"])

    for cur in unit_path(dim, p, d, sign, eps_max, nstep):
        if "opened" in cur:          # the base bonds opened during this step
            sig_open, out["eps_open"] = interpolate(prev, cur["opened"], "open")
            out["C_open"] = -sig_open    # a magnitude, as eq. 22 / eq. 8
        for mode in ("tension", "shear"):
            if cur[mode] > 0.0:
                sig_fail, out["eps_peak"] = interpolate(prev, cur, mode)
                out["peak"] = sign * sig_fail    # a magnitude, as Tu and Cu
                out["mode"] = mode
                return out
        prev = cur
    raise AssertionError(f"finite_strain_unit: no failure up to strain {sign * eps_max}")


def unit_path(dim: int, p: dict[str, float], d: float, sign: int, eps_max: float,
              nstep: int = 2000):
    """Quasi-static response of the unit to the apex moved by sign * eps * l_AO, exact geometry:
    yields the state at eps = sign * eps_max * k / nstep, k = 1..nstep.

    By symmetry the apex stays on the axis and each base particle moves radially (in 3D the
    vertical plane through the axis and a base element is a mirror plane).  In that plane an
    inclined bond joins the base particle at radius rho to the apex at height H: length
    r = hypot(rho, H), angle theta = atan2(H, rho); its shear spring lies in the plane and turns
    with the bond: ds = r dtheta (the incremental spring of the model).  Base bonds have length
    2 rho (2D) or sqrt3 rho (3D) and no shear displacement.  Equilibrium of a base particle along
    the radius (the only free direction it has by symmetry):
        Fn cos(theta) - Ks s sin(theta) + c Fn2 = 0,
    c = 1 (2D), sqrt3 (3D: two base bonds at 30 deg to the radius),
    and the apex force is nbase * (Fn sin(theta) + Ks s cos(theta)).
    Each state: eps, sig (the unit stress, tension positive), lat (the lateral strain
    X_n2 / l_BC of the base bond), rho, r, theta, s, and the margins to the events, > 0 once
    they happened: open (a base bond past Xb in tension), tension (an inclined bond past Xb),
    shear (an inclined bond's shear spring past its Coulomb limit); a state in whose step the
    base bonds opened also holds, under "opened", the state just before they let go.  Bonds
    never break here: the caller decides what an event means (the path goes on with the base
    bonds open once they opened).
    """
    g = unit_geometry(dim, d)
    rho0, h0, nbase = g["rho0"], g["h0"], g["nbase"]
    c_base = 1.0 if dim == 2 else S3
    edge = (lambda rho: 2.0 * rho) if dim == 2 else (lambda rho: S3 * rho)
    kn, ks, xb, fs0, mu_p = p["Kn"], p["Ks"], p["Xb"], p["Fs0"], p["mu_p"]

    rho, s, theta, r = rho0, 0.0, math.atan2(h0, rho0), d
    base_intact = True

    def solve(height: float, intact: bool) -> dict[str, float]:
        def state(rr_base: float):
            rr = math.hypot(rr_base, height)
            th = math.atan2(height, rr_base)
            ss = s + 0.5 * (rr + r) * (th - theta)
            fn = kn * (rr - d)
            xn2 = edge(rr_base) - d
            fn2 = kn * xn2 if (intact or xn2 < 0.0) else 0.0
            return rr, th, ss, fn, fn2, xn2

        def resid(rr_base: float) -> float:
            rr, th, ss, fn, fn2, _ = state(rr_base)
            return fn * math.cos(th) - ks * ss * math.sin(th) + c_base * fn2

        lo, hi = 0.9 * rho0, 1.1 * rho0    # the residual increases with rho
        assert resid(lo) < 0.0 < resid(hi)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if resid(mid) < 0.0:
                lo = mid
            else:
                hi = mid
            if hi - lo < 1e-16 * rho0:
                break
        rb = 0.5 * (lo + hi)
        rr, th, ss, fn, fn2, xn2 = state(rb)
        force = nbase * (fn * math.sin(th) + ks * ss * math.cos(th))
        # dimensionless, > 0 once an inclined bond breaks: opening / intact-bond Coulomb limit
        m_open = (rr - d) / xb - 1.0
        m_slide = ks * abs(ss) / (fs0 - mu_p * fn) - 1.0 if fs0 - mu_p * fn > 0.0 else 1.0
        return {"rho": rb, "r": rr, "theta": th, "s": ss, "sig": unit_stress(dim, force, d),
                "lat": xn2 / d, "open": xn2 / xb - 1.0, "tension": m_open, "shear": m_slide}

    for k in range(1, nstep + 1):
        eps = sign * eps_max * k / nstep
        cur = solve(h0 * (1.0 + eps), base_intact)
        cur["eps"] = eps
        if base_intact and cur["open"] > 0.0:
            before = cur
            base_intact = False
            cur = solve(h0 * (1.0 + eps), base_intact)
            cur["eps"] = eps
            cur["opened"] = before
        rho, s, theta, r = cur["rho"], cur["s"], cur["theta"], cur["r"]
        yield cur
