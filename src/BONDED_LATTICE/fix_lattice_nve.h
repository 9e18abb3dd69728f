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
#include "lattice_group_runs.h"

#include <limits>
#include <vector>

namespace LAMMPS_NS {

class FixLatticeNVE : public Fix {
 public:
  FixLatticeNVE(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void reset_dt() override;

 protected:
  double dtv, dtf;
  // dtf / mass of each atom type (per-type masses): the same quotient fix nve
  // forms per atom, formed once per run instead of once per atom and step
  std::vector<double> dtfm_type;
  bool one_mass = false;    // per-type masses, all equal

  // dt/2 / m of per-atom masses: the quotient fix nve forms per atom, formed
  // again only when the mass differs from the last atom's (the same bits; a
  // block of equal particles divides once per loop instead of once per atom)
  struct MassQuotient {
    double dtf;
    double mass = std::numeric_limits<double>::quiet_NaN();    // equal to no mass
    double quotient = 0.0;
    double of(double m)
    {
      if (!(m == mass)) {
        mass = m;
        quotient = dtf / m;
      }
      return quotient;
    }
  };

  // the steps' measurement for the record store (drift with a measuring store)
  struct Measure {
    double *disp = nullptr;    // the store's displacement array (3 per atom)
    double cap = 0.0;          // longest step that is not an instability
  };
  // a loop over the atoms begin..end-1; false if a measured step exceeded the cap
  using RangeFn = bool (FixLatticeNVE::*)(int begin, int end, const Measure &m);
  // PLANAR: x and y only; ALL: group all, no mask test; RMASS: per-atom
  // mass; DRIFT: also x += dt v (initial_integrate)
  template <bool PLANAR, bool ALL, bool RMASS, bool DRIFT> bool kick(int, int, const Measure &);
  void dispatch(bool drift);
  // runs the loop over atoms 0..n-1: in one range here, in one per thread in
  // fix lattice/nve/omp (the loops are per atom, so the results are the same bits)
  virtual bool run_ranges(RangeFn loop, int n, const Measure &m);

  // a group that is not all, as runs of consecutive atoms (never for a dynamic
  // group: its masks change between steps); over_runs runs the group-all loop
  // run_loop over each run within its range, the same arithmetic per atom
  // without the mask test
  LatticeGroupRuns group_runs;
  RangeFn run_loop = nullptr;
  bool over_runs(int begin, int end, const Measure &m);

  // the record store whose displacements the drift measures (see measuring_store)
  class FixLatticeBondStore *store;
  class FixLatticeBondStore *measuring_store() const;
  template <bool PLANAR, bool ALL, bool RMASS> bool drift_measured(int, int, const Measure &);
  template <bool DRIFT, bool MEASURE> bool stream(int, int, const Measure &);
  double step_cap() const;    // longest step that is not an instability
};

}    // namespace LAMMPS_NS

#endif
#endif
