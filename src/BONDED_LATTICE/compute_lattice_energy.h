/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   compute lattice/energy: the energy budget of Liu et al. (2017): elastic,
   kinetic and gravitational energy, viscous, breaking and frictional heat,
   external work, their total and the balance error.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(lattice/energy,ComputeLatticeEnergy);
// clang-format on
#else

#ifndef LMP_COMPUTE_LATTICE_ENERGY_H
#define LMP_COMPUTE_LATTICE_ENERGY_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputeLatticeEnergy : public Compute {
 public:
  ComputeLatticeEnergy(class LAMMPS *, int, char **);
  ~ComputeLatticeEnergy() override;
  void init() override;
  void compute_vector() override;

  // elastic + kinetic + gravitational energy now, summed over ranks (collective)
  double stored_energy();

 private:
  std::string fix_id;
  class FixLatticeEnergy *fix;
  double values[10];

  void stored_parts(double *parts);    // [0] elastic, [1] kinetic, [2] gravitational
};

}    // namespace LAMMPS_NS

#endif
#endif
