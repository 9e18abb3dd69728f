"""pair_style lattice/bond against its force-style YAML files, in the format of LAMMPS'
unittest/force-styles (tests/data/force-styles/pair-lattice_bond_*.yaml, written
by tests/force_style_yaml.py; see there for the decks and when to regenerate).

As LAMMPS' test_pair_style does: the deck, then ``run 0 post no`` (init) and
``fix 1 all nve`` + ``run 4 post no`` (run); pair energy, pair virial and the
force on every atom against the file within its epsilon, measured per value as
the harness measures (relative to the smaller of the two; run forces 5 epsilon),
on 1 rank in-process and on 2 ranks with mpirun.  lattice/bond requires newton
on, so the harness's newton-off pass becomes a check that newton off is refused.

A regression file only says that the numbers did not move.  So that it cannot
hold wrong numbers, its init part is checked against the force law computed
here from the data file (tests/force_style_yaml.py: hand_init): at the first
force evaluation no shear spring has grown, and every bond and closed contact
pushes or pulls with Kn (r - (R_i + R_j)) along the line of centres.
"""

from __future__ import annotations

import numpy as np
import pytest
import yaml  # noqa: F401  PyYAML (test extras of pyproject.toml): fail, not skip, without it
from force_style_yaml import (CONFIGS, DECKS, FOLDER, check_margins, hand_init,
                              pair_parameters, read_config, read_data_file,
                              relative_errors, run_in_process, run_mpi)


def compare(cfg, res, epsilon: float) -> dict[str, float]:
    """The largest relative error (LAMMPS' measure) of each entry; asserts each within
    epsilon (run forces within 5 epsilon, as in test_pair_style)."""
    assert len(res.init_forces) == cfg.natoms
    for stage in ("init", "run"):
        ids = getattr(res, f"{stage}_forces")[:, 0]
        assert np.array_equal(ids, getattr(cfg, f"{stage}_forces")[:, 0])
    errors = {
        "init_vdwl": relative_errors(res.init_vdwl, cfg.init_vdwl).max(),
        "init_coul": relative_errors(res.init_coul, cfg.init_coul).max(),
        "init_stress": relative_errors(res.init_stress, cfg.init_stress).max(),
        "init_forces": relative_errors(res.init_forces[:, 1:], cfg.init_forces[:, 1:]).max(),
        "run_vdwl": relative_errors(res.run_vdwl, cfg.run_vdwl).max(),
        "run_coul": relative_errors(res.run_coul, cfg.run_coul).max(),
        "run_stress": relative_errors(res.run_stress, cfg.run_stress).max(),
        "run_forces": relative_errors(res.run_forces[:, 1:], cfg.run_forces[:, 1:]).max(),
        # the per-atom energies (compute pe/atom pair) add up to the pair energy
        "run_peratom": relative_errors(res.run_peratom_sum, res.run_vdwl).max(),
    }
    for key, err in errors.items():
        limit = 5 * epsilon if key == "run_forces" else epsilon
        assert err <= limit, f"{key}: relative error {err:.3g} > {limit:g}"
    return errors


@pytest.fixture(params=CONFIGS)
def config(request):
    return request.param, read_config(FOLDER / request.param)


def test_yaml_file_is_complete(config):
    """The file holds the harness's entries, with nonzero numbers where the deck
    makes them (2D: no z forces, no zz, xz, yz virial)."""
    name, cfg = config
    dim = DECKS[name]["dim"]
    assert cfg.pair_style == "lattice/bond" and "pair lattice/bond" in cfg.prerequisites
    assert (FOLDER / cfg.input_file).is_file()
    assert cfg.init_forces.shape == cfg.run_forces.shape == (cfg.natoms, 4)
    assert cfg.init_vdwl > 0 and cfg.run_vdwl > 0 and cfg.init_coul == cfg.run_coul == 0
    nonzero = [0, 1, 3] if dim == 2 else range(6)
    assert all(cfg.init_stress[k] != 0 and cfg.run_stress[k] != 0 for k in nonzero)
    # the run moved the forces: shear springs have grown (init has none)
    assert np.max(np.abs(cfg.run_forces[:, 1:] - cfg.init_forces[:, 1:])) > \
        1e-3 * np.max(np.abs(cfg.init_forces[:, 1:]))


def test_yaml_matches_build(tmp_path, config):
    """1 rank in-process: the build reproduces the file within its epsilon."""
    _, cfg = config
    errors = compare(cfg, run_in_process(cfg, tmp_path), cfg.epsilon)
    print({k: f"{v:.2g}" for k, v in errors.items()})


