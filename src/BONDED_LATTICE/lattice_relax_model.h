/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   What the relaxations of a central-spring network (lattice/quasistatic
   relax local and relax direct) accept, in one place: pair_style
   lattice/bond alone, without shear springs, and fixes that hold force
   components at zero (fix setforce 0.0, fix enforce2d); and which
   components those fixes hold.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_RELAX_MODEL_H
#define LMP_LATTICE_RELAX_MODEL_H

#include "lmptype.h"

#include <vector>

namespace LAMMPS_NS {

class LAMMPS;
class PairLatticeBond;

namespace LatticeRelaxModel {

  // an error naming what the relaxation `method` ("relax local") cannot
  // treat: shear springs, other force styles, fixes that add forces in a
  // minimisation; collective
  void check(LAMMPS *lmp, PairLatticeBond *pair, const char *method);

  // which force components the fixes hold at zero: each fix that acts in a
  // minimisation is given forces of 1 and then 2; a component it keeps is
  // free, one it sets to 0 both times is held, anything else is an error.
  // Returns (ID, bits) of every particle with a held component (bit k:
  // component k; z is not listed in 2D), on every rank.  Call it before a
  // force evaluation (which then recomputes what the fixes report); collective
  std::vector<tagint> held_components(LAMMPS *lmp, const char *method);

}    // namespace LatticeRelaxModel
}    // namespace LAMMPS_NS

#endif
