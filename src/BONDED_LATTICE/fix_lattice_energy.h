/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   fix LATTICE/ENERGY: internal fix of compute lattice/energy.  It finds the
   energy sources (LatticeEnergySource: pair lattice/bond, fix lattice/viscous,
   fix lattice/wall) and switches their heat and work tallies on, integrates
   the work done on groups whose motion is prescribed, and keeps the
   accounting's totals and starting energy in restart files.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(LATTICE/ENERGY,FixLatticeEnergy);
// clang-format on
#else

#ifndef LMP_FIX_LATTICE_ENERGY_H
#define LMP_FIX_LATTICE_ENERGY_H

#include "fix_lattice_atom_history.h"
#include "lattice_energy_source.h"

#include <set>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixLatticeEnergy : public FixLatticeAtomHistory {
 public:
  // tallies, in the order of compute lattice/energy's vector elements 4-8
  static constexpr int NTALLY = LatticeEnergySource::NTALLY;

  FixLatticeEnergy(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void set_arrays(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // the tallies since the accounting started, summed over all ranks
  void totals(double *out);
  // the total energy when the accounting started, and whether it has
  bool started() const { return start_set; }
  double start_energy() const { return energy0; }
  // the energy sources (the pair style first, then fixes in the order of
  // their definition) and the gravity fixes, found at init()
  const std::vector<LatticeEnergySource *> &sources() const { return energy_sources; }
  const std::vector<class Fix *> &gravity_fixes() const { return gravity; }

 protected:
  std::string compute_id;            // the compute lattice/energy that owns this fix
  int workbit;                       // union of the work groups' bits
  std::vector<std::string> work_groups;
  std::vector<LatticeEnergySource *> energy_sources;
  std::vector<class Fix *> gravity;

  double carried[NTALLY];    // totals brought in by a restart file
  double base[NTALLY];       // this rank's raw tallies when counting began
  double group_work;         // this rank's work on the prescribed groups
  double group_ke_prev;      // this rank's kinetic energy of the groups at the last step
  int need_base;             // take the raw tallies as the base at the next setup
  int start_set;
  double energy0;

  std::set<std::string> warned;    // fixes already named by warn_uncounted()

  void raw(double *local);    // this rank's raw tallies of all sources
  double group_kinetic() const;
  void warn_uncounted();
};

}    // namespace LAMMPS_NS

#endif
#endif