@pytest.mark.mpi
def test_yaml_matches_on_2_ranks(tmp_path, config):
    """2 ranks (mpirun lmp): the same numbers within epsilon (other summation order)."""
    _, cfg = config
    errors = compare(cfg, run_mpi(cfg, tmp_path, 2), cfg.epsilon)
    print({k: f"{v:.2g}" for k, v in errors.items()})


def test_yaml_init_by_hand(config):
    """The file's init entries are the force law: sum over intact bonds and closed
    contacts of -Kn X_n n on the lower-ID particle (X_n = r - (R_i + R_j)), energy
    Kn X_n^2 / 2, virial r (x) F; bonds made beyond Xb break at once and exert
    nothing; open contacts nothing.

    Tolerance 1e-11 of the largest force (energy, virial: of their own size): this
    computation and the C++ may round r = |x_i - x_j| differently, by ~1 ulp of a
    coordinate (4e-19 m in the 3D periodic box, where this code subtracts the box
    length from x_i - x_j and LAMMPS adds it to the ghost's x_j), and X_n = r - d
    cancels: Kn * 4e-19 m against the largest force is ~1e-12.  Measured: 2D
    1.2e-16 (forces), 0 (energy), 9e-16 (virial); 3D 4e-13, 2e-13, 5e-13. Getting
    the force law wrong (the rest length from the initial distance, a shear force at
    init, a missing contact, a broken bond that still pulls) moves the numbers by
    1e-3 or more.
    """
    name, cfg = config
    spec = DECKS[name]
    counts = check_margins(cfg, spec)
    assert counts["broken"] > 0 and counts["contact"] > 0 and counts["open"] > 0
    data = read_data_file(FOLDER / spec["data"])
    periodic = [True] * 3 if spec["dim"] == 3 else [False, False, True]
    hand = hand_init(data, pair_parameters(cfg.pair_coeff, 3), periodic)
    scale = np.max(np.abs(hand["forces"]))
    assert np.array_equal(cfg.init_forces[:, 0], data["id"])
    force_err = np.max(np.abs(cfg.init_forces[:, 1:] - hand["forces"])) / scale
    energy_err = abs(cfg.init_vdwl - hand["energy"]) / hand["energy"]
    virial_err = np.max(np.abs(cfg.init_stress - hand["virial"])) / np.max(np.abs(hand["virial"]))
    print(f"{name}: {counts}; forces {force_err:.2g}, energy {energy_err:.2g}, "
          f"virial {virial_err:.2g}")
    assert force_err < 1e-11 and energy_err < 1e-11 and virial_err < 1e-11


@pytest.mark.parametrize("change", [1e-6, 1e-9])
def test_kn_change_fails(tmp_path, change):
    """The comparison can fail: Kn of the first pair_coeff line (types 1-1 and 3-3)
    changed by 1e-6 or 1e-9 relative moves init forces, energies and stress beyond
    epsilon, and the hand computation catches the 1e-6 change."""
    name = CONFIGS[0]
    cfg = read_config(FOLDER / name)
    first = cfg.pair_coeff[0].split()
    first[2] = repr(float(first[2]) * (1.0 + change))
    changed = read_config(FOLDER / name)
    changed.pair_coeff = [" ".join(first)] + cfg.pair_coeff[1:]
    res = run_in_process(changed, tmp_path)
    with pytest.raises(AssertionError):
        compare(cfg, res, cfg.epsilon)
    assert relative_errors(res.init_vdwl, cfg.init_vdwl) > 10 * cfg.epsilon
    if change >= 1e-6:
        data = read_data_file(FOLDER / DECKS[name]["data"])
        hand = hand_init(data, pair_parameters(changed.pair_coeff, 3), [False, False, True])
        assert np.max(np.abs(cfg.init_forces[:, 1:] - hand["forces"])) > \
            1e-9 * np.max(np.abs(hand["forces"]))


def test_newton_off_is_refused(tmp_path):
    """LAMMPS' harness repeats the test with newton off; lattice/bond requires newton
    on (each bond computed once, the partner's share by reverse communication) and
    says so."""
    cfg = read_config(FOLDER / CONFIGS[0])
    with pytest.raises(Exception, match="requires newton on"):
        run_in_process(cfg, tmp_path, newton="off")


def test_yaml_deck_is_the_generators(config):
    """The deck in the file is the generator's (tests/force_style_yaml.py: DECKS), so
    regenerating cannot silently change the deck."""
    import force_style_yaml as fsy

    name, committed = config
    cfg = fsy.config_from_spec(DECKS[name])
    for key in ("prerequisites", "pre_commands", "post_commands", "input_file",
                "pair_style", "pair_coeff"):
        assert getattr(cfg, key) == getattr(committed, key), key
