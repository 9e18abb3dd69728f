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
// updates it, so ranks can never disagree about whether a bond broke.
struct LatticeBondRecord {
  double shear[3];      // shear-spring displacement; force on the owner is -Ks*shear
  double dx_prev[3];    // owner-minus-partner separation at the last update
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

  // records of atom i are rec[i*maxslot .. i*maxslot + nrec[i] - 1]
  LatticeBondRecord *records(int i) const { return rec + (bigint) i * maxslot; }
  LatticeBondRecord *add_record(int i);    // error if atom i is full
  void remove_record(int i, int slot);     // swap-with-last removal

  int maxslot;           // capacity per atom
  int *nrec;             // number of records per atom
  LatticeBondRecord *rec;
  int bonds_created;     // 1 once the initial bonds exist; never reset (survives restart)

 private:
  int nmax_store;
  static constexpr int RECORD_DOUBLES = 8;    // packed size of one record
  int pack_atom(int, double *) const;
  int unpack_atom(int, const double *);
};

}    // namespace LAMMPS_NS

#endif
#endif
