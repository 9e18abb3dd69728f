/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   fix lattice/nve: velocity Verlet for the particles' translations,
   compiled for 2D (x and y only) and 3D.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(lattice/nve,FixLatticeNVE);
// clang-format on
#else

#ifndef LMP_FIX_LATTICE_NVE_H
#define LMP_FIX_LATTICE_NVE_H

#include "fix.h"

#include <vector>

namespace LAMMPS_NS {

class FixLatticeNVE : public Fix {
 public:
  FixLatticeNVE(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void reset_dt() override;

 protected:
  double dtv, dtf;
  // dtf / mass of each atom type (per-type masses): the same quotient fix nve
  // forms per atom, formed once per run instead of once per atom and step
  std::vector<double> dtfm_type;
  bool one_mass = false;    // per-type masses, all equal

  // PLANAR: x and y only; ALL: group all, no mask test; RMASS: per-atom
  // mass; DRIFT: also x += dt v (initial_integrate)
  template <bool PLANAR, bool ALL, bool RMASS, bool DRIFT> void kick();
  void dispatch(bool drift);

  // the record store whose displacements the drift measures (see measuring_store)
  class FixLatticeBondStore *store;
  class FixLatticeBondStore *measuring_store() const;
  template <bool PLANAR, bool RMASS> void drift_measured();
  template <bool DRIFT, bool MEASURE> void stream();
  double step_cap() const;    // longest step that is not an instability
};

}    // namespace LAMMPS_NS

#endif
#endif
