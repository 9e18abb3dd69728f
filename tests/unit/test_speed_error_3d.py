"""The 3D part of bonded_lattice.speed_error and the report's statements on the references and
the defaults (no simulation; well under a second): the 3D cases, the reference of the
transfer check, the stepwise variants that show the reference converged, the tolerance
shares and the Pareto membership of a default setting, on synthetic data with a known
answer."""

from __future__ import annotations

import dataclasses

import pytest

from bonded_lattice import speed_error as se
from bonded_lattice.schedules import DEFAULT_LOADING, PAPER_SCHEDULES
from bonded_lattice.speed_error.lattice_runs import (SpeedErrorRun, case_folder,
                                                     check_reference_case)
from bonded_lattice.speed_error.report_defaults import (converged_text, default_on_fronts,
                                                        per_test_settings, reference_convergence,
                                                        reference_variants)


def test_3d_cases():
    cases = se.lattice_cases(se.FULL_3D)
    s = se.FULL_3D
    grid = len(s.crossings) * len(s.dampings)
    stepwise = len(s.relax) * len(s.step_factors)
    assert len(cases) == 3 * (grid + stepwise)      # no slow or dt variants in 3D
    assert {c.dim for c in cases} == {3}
    assert len({c.name for c in cases}) == len(cases)
    # 3D names never collide with 2D ones (n_y, not N)
    assert not {c.name for c in cases} & {c.name for c in se.lattice_cases(se.FULL)}
    assert {c.n for c in cases if c.test == "elastic"} == {s.n_elastic}
    assert {c.n for c in cases if c.test != "elastic"} == {s.n_strength}
    # the reference: exactly one papers' 3D schedule per test, 100 relaxation steps, step x1
    paper = [c for c in cases if c.family == "paper"]
    assert sorted(c.test for c in paper) == ["compression", "elastic", "tension"]
    assert {(c.relax_steps, c.step_factor) for c in paper} == {
        (PAPER_SCHEDULES[3]["relax_steps"], 1.0)}
    assert se.paper_relax(3) == 100 and se.paper_relax(2) == 400
    with pytest.raises(ValueError, match="dim = 4"):
        se.paper_relax(4)
    with pytest.raises(ValueError, match="dim = 1"):
        dataclasses.replace(se.FULL, dim=1)
    # the 2D cases are unchanged (dim 2, the names of the cache)
    assert {c.dim for c in se.lattice_cases(se.FULL)} == {2}
    assert se.Case("paper", "tension", 6, schedule="stepwise", relax_steps=100,
                   dim=3).name == "tension_ny6_stepwise_r100_s1"


def test_check_reference_and_folders(tmp_path):
    # 2D: a slow constant run; 3D: the papers' stepwise schedule at the check's size
    ref2 = check_reference_case(se.FULL, "compression")
    assert (ref2.schedule, ref2.crossings, ref2.n) == ("constant", 800, 30)
    ref3 = check_reference_case(se.FULL_3D, "tension")
    assert (ref3.schedule, ref3.relax_steps, ref3.n, ref3.dim) == ("stepwise", 100, 10, 3)
    assert case_folder(ref3, tmp_path).parts[-3:] == ("lattice3d", "check",
                                                       "tension_ny10_stepwise_r100_s1")
    assert se.FULL.default == DEFAULT_LOADING[2] and se.FULL_3D.default == DEFAULT_LOADING[3]
    assert se.FULL_3D.size_name == "n_y" and se.FULL.size_name == "N"


def test_cached_2d_result_without_dim_is_accepted(tmp_path):
    case = se.Case("constant", "tension", 15, crossings=50, damping=0.25)
    old = {k: v for k, v in dataclasses.asdict(case).items() if k != "dim"}
    stored = {"case": old, "halted": False}
    got = SpeedErrorRun(case, tmp_path)._accept_stored(dict(stored))
    assert got is not None and got["cached"] and got["case"]["dim"] == 2
    # ... but not for the 3D case of the same numbers
    case3 = dataclasses.replace(case, dim=3)
    assert SpeedErrorRun(case3, tmp_path)._accept_stored(dict(stored)) is None


def test_reference_variants():
    # one factor 4 cheaper than the papers' schedule: 4x fewer relaxation steps, 4x larger steps
    assert reference_variants(se.FULL) == [(100, 1.0), (400, 4.0)]
    assert reference_variants(se.FULL_3D) == [(25, 1.0), (100, 4.0)]


def test_worst_share_and_robust_shares():
    tol = {"E": 0.001, "Cu": 0.005}
    paper = {"E": -0.002, "Cu": 0.0}
    assert se.worst_share({"E": -0.0025, "Cu": 0.004}, paper, tol) == pytest.approx(0.8)
    assert se.worst_share({"E": -0.0025, "Cu": None}, paper, tol) is None
    grid = {(10, 1.0): {"E": -0.002, "Cu": 0.001},      # share 0.2
            (30, 1.0): {"E": -0.004, "Cu": 0.0},        # share 2.0
            (100, 1.0): {"E": -0.002, "Cu": 0.0025},    # share 0.5
            (10, 2.0): {"E": -0.002, "Cu": None}}
    r = se.robust_shares(grid, paper, tol)
    # the faster setting carries the worst of every slower one of its damping
    assert r[(10, 1.0)] == pytest.approx(2.0) and r[(30, 1.0)] == pytest.approx(2.0)
    assert r[(100, 1.0)] == pytest.approx(0.5) and r[(10, 2.0)] is None


