/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Communication of the parts of pair_style lattice/bond.  LAMMPS
   communicates per-atom values for a Pair (or Fix, Compute, ...) only: each
   part that needs ghost values (heterogeneity, the rotation fit, the
   time-step check) packs and unpacks its own, and the pair style carries
   them (PairLatticeBond::pack_forward_comm and the others route to the part
   that asked).  A part sends at most the pair's comm_forward / comm_reverse
   values per atom, or, naming the count, up to 3 in reverse (LAMMPS sizes
   its buffers for the 3 force components of every atom style).
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_COMM_H
#define LMP_LATTICE_COMM_H

namespace LAMMPS_NS {

// per-atom values a part sends from the owners to their ghosts
class LatticeForwardPart {
 public:
  virtual int pack_forward(int n, const int *list, double *buf) = 0;
  virtual void unpack_forward(int n, int first, const double *buf) = 0;

 protected:
  ~LatticeForwardPart() = default;
};

// per-atom values a part sums from the ghosts into their owners
class LatticeReversePart {
 public:
  virtual int pack_reverse(int n, int first, double *buf) = 0;
  virtual void unpack_reverse(int n, const int *list, const double *buf) = 0;

 protected:
  ~LatticeReversePart() = default;
};

// the pair style: LAMMPS' forward_comm / reverse_comm for a part (collective)
class LatticeCommCarrier {
 public:
  virtual void carry_forward(LatticeForwardPart *part) = 0;
  // values: per atom, 0 = the pair's comm_reverse; at most 3
  virtual void carry_reverse(LatticeReversePart *part, int values = 0) = 0;

 protected:
  ~LatticeCommCarrier() = default;
};

}    // namespace LAMMPS_NS

#endif
