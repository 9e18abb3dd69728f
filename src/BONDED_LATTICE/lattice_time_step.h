/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The time step of pair_style lattice/bond: the critical time step of the
   bonded lattice, reported at the start of each run (check), and the stop
   of an unstable integration, a particle that moves more than a tenth of
   the smallest radius in one step (step_limit, report_instability).
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_TIME_STEP_H
#define LMP_LATTICE_TIME_STEP_H

#include "lattice_comm.h"
#include "pointers.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixLatticeBondStore;
class PairLatticeBond;

class LatticeTimeStep : protected Pointers, public LatticeReversePart {
 public:
  explicit LatticeTimeStep(LAMMPS *lmp) : Pointers(lmp), dt_critical(0.0) {}

  // the longest step along an axis that is not an instability, for particles
  // whose smallest radius is min_radius
  static double step_limit(double min_radius);
  // the critical time step of the pair's records, logged with a warning if
  // the time step is above its safety fraction; collective
  void check(const PairLatticeBond &pair, LatticeCommCarrier &carrier);
  // the message that local atom i moved more than step_limit(min_radius) in this step
  std::string instability_message(const FixLatticeBondStore *store, int i,
                                  double min_radius) const;
  // stop with that message, found by this rank alone (lattice_error_one)
  [[noreturn]] void report_instability(const FixLatticeBondStore *store, int i,
                                       double min_radius) const;
  // during a run: stop if a particle moved more than step_limit(min_radius)
  // in this step (the displacements formed now); collective
  void stop_if_unstable(FixLatticeBondStore *store, double min_radius) const;

  int pack_reverse(int n, int first, double *buf) override;
  void unpack_reverse(int n, const int *list, const double *buf) override;

 private:
  double dt_critical;                 // see check()
  std::vector<double> stiffness_sum;  // per particle (local and ghost), for check()
};

}    // namespace LAMMPS_NS

#endif