def test_grid_front():
    costs = {(10, 1.0): 10.0, (30, 1.0): 30.0, (100, 1.0): 100.0, (30, 2.0): 30.0,
             (300, 1.0): 300.0}
    errors = {(10, 1.0): 3.0, (30, 1.0): 0.9, (100, 1.0): 0.95, (30, 2.0): 1.5,
              (300, 1.0): 0.1}
    # (100, 1) is dominated by the cheaper and better (30, 1); (30, 2) by (30, 1)
    assert se.grid_front(costs, errors) == [(10, 1.0), (30, 1.0), (300, 1.0)]
    errors[(10, 1.0)] = None        # a setting without an error is left out
    assert se.grid_front(costs, errors) == [(30, 1.0), (300, 1.0)]


def _fake_lat(s: se.Settings, table: dict[tuple[float, float], dict[str, float]],
              paper_err: dict[str, float]) -> dict:
    """A run_lattice-like result: one run per test and grid setting, time steps = crossings
    x (10 for the elastic block, 1 for the strength blocks), the errors of ``table``; the
    papers' schedule at 1e6 steps per test."""
    results = []
    for (c, f), errs in table.items():
        for test in ("elastic", "tension", "compression"):
            case = se.grid_case(s, test, c, f)
            qs = [q for q in se.QUANTITIES if se.TEST_OF[q] == test]
            results.append({"name": case.name, "case": dataclasses.asdict(case), "ok": True,
                            "steps": int(c * (10 if test == "elastic" else 1)),
                            "errors": {q: errs[q] for q in qs}})
    paper = {}
    for test in ("elastic", "tension", "compression"):
        case = se.Case("paper", test, se.settings.test_n(s, test), schedule="stepwise",
                       relax_steps=se.paper_relax(s.dim), dim=s.dim)
        rec = {"name": case.name, "case": dataclasses.asdict(case), "ok": True, "steps": 10**6,
               "errors": {q: paper_err[q] for q in se.QUANTITIES if se.TEST_OF[q] == test}}
        results.append(rec)
        paper[test] = rec
    grid = {k: dict(v) for k, v in table.items()}
    return {"results": results, "grid": grid, "paper": paper, "paper_err": paper_err}


def test_default_on_fronts():
    s = dataclasses.replace(se.FULL_3D, crossings=(100, 300, 1000), dampings=(0.5, 1.0))
    paper_err = {"E": 0.007, "nu": -0.03, "Tu": 0.0, "Cu": 0.0}

    def errs(cu: float) -> dict[str, float]:
        # E and nu as the papers' schedule, Tu 0.001 (0.2 of its tolerance 0.005)
        return {"E": 0.007, "nu": -0.03, "Tu": 0.001, "Cu": cu}

    table = {(100, 1.0): errs(0.05), (300, 1.0): errs(0.006), (1000, 1.0): errs(0.004),
             (100, 0.5): errs(-0.02), (300, 0.5): errs(-0.03), (1000, 0.5): errs(-0.03)}
    lat = _fake_lat(s, table, paper_err)
    by_name = {r["name"]: r for r in lat["results"]}
    d = default_on_fronts(s, lat, by_name, default=(1000, 1.0))
    # costs: 10 c (elastic) + c + c; robust shares (Cu / 0.005 at the setting and every slower
    # one): damping 1: 10, 1.2, 0.8; damping 0.5: 6 everywhere (from 0.03 at 300 and 1000)
    assert d["costs"][(300, 1.0)] == 3600
    assert [d["robust"][(c, 1.0)] for c in (100, 300, 1000)] == pytest.approx([10, 1.2, 0.8])
    assert [d["robust"][(c, 0.5)] for c in (100, 300, 1000)] == pytest.approx([6, 6, 6])
    # front: (100, 0.5) beats (100, 1) at the same cost; then (300, 1) and (1000, 1)
    assert d["front"] == [(100, 0.5), (300, 1.0), (1000, 1.0)]
    assert d["on_front"] and d["share"] == pytest.approx(0.8)
    # per quantity: E, nu, Tu have the same deviation at every setting, so only the cheapest
    # run of each (100 crossings) is on their fronts; Cu at 1000/1 (0.004) is beaten only by
    # the stepwise runs' 0 at 1e6 steps, which cost more
    assert d["per_quantity"] == {"E": False, "nu": False, "Tu": False, "Cu": True}
    assert not default_on_fronts(s, lat, by_name, default=(300, 0.5))["on_front"]
    assert not default_on_fronts(s, lat, by_name, default=(100, 1.0))["on_front"]
    assert default_on_fronts(s, lat, by_name, default=(300, 1.0))["on_front"]
    assert not default_on_fronts(s, lat, by_name, default=(50, 1.0))["in_grid"]
    # per test kind (recommend on the test's own quantities): elastic and tension hold at
    # every setting, ties in crossings go to the first damping of equal share; Cu needs 1000/1
    per = per_test_settings(s, lat)
    assert per["elastic"][:2] == (100, 0.5) and per["tension"][:2] == (100, 0.5)
    assert per["compression"][:2] == (1000, 1.0)
    per = per_test_settings(s, lat, damping=1.0)
    assert [per[t][:2] for t in ("elastic", "tension", "compression")] == [
        (100, 1.0), (100, 1.0), (1000, 1.0)]
    # per-test defaults at damping 1: 1000 + 100 + 1000 steps, share max(0, 0.2, 0.8); the
    # only cheaper grid settings (100 crossings, 1200 steps) use 6 and 10 of the tolerance
    mixed = {"elastic": (100, 1.0), "tension": (100, 1.0), "compression": (1000, 1.0)}
    d = default_on_fronts(s, lat, by_name, default=mixed)
    assert d["cost"] == 2100 and d["share"] == pytest.approx(0.8) and d["on_front"]
    # compression at 300 and damping 0.5 (Cu 6 x its tolerance, 1400 steps) is beaten by the
    # cheaper (100, 0.5) at the same share
    mixed["compression"] = (300, 0.5)
    d = default_on_fronts(s, lat, by_name, default=mixed)
    assert d["share"] == pytest.approx(6.0) and not d["on_front"]


