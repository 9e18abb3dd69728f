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
  ~FixLatticeViscous() override;
  int setmask() override;
  void setup(int) override;
  void post_force(int) override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  double memory_usage() override;

 protected:
  double eta;         // damping coefficient, force/velocity
  double **fdamp;     // damping force of the last step, reapplied by setup()
  int fdamp_valid;    // 1 once fdamp holds a step's force
};

}    // namespace LAMMPS_NS

#endif
#endif
