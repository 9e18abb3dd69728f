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

#include "fix_lattice_atom_history.h"
#include "lattice_energy_source.h"
#include "lattice_group_runs.h"

namespace LAMMPS_NS {

class FixLatticeViscous : public FixLatticeAtomHistory, public LatticeEnergySource {
 public:
  FixLatticeViscous(class LAMMPS *, int, char **);
  int setmask() override;
  void setup(int) override;
  void post_force(int) override;
  void post_run() override;

  void set_arrays(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // energy accounting (LatticeEnergySource): the heat dissipated on this rank
  // (VISCOUS); the damping stores no energy
  void enable_energy_tallies(bool on) override { tally_flag = on ? 1 : 0; }
  void add_energy_tallies(double *tally) const override { tally[VISCOUS] += heat; }
  double elastic_energy() override { return 0.0; }

 protected:
  double eta;         // damping coefficient, force/velocity
  int tally_flag;
  double heat;        // work of the damping forces, trapezoidal rule, sign flipped
  // hist[i][0..2]: damping force of the last step, reapplied by setup()
  int fdamp_valid;    // 1 once fdamp holds a step's force

  // a group that is not all in runs of consecutive atoms (LatticeGroupRuns)
  LatticeGroupRuns group_runs;

  void damp(bool step_taken);
  template <int DIM, bool ALL, bool KEEP> void damp_components(bool step_taken);
};

}    // namespace LAMMPS_NS

#endif
#endif
