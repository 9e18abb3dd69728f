/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   fix lattice/nve/omp: fix lattice/nve with its loops over atoms split over
   OpenMP threads (LAMMPS' OPENMP package: `package omp N`, `-sf omp`).  The
   loops are per atom, so the results are the same bits as fix lattice/nve's.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(lattice/nve/omp,FixLatticeNVEOMP);
// clang-format on
#else

#ifndef LMP_FIX_LATTICE_NVE_OMP_H
#define LMP_FIX_LATTICE_NVE_OMP_H

#include "fix_lattice_nve.h"

namespace LAMMPS_NS {

class FixLatticeNVEOMP : public FixLatticeNVE {
 public:
  FixLatticeNVEOMP(class LAMMPS *lmp, int narg, char **arg) : FixLatticeNVE(lmp, narg, arg) {}

 protected:
  bool run_ranges(RangeFn loop, int n, const Measure &m) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
