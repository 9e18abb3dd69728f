/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The geometry of a pair of particles, in one place: their radii (per atom,
   or one for all with the pair_style keyword diameter), the rest length
   r_i + r_j of a bond between them (where the lattice model's particles
   touch) and their separation.  The pair style's record lifecycle, its
   query API and compute lattice/bonds use these; the force loop forms the
   same expressions in batches (pair_lattice_bond_kernel.cpp).

   The order of operations is part of the results (-ffp-contract=off):
   every caller gets the bits it had when it spelled the expressions out.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_BOND_GEOMETRY_H
#define LMP_LATTICE_BOND_GEOMETRY_H

#include <cmath>

namespace LAMMPS_NS {

// the particles' radii: per atom (atom_style sphere), or D/2 for all with the
// keyword diameter D (atom styles without per-atom radius).  Loops fetch the
// radii once (PairLatticeBond::radii()): the pointer test inside is then the
// same for every particle
struct LatticeRadii {
  const double *per_atom;    // atom->radius, or nullptr
  double all;                // every particle's radius when per_atom is null
  double operator[](int i) const { return per_atom ? per_atom[i] : all; }
  // the rest length of a bond between particles i and j: r_i + r_j
  double touch(int i, int j) const { return (*this)[i] + (*this)[j]; }
};

// the separation r_i - r_j of particles i and j and its squared length
struct PairSeparation {
  double dx, dy, dz, rsq;
  double length() const { return sqrt(rsq); }
};

inline PairSeparation pair_separation(double **x, int i, int j)
{
  PairSeparation d;
  d.dx = x[i][0] - x[j][0];
  d.dy = x[i][1] - x[j][1];
  d.dz = x[i][2] - x[j][2];
  d.rsq = d.dx * d.dx + d.dy * d.dy + d.dz * d.dz;
  return d;
}

// particles i and j overlap (closer than r_i + r_j): a closed contact
inline bool pair_touches(const PairSeparation &d, double touch)
{
  return d.rsq < touch * touch;
}

}    // namespace LAMMPS_NS

#endif
