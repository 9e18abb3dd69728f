/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   compute lattice/bond/local: per-bond values of pair_style lattice/bond
   (IDs, state, position, forces, the bond's own parameters and how close it
   is to breaking) for dump local, compute reduce and analysis.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(lattice/bond/local,ComputeLatticeBondLocal);
// clang-format on
#else

#ifndef LMP_COMPUTE_LATTICE_BOND_LOCAL_H
#define LMP_COMPUTE_LATTICE_BOND_LOCAL_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeLatticeBondLocal : public Compute {
 public:
  ComputeLatticeBondLocal(class LAMMPS *, int, char **);
  ~ComputeLatticeBondLocal() override;
  void init() override;
  void compute_local() override;
  double memory_usage() override;

 private:
  enum Value { ID1, ID2, STATE, DIST, X, Y, Z, FN, FS, KN, FB, FS0, RATIO };
  std::vector<int> values;
  class PairLatticeBond *pair;
  int nmax;                 // rows allocated
  double *vlocal;           // one value
  double **alocal;          // several values
};

}    // namespace LAMMPS_NS

#endif
#endif
