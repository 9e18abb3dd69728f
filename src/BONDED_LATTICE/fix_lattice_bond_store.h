/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   Per-atom bond and contact records owned by pair_style lattice/bond.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(LATTICE/BOND/STORE,FixLatticeBondStore);
// clang-format on
#else

#ifndef LMP_FIX_LATTICE_BOND_STORE_H
#define LMP_FIX_LATTICE_BOND_STORE_H

#include "fix.h"

namespace LAMMPS_NS {

// One bond or contact between two particles.  It is stored once, on the
// particle with the lower tag ("owner"); only the rank owning that particle
// updates it, so ranks can never disagree about whether a bond broke.  The
// step's relative displacement comes from the two particles' displacements
// (FixLatticeBondStore::disp), so a record keeps no old separation.
struct LatticeBondRecord {
  double shear[3];      // shear-spring displacement; force on the owner is -Ks*shear
  tagint partner;       // tag of the higher-tag particle
  int state;            // one of LatticeBondState
};

enum LatticeBondState { LB_INTACT = 0, LB_BROKEN_TENSION = 1, LB_BROKEN_SHEAR = 2, LB_CONTACT = 3 };

class FixLatticeBondStore : public Fix {
 public:
  FixLatticeBondStore(class LAMMPS *, int, char **);
  ~FixLatticeBondStore() override;
  int setmask() override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  double memory_usage() override;

  // records of atom i are rec[i*capacity .. i*capacity + nrec[i] - 1]
  LatticeBondRecord *records(int i) const { return rec + (bigint) i * capacity; }
  LatticeBondRecord *add_record(int i);    // grows the capacity; error beyond maxslot
  void remove_record(int i, int slot);     // swap-with-last removal
  void set_maxslot(int n);                 // new limit; error if an atom holds more
  void fit_capacity(int n);                // capacity = max(n, every atom's count) <= maxslot
  int local_max_records() const;
  int global_max_records() const;          // over all ranks (collective)
  int update_displacements(double limit);  // disp = x - xlast, xlast = x (local atoms)

  int maxslot;           // most records an atom may hold (pair_style keyword)
  int capacity;          // records stored per atom now: grows on demand up to maxslot
  int *nrec;             // number of records per atom
  LatticeBondRecord *rec;
  double **xlast;        // position at the last force evaluation (local atoms)
  double **disp;         // displacement since then (local atoms; ghosts by forward comm)
  int bonds_created;     // 1 once the initial bonds exist; never reset (survives restart)
  // how the records hold the shear spring: SHEAR_VECTOR, a 3-vector in the
  // tangent plane (3D; also 2D records read from a bond file or an older
  // restart file, until the pair style turns them into scalars), or
  // SHEAR_PLANAR, the signed length along t = z x n in shear[0] (2D)
  enum { SHEAR_VECTOR = 0, SHEAR_PLANAR = 1 };
  int shear_layout;

 private:
  int nmax_store;
  static constexpr int RECORD_DOUBLES = 5;    // packed size of one record
  static constexpr int ATOM_DOUBLES = 4;      // count + xlast
  // 1: records with the old separation; 2: no shear layout (vectors)
  static constexpr int RESTART_FORMAT = 3;
  void set_capacity(int n);
  template <int DIM> int orthogonal_steps(double limit);
  int first_beyond(double limit, int dim) const;
  int pack_atom(int, double *) const;
  int unpack_atom(int, const double *);
};

}    // namespace LAMMPS_NS

#endif
#endif
