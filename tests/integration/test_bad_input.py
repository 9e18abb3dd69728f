"""Bad input stops with an error that names the bad value and the valid range."""

from __future__ import annotations

import pytest
from helpers.decks import TOUCHING_TRIANGLE, atoms_at, opening, pair_lines, run_deck, sphere_props
from helpers.materials import QUARTZ, QUARTZ_2D, coeffs

SPHERE = sphere_props()
GOOD = QUARTZ_2D
TAIL = "fix 1 all nve\ntimestep 1e-8\nrun 10\n"


def deck(pair_lines: str, atom_style: str = "sphere", newton: str = "on", extra: str = "",
         setup: str = SPHERE) -> str:
    return (opening(types=2, atom_style=atom_style, newton=newton) + TOUCHING_TRIANGLE + setup
            + pair_lines + extra + TAIL)


def pair(c11: str = GOOD, c12: str = GOOD, c22: str = GOOD, style: str = "") -> str:
    return pair_lines({"1 1": c11, "1 2": c12, "2 2": c22}, style)


CASES = {
    "negative Kn": (pair(c12=coeffs(QUARTZ[2], Kn=-1)),
                    ["Kn = -1", "need Kn > 0"]),
    "negative Ks": (pair(c11=coeffs(QUARTZ[2], Ks=-5)),
                    ["Ks = -5", "need Ks >= 0"]),
    "zero Xb": (pair(c22=coeffs(QUARTZ[2], Xb=0)), ["Xb = 0", "need Xb > 0"]),
    "negative Xb": (pair(c22=coeffs(QUARTZ[2], Xb=-1e-7)),
                    ["Xb = -1e-07", "need Xb > 0"]),
    "negative Fs0": (pair(c11=coeffs(QUARTZ[2], Fs0=-1)),
                     ["Fs0 = -1", "need Fs0 >= 0"]),
    "negative mu_p": (pair(c11=coeffs(QUARTZ[2], mu_p=-0.1)),
                      ["mu_p = -0.1", "need mu_p >= 0"]),
    "too few coefficients": (pair(c11=" ".join(GOOD.split()[:2])), ["I J Kn Ks Xb Fs0 mu_p", "got 4"]),
    "unknown pair_coeff keyword": (pair(c11=GOOD + " glue yes"), ["unknown keyword glue"]),
    "missing pair_coeff": (pair(c12=None), ["pair_coeff 1 2 is missing"]),
    "no pair_coeff at all": ("pair_style lattice/bond\n", ["pair_coeff 1 1 is missing"]),
    "tolerance out of range": (pair(style="tolerance 0.5"),
                               ["tolerance 0.5 is out of range", "0 <= tolerance < 0.4"]),
    "maxslot out of range": (pair(style="maxslot 0"), ["maxslot 0 is out of range", "1 <= maxslot <= 64"]),
    "unknown pair_style keyword": (pair(style="damping 3"), ["Unknown pair_style lattice/bond keyword damping",
                                                            "shear_frame"]),
    "unknown shear frame": (pair(style="shear_frame rigid"),
                            ["shear_frame rigid is not valid", "use fixed or corotational"]),
    "shear frame without value": (pair(style="maxslot 8 shear_frame"),
                                  ["keyword shear_frame needs a value"]),
    "cutoff shorter than bonds": (pair(style="cutoff 0.0005"),
                                  ["cutoff 0.0005 is too small", "use cutoff >= 0.00101"]),
    # atom_style atomic needs the diameter keyword (tests/integration/test_atomic_style.py)
    "atomic style without diameter": ("", ["atom_style atomic has no per-atom diameter",
                                           "keyword diameter"]),
    "newton off": (pair(), ["requires newton on"]),
    "viscous eta negative": (pair() + "fix v all lattice/viscous -3\n", ["eta = -3", "need eta >= 0"]),
    "wall bad face": (pair() + "fix w all lattice/wall top 0 1 1 0\n", ["face top is not valid"]),
    "wall face z in 2d": (pair() + "fix w all lattice/wall zlo 0 1 1 0\n", ["not allowed in a 2d"]),
    "wall negative Kn": (pair() + "fix w all lattice/wall ylo 0 -1 1 0\n", ["Kn = -1", "need Kn > 0"]),
    "wall negative mu": (pair() + "fix w all lattice/wall ylo 0 1 1 -0.2\n", ["mu = -0.2", "need mu >= 0"]),
    "lattice/nve with an argument": (pair() + "fix n all lattice/nve 1.0\n",
                                     ["Illegal fix lattice/nve command", "got 1 more"]),
    "too many records": (pair(style="maxslot 1"), ["more than maxslot = 1", "increase"]),
}


@pytest.mark.parametrize("name", list(CASES))
def test_bad_input_is_rejected_with_named_value(tmp_path, name):
    lines, expected = CASES[name]
    kwargs = {}
    if name == "atomic style without diameter":
        kwargs = dict(atom_style="atomic", setup="mass * 1.0\n")
        lines = pair()
    if name == "newton off":
        kwargs = dict(newton="off")
    res = run_deck(deck(lines, **kwargs), tmp_path)
    assert res.returncode != 0, f"{name}: the run did not stop\n{res.output[-1500:]}"
    for fragment in expected:
        assert fragment in res.output, f"{name}: {fragment!r} missing in\n{res.output[-1500:]}"
    assert "Step" not in res.output or "ERROR" in res.output


# two particles 1 mm apart
LOST_PARTNER = opening() + atoms_at([(-0.0005, 0), (0.0005, 0)]) + sphere_props(mass=1.0) + """\
# a weak, unbreakable bond: the particles fly apart and stay bonded
""" + pair_lines({"1 1": "1.0 0.0 1.0 0.0 0.0"}) + """\
neighbor 1e-4 bin
velocity all set 0 0 0 units box
set atom 1 vx -10
set atom 2 vx 10
fix 1 all nve
timestep 1e-6
run 200
"""

@pytest.mark.parametrize("np_", [1, 2])
def test_bond_longer_than_ghost_cutoff_is_an_error(tmp_path, np_):
    # whether or not the partner is still on the same rank, an intact bond
    # longer than the communication cutoff stops the run: the outcome must not
    # depend on the number of ranks
    res = run_deck(LOST_PARTNER, tmp_path, np=np_)
    assert res.returncode != 0
    assert "bond 1-2 is" in res.output and "beyond the communication cutoff" in res.output
    assert "raise neighbor skin or comm_modify cutoff" in res.output


# two pairs of touching particles, far apart
RENUMBER = (opening() + atoms_at([(-0.005, 0), (-0.004, 0), (0.004, 0), (0.005, 0)])
            + sphere_props(mass=1.0) + pair_lines({"1 1": "1.0e6 1.0e5 1.0e-4 1.0 0.1"}) + """\
neighbor 1e-4 bin
fix 1 all nve
run 1
group one id 1
delete_atoms group one compress yes
run 1
""")

def test_renumbered_atoms_are_detected(tmp_path):
    # bonds 1-2 and 3-4; deleting atom 1 renumbers 3 -> 2 and 4 -> 3, so the
    # record "3-4" now names a partner that no longer exists: stop, do not guess
    res = run_deck(RENUMBER, tmp_path)
    assert res.returncode != 0
    assert "lost its partner" in res.output
    assert "renumbered" in res.output
