/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Base class for fixes that keep a fixed number of doubles per atom which
   must follow the atom through sorting, migration and restart files
   (fix lattice/viscous, fix lattice/wall).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_LATTICE_ATOM_HISTORY_H
#define LMP_FIX_LATTICE_ATOM_HISTORY_H

#include "fix.h"

namespace LAMMPS_NS {

class FixLatticeAtomHistory : public Fix {
 public:
  FixLatticeAtomHistory(class LAMMPS *, int, char **);
  ~FixLatticeAtomHistory() override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

 protected:
  int nvalues;      // doubles per atom
  double **hist;    // nmax x nvalues

  // derived constructors call this once they know nvalues; it also
  // initialises the local atoms with set_arrays()
  void create_history(int n);
};

}    // namespace LAMMPS_NS

#endif
