"""Property-based tests (hypothesis) of the Python side: for any input, the conversion,
the lattice generators and the deck writer either work and give a sensible result, or
raise a ValueError that names the offending quantity.  Never another exception, never
a non-finite number in a result or a deck."""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bonded_lattice.conversion import bond_to_rock, rock_to_bond
from bonded_lattice.decks import DeckSpec, deck_text
from bonded_lattice.lattice import close_packed_block_3d, hex_block_2d
from helpers.materials import QUARTZ

# any float, including the awkward ones
ANY = st.floats(allow_nan=True, allow_infinity=True)
# plausible magnitudes, so that valid cases are common
E = st.floats(1e6, 1e12) | ANY
NU = st.floats(-0.2, 0.5) | ANY
STRENGTH = st.floats(1e4, 1e10) | ANY
MU = st.floats(0.0, 3.0) | ANY
DIAMETER = st.floats(1e-6, 1.0) | ANY
DIM = st.sampled_from([2, 3]) | st.integers(-3, 6)
NAMES = ("E", "nu", "Tu", "Cu", "mu_i", "d", "dim", "Kn", "Ks", "Xb", "Fs0", "mu_p")
# derandomized (the same examples every run, so CI is reproducible), no example database
FAST = settings(max_examples=300, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow])
FEW = settings(max_examples=60, deadline=None, derandomize=True, database=None)


def names_a_quantity(message: str, names=NAMES) -> bool:
    return any(re.search(rf"\b{re.escape(n)}\b", message) for n in names)


@FAST
@given(E, NU, STRENGTH, STRENGTH, MU, DIAMETER, DIM)
def test_rock_to_bond_works_or_names_the_bad_value(E, nu, Tu, Cu, mu_i, d, dim):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the documented Cu caveat warns, fine
        try:
            bond = rock_to_bond(E, nu, Tu, Cu, mu_i, d, dim)
        except ValueError as exc:
            assert names_a_quantity(str(exc)), str(exc)
            return
    values = [bond.Kn, bond.Ks, bond.Xb, bond.Fs0, bond.mu_p]
    assert all(math.isfinite(v) and v >= 0.0 for v in values), values
    assert bond.Kn > 0 and bond.Xb > 0
    # and back: the closed forms are inverse to each other
    rock = bond_to_rock(bond.Kn, bond.Ks, bond.Xb, bond.Fs0, bond.mu_p, d, dim)
    for got, want in zip((rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i), (E, nu, Tu, Cu, mu_i)):
        assert got == pytest.approx(want, rel=1e-6, abs=1e-9)


@FAST
@given(st.floats(1e-3, 1e12) | ANY, st.floats(0, 1e12) | ANY, st.floats(1e-12, 1e-3) | ANY,
       st.floats(0, 1e6) | ANY, MU, DIAMETER, DIM)
def test_bond_to_rock_works_or_names_the_bad_value(Kn, Ks, Xb, Fs0, mu_p, d, dim):
    try:
        rock = bond_to_rock(Kn, Ks, Xb, Fs0, mu_p, d, dim)
    except ValueError as exc:
        assert names_a_quantity(str(exc)), str(exc)
        return
    assert all(math.isfinite(v) for v in (rock.E, rock.nu, rock.Tu, rock.Cu, rock.mu_i)), rock


@FEW
@given(st.integers(-2, 14), st.floats(1e-5, 1e-1) | ANY, st.floats(0.2, 4.0) | ANY,
       st.floats(-180, 180) | ANY)
def test_2d_blocks_work_or_name_the_bad_value(n, d, aspect, orientation):
    try:
        lattice = hex_block_2d(n, d, aspect=aspect, orientation=orientation)
    except ValueError as exc:
        assert names_a_quantity(str(exc), ("n_across", "d", "aspect", "orientation", "width",
                                           "height", "width x height")), str(exc)
        return
    assert lattice.n > 0 and np.all(np.isfinite(lattice.positions))
    if 1 < lattice.n <= 3000:        # neighbours touch: the closest pair is d apart
        p = lattice.positions / d      # in units of d: no overflow for huge d
        dist = np.sqrt(((p[:, None, :] - p[None, :, :]) ** 2).sum(-1))
        np.fill_diagonal(dist, np.inf)
        assert dist.min() == pytest.approx(1.0, rel=1e-9)


@FEW
@given(st.integers(-2, 6), st.floats(1e-5, 1e-1) | ANY, st.floats(0.2, 3.0) | ANY)
def test_3d_blocks_work_or_name_the_bad_value(n, d, aspect):
    try:
        lattice = close_packed_block_3d(n, d, aspect=aspect)
    except ValueError as exc:
        assert names_a_quantity(str(exc), ("n_y", "d", "aspect", "size_x", "size_y",
                                           "size_z")), str(exc)
        return
    assert lattice.n > 0 and np.all(np.isfinite(lattice.positions))


QUARTZ_2D = QUARTZ[2]


@FAST
@given(test=st.sampled_from(["tension", "compression", "elastic", "confined"]) | st.text(max_size=8),
       dim=DIM, d=DIAMETER, area=st.floats(1e-6, 1.0) | ANY, eta=st.floats(0, 10) | ANY,
       speed=st.floats(1e-4, 1.0) | ANY, steps=st.integers(-5, 10**7),
       dt=st.floats(1e-10, 1e-6) | ANY, schedule=st.sampled_from(["constant", "stepwise", "x"]),
       step_size=st.floats(0, 1e-6) | ANY, relax=st.integers(-3, 1000),
       confining=st.floats(0, 1e8) | ANY)
def test_deck_writer_gives_a_deck_or_names_the_bad_value(test, dim, d, area, eta, speed, steps,
                                                         dt, schedule, step_size, relax,
                                                         confining):
    try:
        spec = DeckSpec(test=test, dim=dim, d=d, bond=QUARTZ_2D, data_file="data.lattice",
                        area=area, eta=eta, speed=speed, steps=steps, dt=dt, schedule=schedule,
                        step_size=step_size, relax_steps=relax, confining=confining)
        text = deck_text(spec)
    except ValueError as exc:
        assert names_a_quantity(str(exc), ("test", "dim", "d", "area", "eta", "speed", "steps",
                                           "dt", "schedule", "step_size", "relax_steps",
                                           "confining", "thermo_every")), str(exc)
        return
    assert "pair_style      lattice/bond" in text or "pair_style lattice/bond" in text
    # no non-finite number anywhere in the deck (LAMMPS' own INF bounds are upper case)
    assert not re.search(r"\b(nan|inf)\b", text), text
