"""The pair style of a deck with its per-atom properties.

``pair_style lattice/bond`` takes the model's per-particle data in one of two ways:

- ``atom_style sphere``: each particle's diameter from the data file; ``atom_style
  atomic``: one diameter for all, the pair style's keyword ``diameter``;
- a heterogeneous model (:class:`bonded_lattice.grains.GrainPairOptions`): grain ids
  and stiffness factors in ``fix property/atom i_grain d_stiffness``, filled from the
  data file's ``Grains`` section (:func:`bonded_lattice.lattice.write_data`), and the
  pair style's keywords ``grain``, ``stiffness``, ``strength``, ``seed``,
  ``boundary_strength``.

The pair style sends the ghosts' grain ids and stiffness factors itself at every
reneighbouring (docs/pair_lattice_bond.rst, "Heterogeneous rock"), so ``ghost yes`` is not
needed for it; the decks keep it, so the fix's ghost copies are current for any other
command too.  The pair style's keywords may come in any order.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..conversion import BondParameters
from ..grains import GrainPairOptions

SHEAR_FRAMES = ("fixed", "corotational")    # pair_style lattice/bond shear_frame
PROPERTY_FIX = "grains"                     # ID of the fix property/atom of the grain data


@dataclass(frozen=True)
class PairStyle:
    """``pair_style lattice/bond`` and ``pair_coeff`` of one deck.

    bond: the bond parameters (``pair_coeff * *``); d: the particle diameter (m), given
    to the pair style when the atom style carries none (``atomic``); grains: the
    heterogeneous model's keywords, or None (homogeneous); shear_frame: one of
    :data:`SHEAR_FRAMES` (the papers': fixed, the default, which is not written).
    """

    bond: BondParameters
    d: float
    atom_style: str = "sphere"
    grains: GrainPairOptions | None = None
    shear_frame: str = "fixed"

    def __post_init__(self) -> None:
        if self.shear_frame not in SHEAR_FRAMES:
            raise ValueError(f"shear_frame = {self.shear_frame!r} is not known: use one of "
                             f"{', '.join(SHEAR_FRAMES)}")

    def keywords(self) -> str:
        """The pair style's keywords, each with a leading space ('' for none)."""
        args = ""
        if self.grains is not None:
            args += " " + self.grains.pair_style_args()
        if self.atom_style == "atomic":    # no per-atom diameter: one for every particle
            args += f" diameter {self.d!r}"
        if self.shear_frame != "fixed":
            args += " shear_frame " + self.shear_frame
        return args

    def read_data(self, data_file: str) -> str:
        """``read_data``, after the fix that takes the data file's Grains section."""
        if self.grains is None:
            return f"read_data       {data_file}\n"
        what = ("grain id, stiffness and strength factors" if self.grains.particle_strength
                else "grain id and stiffness factor")
        return (f"# {what} per particle, from the data file's Grains "
                "section\n# (the pair style sends the ghosts' values itself at every "
                "reneighbouring; ghost yes,\n# which it does not need, keeps the fix's ghost "
                "copies current for other commands)\n"
                f"fix             {PROPERTY_FIX} all property/atom {self.grains.properties()} "
                "ghost yes\n"
                f"read_data       {data_file} fix {PROPERTY_FIX} NULL Grains\n")

    def text(self) -> str:
        """``pair_style`` and ``pair_coeff``, with a comment on the heterogeneity."""
        note = ""
        g = self.grains
        if g is not None:
            strength = (f"{g.strength_min:g}" if g.strength_min == g.strength_max
                        else f"uniform in [{g.strength_min:g}, {g.strength_max:g})")
            mean = " x the mean of its particles' d_strength," if g.particle_strength else ""
            note = ("# heterogeneity: a bond's stiffness factor is the mean of its particles'; "
                    f"its strength\n# factor is {strength},{mean} x {g.boundary_strength:g} "
                    "across grain boundaries\n")
        return f"{note}pair_style      lattice/bond{self.keywords()}\n{self.bond.pair_coeff()}\n"
