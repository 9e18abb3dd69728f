/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   pair_style lattice/bond/omp: the force loop of pair_style lattice/bond on
   OpenMP threads (LAMMPS' OPENMP package: `package omp N`, `-sf omp`).  Each
   thread runs the same compiled loop (pair_lattice_bond_eval.h) over its own
   range of particles, whose records it alone updates, and adds forces into
   its own copy of the force array, which LAMMPS' ThrOMP sums.  Everything
   else (bond creation, displacements, communication) is the serial style's.
   Forces equal the serial style's to round-off (the threads' sums are added
   in another order).
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(lattice/bond/omp,PairLatticeBondOMP);
// clang-format on
#else

#ifndef LMP_PAIR_LATTICE_BOND_OMP_H
#define LMP_PAIR_LATTICE_BOND_OMP_H

#include "pair_lattice_bond.h"
#include "thr_omp.h"

#include <vector>

namespace LAMMPS_NS {

class PairLatticeBondOMP : public PairLatticeBond, public ThrOMP {
 public:
  PairLatticeBondOMP(class LAMMPS *);
  void compute(int, int) override;
  double memory_usage() override;

 protected:
  void run_force_loop() override;

 private:
  int eflag_step, vflag_step;         // this compute()'s flags, for the threads' tallies
  std::vector<double> thread_heat;    // 3 heat sums per thread, added in thread order

  // what a thread's loop tallies: energy/virial into its ThrData, heat into its sums
  struct ThreadTally {
    PairLatticeBondOMP *style;
    ThrData *thr;
    double *heat_sums;
    void pair(int i, int j, int nlocal, double e, double fx, double fy, double fz, double dx,
              double dy, double dz)
    {
      style->ev_tally_xyz_thr(style, i, j, nlocal, 1, e, 0.0, fx, fy, fz, dx, dy, dz, thr);
    }
    void heat(double break_normal, double break_shear, double friction)
    {
      heat_sums[0] += break_normal;
      heat_sums[1] += break_shear;
      heat_sums[2] += friction;
    }
  };
  using ThreadFn = void (PairLatticeBondOMP::*)(int, int, int, ThrData *);
  template <int F> void eval_thread(int ifrom, int ito, int tid, ThrData *thr);
  template <std::size_t... I>
  static constexpr std::array<ThreadFn, sizeof...(I)> make_thread_table(std::index_sequence<I...>);
  static const std::array<ThreadFn, LB_NFEATURES> THREAD_TABLE;
};

}    // namespace LAMMPS_NS

#endif
#endif
