/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Base class for fixes that keep a fixed number of doubles per atom which
   must follow the atom through sorting, migration and restart files
   (fix lattice/viscous, fix lattice/wall).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_LATTICE_ATOM_HISTORY_H
#define LMP_FIX_LATTICE_ATOM_HISTORY_H

#include "domain.h"
#include "lammps_api_compat.h"
#include "fix.h"

#include <cmath>

namespace LAMMPS_NS {

// remove a periodic jump from a one-step displacement d.  Per atom and step
// Domain::minimum_image is costly here: its FLERR argument becomes a
// std::string that allocates on every call (about a third of a 2D
// compression run's instructions); orthogonal boxes take the direct test
inline void lattice_unwrap_step(Domain *domain, double *d)
{
  if (domain->triclinic) {
    lattice_minimum_image(domain, d);
    return;
  }
  if (domain->xperiodic && std::fabs(d[0]) > 0.5 * domain->xprd)
    d[0] -= std::copysign(domain->xprd, d[0]);
  if (domain->yperiodic && std::fabs(d[1]) > 0.5 * domain->yprd)
    d[1] -= std::copysign(domain->yprd, d[1]);
  if (domain->zperiodic && std::fabs(d[2]) > 0.5 * domain->zprd)
    d[2] -= std::copysign(domain->zprd, d[2]);
}

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
  int nvalues;     // doubles per atom
  // nmax x nvalues in one block: no row pointers (8 bytes per atom less
  // than a LAMMPS 2D array)
  double *hist;
  double *history(int i) const { return hist + (bigint) i * nvalues; }

  // derived constructors call this once they know nvalues; it also
  // initialises the local atoms with set_arrays()
  void create_history(int n);

  // remove a periodic jump from a one-step displacement (see lattice_unwrap_step)
  void unwrap_step(double *d) const { lattice_unwrap_step(domain, d); }
};

}    // namespace LAMMPS_NS

#endif
