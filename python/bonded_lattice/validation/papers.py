"""Every number the validation compares with, as the papers state it, and where.

Liu, Pollard & Shi (2013), J. Geophys. Res. 118 (2D, quartz) and Liu et al. (2017), Comput.
Geotech. (3D, quartzite with the same properties).  Relative errors are measured minus
formula over formula; docs/theory.md, "The papers' numerical results", derives the formulas
the errors refer to.  Each entry: the value and the place in the paper that states it.
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = ["PAPER", "PaperValue", "paper_value"]


class PaperValue(NamedTuple):
    value: float
    source: str


PAPER: dict[str, PaperValue] = {
    # 2013, 2D
    "2d.unit.Tu": PaperValue(-0.0003, "Liu 2013, para. 50: one unit 0.03% below"),
    "2d.unit.Cu": PaperValue(-0.0098, "Liu 2013, para. 50: one unit 0.98% below"),
    "2d.multi.Tu": PaperValue(-0.043, "Liu 2013, para. 51: mean of the six multi-unit "
                                      "lattices (18-16611 particles) 4.3% below"),
    "2d.multi.Cu": PaperValue(-0.222, "Liu 2013, para. 51: mean of the six multi-unit "
                                      "lattices 22.2% below"),
    "2d.n30.Tu": PaperValue(-0.033, "Liu 2013, para. 54: the 1033-particle block 3.3% below"),
    "2d.n4.E": PaperValue(-0.03, "Liu 2013, para. 45: 18 particles, E about 3% low "
                                 "(small strain)"),
    "2d.unit.E_1e-3": PaperValue(-0.00034, "Liu 2013, para. 47: one unit at strain -1e-3, "
                                           "E 0.034% low"),
    "2d.unit.nu_1e-3": PaperValue(0.00084, "Liu 2013, para. 47: one unit at strain -1e-3, "
                                           "nu 0.084% high"),
    "2d.unit.Cu_strain": PaperValue(3.17e-3, "Liu 2013, para. 50: failure strain of the "
                                             "unit's Cu test"),
    "2d.unit.Tu_strain": PaperValue(2.71e-4, "Liu 2013, para. 50: failure strain of the "
                                             "unit's Tu test"),
    "2d.anisotropy.direction_deg": PaperValue(
        90.0, "Liu 2013, para. 55: the formulas are validated with the load vertical, at 90 "
              "degrees to the close-packed rows (by the unit's symmetry also at 30 and 150); "
              "E and Tu 'a bit lower along other directions'"),
    "2d.elastic.strain_constant": PaperValue(
        1e-3, "Liu 2013, para. 46: the elastic properties almost keep constant values while the "
              "strain magnitude is below 1e-3, and change significantly beyond it"),
    "2d.n30.particles": PaperValue(1033, "Liu 2013, Fig. 7 caption: the compressed lattice of "
                                         "1033 particles, 30 across"),
    # 2017, 3D
    "3d.elastic.strain_growth": PaperValue(
        1e-3, "Liu 2017, section 5.2 (Fig. 4a): the error of Young's modulus is greater when "
              "the strain exceeds 1e-3"),
    "3d.n12.elements": PaperValue(2166, "Liu 2017, Fig. 5 caption: compressive strength test "
                                        "of a cubic model with 2166 elements"),
    "3d.unit.Tu": PaperValue(-0.00011, "Liu 2017, section 5.2: one unit 0.011% below"),
    "3d.unit.Cu": PaperValue(-0.0173, "Liu 2017, section 5.2: one unit 1.73% below"),
    "3d.multi.Tu": PaperValue(-0.0889, "Liu 2017, section 5.2: mean of the multi-unit "
                                       "models 8.89% below"),
    "3d.multi.elastic": PaperValue(0.006, "Liu 2017, section 5.2: for models with multiple "
                                          "units the elastic properties err by about 0.6% on "
                                          "average at strains from -1e-6 to -1e-3"),
    "3d.multi.Cu": PaperValue(-0.1851, "Liu 2017, section 5.2: mean of the multi-unit "
                                       "models 18.51% below"),
    "3d.energy.tension.peak_kinetic": PaperValue(
        0.162, "Liu 2017, section 5.3: maximum kinetic energy 16.2% of the total energy, "
               "tension test of the 2166-element model"),
    "3d.energy.tension.duration_s": PaperValue(
        2.83e-6, "Liu 2017, section 5.3 (Fig. 6d): breaking heat rises from D1 to D2 "
                 "in 2.83e-6 s"),
    "3d.energy.tension.width_m": PaperValue(0.012, "Liu 2017, section 5.3: the model is "
                                                   "1.2 cm in width"),
    "3d.energy.tension.crack_speed": PaperValue(4240.0, "Liu 2017, section 5.3: the opening "
                                                        "crack runs at about 4240 m/s"),
    "3d.energy.tension.failure_time_s": PaperValue(
        1.072e-2, "Liu 2017, section 5.3 (Fig. 6b): the model breaks in two at 1.072e-2 s"),
    "3d.energy.tension.frictional_heat": PaperValue(
        0.0, "Liu 2017, section 5.3: there is no slipping when the model splits into two "
             "halves in the Tu test, so the frictional heat is always zero"),
    "3d.energy.elements": PaperValue(2166.0, "Liu 2017, section 5.3: the cubic model with "
                                             "2166 elements (12 along y) of the energy tests"),
    "3d.schedule.tension.step_m": PaperValue(
        1.7e-10, "Liu 2017, section 5.1: boundary displacement 1.70e-10 m in each tensile step "
                 "(tests of tensile strength)"),
    "3d.schedule.compression.step_m": PaperValue(
        1.7e-9, "Liu 2017, section 5.1: boundary displacement 1.70e-9 m in each compressive "
                "step (tests of compressive strength)"),
    "3d.schedule.relax_steps": PaperValue(100.0, "Liu 2017, section 5.1: after each step the "
                                                 "model is run for 100 time steps"),
    "3d.schedule.dt_s": PaperValue(1e-8, "Liu 2017, section 5.1: the time step is 1e-8 s"),
    "3d.energy.compression.failure_duration_s": PaperValue(
        1e-4, "Liu 2017, section 5.3 (Fig. 6a inset): the failure takes about 1e-4 s"),
}


def paper_value(key: str) -> float:
    """The value of :data:`PAPER` ``key``; a KeyError naming the known keys otherwise."""
    try:
        return PAPER[key].value
    except KeyError:
        raise KeyError(f"no paper value {key!r}: known are {', '.join(sorted(PAPER))}") from None
