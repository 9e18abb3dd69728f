/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   fix lattice/viscous: the papers' artificial viscosity F = -eta v.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(lattice/viscous,FixLatticeViscous);
// clang-format on
#else

#ifndef LMP_FIX_LATTICE_VISCOUS_H
#define LMP_FIX_LATTICE_VISCOUS_H

#include "fix.h"

namespace LAMMPS_NS {

class FixLatticeViscous : public Fix {
 public:
  FixLatticeViscous(class LAMMPS *, int, char **);
  int setmask() override;
  void setup(int) override;
  void post_force(int) override;

 protected:
  double eta;    // damping coefficient, force/velocity
};

}    // namespace LAMMPS_NS

#endif
#endif
