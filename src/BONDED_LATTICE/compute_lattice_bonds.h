/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   compute lattice/bonds: bond and contact counts of pair_style lattice/bond.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(lattice/bonds,ComputeLatticeBonds);
// clang-format on
#else

#ifndef LMP_COMPUTE_LATTICE_BONDS_H
#define LMP_COMPUTE_LATTICE_BONDS_H

#include "compute.h"
#include "fix_lattice_bond_store.h"

namespace LAMMPS_NS {

class ComputeLatticeBonds : public Compute {
 public:
  ComputeLatticeBonds(class LAMMPS *, int, char **);
  ~ComputeLatticeBonds() override;
  void init() override;
  void compute_vector() override;
  void compute_peratom() override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

 private:
  class PairLatticeBond *pair;
  double counts[4];
  LatticeBondState peratom_state;    // bond state counted per atom (intact by default)
  int nmax;
  double *intact_per_atom;    // per-atom counts of bonds in peratom_state
};

}    // namespace LAMMPS_NS

#endif
#endif