def test_reference_convergence():
    s = se.FULL_3D
    lat = {"paper": {}}
    by_name = {}
    for test, key, value in (("tension", "strength", 20e6), ("compression", "strength", 200e6),
                             ("elastic", "E", 90e9)):
        case = se.Case("paper", test, se.settings.test_n(s, test), schedule="stepwise",
                       relax_steps=100, dim=3)
        rec = {"name": case.name, "ok": True, key: value, "nu": 0.16}
        lat["paper"][test] = rec
        for (r_, f), dev in zip(reference_variants(s), (0.0004, -0.0008)):
            v = se.Case("stepwise", test, case.n, schedule="stepwise", relax_steps=r_,
                        step_factor=f, dim=3)
            by_name[v.name] = {"name": v.name, "ok": True, key: value * (1 + dev),
                               "nu": 0.16 * (1 + dev)}
    conv = reference_convergence(s, lat, by_name)
    assert conv["Tu"] == pytest.approx(0.0008) and conv["Cu"] == pytest.approx(0.0008)
    assert conv["E"] == pytest.approx(0.0008) and conv["nu"] == pytest.approx(0.0008)
    text = converged_text(s, lat, by_name)
    # the variants 4x coarser deviate by 0.08%: the reference's own error <= 0.08% / 3
    assert text.startswith("a converged reference") and "0.027%" in text
    # a variant 0.4% away: its own error may be 0.4% / 3 > 0.1%, not converged
    name = se.Case("stepwise", "compression", s.n_strength, schedule="stepwise", relax_steps=25,
                   dim=3).name
    by_name[name]["strength"] = 200e6 * 1.004
    assert converged_text(s, lat, by_name).startswith("NOT a converged reference")
    # a missing variant: not measured
    del by_name[name]
    assert "not measured" in converged_text(s, lat, by_name)


def test_default_loading_per_test_kind():
    from bonded_lattice.conversion import rock_to_bond
    from bonded_lattice.experiment import plan_test, test_lattice
    from bonded_lattice.rocks import get_rock
    from bonded_lattice.schedules import DEFAULT_CROSSINGS_BY_TEST, default_loading

    # 3D: the papers' damping, 1000 crossings, except the elastic (30) and tension (100)
    # tests (docs/speed_error.md, part 4); 2D: one setting for every test
    assert default_loading(3, "compression") == {"crossings": 1000.0, "damping": 1.0}
    assert default_loading(3, "confined") == default_loading(3, "compression")
    assert default_loading(3, "elastic") == {"crossings": 30.0, "damping": 1.0}
    assert default_loading(3, "tension") == {"crossings": 100.0, "damping": 1.0}
    assert all(default_loading(2, t) == DEFAULT_LOADING[2]
               for t in ("elastic", "tension", "compression"))
    assert DEFAULT_CROSSINGS_BY_TEST[2] == {}
    with pytest.raises(ValueError, match="dim = 4"):
        default_loading(4, "tension")
    # plan_test's defaults are these: the same plan as with the values given explicitly
    rock = get_rock("quartzite")
    for dim in (2, 3):
        bond = rock_to_bond(rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i, 1e-3, dim)
        for test in ("elastic", "tension", "compression"):
            lat = test_lattice(dim, 4, 1e-3, test)
            assert plan_test(rock, bond, lat, test) == plan_test(rock, bond, lat, test,
                                                                 **default_loading(dim, test))


def test_cli_help_states_the_per_test_defaults():
    from bonded_lattice.cli_options import _loading_default

    assert _loading_default("crossings") == "50 in 2D, 1000 in 3D except elastic 30, tension 100"
    assert _loading_default("damping") == "0.25 in 2D, 1 in 3D"
