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
// (FixLatticeBondStore::displacements), so a record keeps no old separation.
//
// A record is one entry in each of three arrays (FixLatticeBondStore): its
// shear spring (ncomp doubles, force on the owner -Ks*spring), the partner's
// tag and its state.  Separate arrays let the force loop stream springs and
// states only; the partner tag is read after reneighbouring.

// one byte; its own type rather than a char, which the compiler must assume
// aliases every other array of the force loop
enum LatticeBondState : unsigned char {
  LB_INTACT = 0,
  LB_BROKEN_TENSION = 1,
  LB_BROKEN_SHEAR = 2,
  LB_CONTACT = 3
};

class FixLatticeBondStore : public Fix {
 public:
  FixLatticeBondStore(class LAMMPS *, int, char **);
  ~FixLatticeBondStore() override;
  int setmask() override;
  void post_run() override;

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

  // record s (0 <= s < nrec[i]) of atom i: springs(i)[s*ncomp .. s*ncomp + ncomp-1],
  // partners(i)[s], states(i)[s]; each atom has room for `capacity` records
  double *springs(int i) const { return spring + (bigint) i * capacity * ncomp; }
  tagint *partners(int i) const { return partner + (bigint) i * capacity; }
  LatticeBondState *states(int i) const { return state + (bigint) i * capacity; }
  // squared length of the spring of record s of atom i (either layout)
  double spring_squared(int i, int s) const
  {
    const double *sh = springs(i) + s * ncomp;
    double s2 = 0.0;
    for (int k = 0; k < ncomp; k++) s2 += sh[k] * sh[k];
    return s2;
  }
  // a new record with a zero spring, its slot; grows the capacity, error beyond maxslot
  int add_record(int i, tagint partner_tag, int record_state);
  void remove_record(int i, int slot);     // swap-with-last removal
  // change the shear layout; records keep spring component 0 (the signed
  // length when turning vectors into planar springs, see shear_layout)
  void set_shear_layout(int layout);
  void set_maxslot(int n);                 // new limit; error if an atom holds more
  void fit_capacity(int n);                // capacity = max(n, every atom's count) <= maxslot
  int local_max_records() const;
  int global_max_records() const;          // over all ranks (collective)
  // this step's displacements: formed from the last positions by the store
  // (disp = x - last position, periodic jumps removed), or already measured
  // by fix lattice/nve; with limit > 0 the index of an atom that moved more
  // than limit along an axis (or to NaN), else -1
  int update_displacements(double limit);
  // the force evaluation that used the displacements is over: the store's
  // own displacements give way to the current positions again
  void end_evaluation();
  // fix lattice/nve, integrating every atom, measured this step's displacements
  // into displacements() while it moved them (new - old position);
  // update_displacements() then only tests them; ok: none longer than step_limit
  void mark_integrated(bool ok);
  bool integrated() const;    // this step's displacements are measured
  // the displacements over the step (3 per atom, ghosts by forward comm of the
  // pair style), valid from update_displacements() or the measuring drift to the
  // end of the force evaluation
  double *displacements() const { return motion; }

  // the periodic box over the step.  A ghost is its owner shifted by a lattice
  // vector of the box, p0 a + p1 b + p2 c (p = the first three values of LAMMPS'
  // pbc of a communication swap); when the box changes between two force
  // evaluations (change_box, fix deform, barostats) that shift changes with it,
  // and the ghost moves by its owner's displacement plus shift(p).  A flip of a
  // tilted box (fix deform flip) is a new choice of lattice vectors, not a
  // deformation: it is undone first, with the integers k, l, m, so that
  // p refers to the same image before and after.  Formed by update_displacements()
  struct BoxStep {
    bool moved;        // the box differs from the last force evaluation's
    int k, l, m;       // b = b' + k a', c = c' + m b' + (mk + l) a' undoes a flip
    double d[6];       // change of the (unflipped) box: xprd, yprd, zprd, yz, xz, xy
    // the change of the shift of an image with pbc (p0, p1, p2) of the current box
    void shift(const int *p, double *out) const
    {
      const double q0 = p[0] - k * p[1] - l * p[2], q1 = p[1] - m * p[2], q2 = p[2];
      out[0] = q0 * d[0] + q1 * d[5] + q2 * d[4];
      out[1] = q1 * d[1] + q2 * d[3];
      out[2] = q2 * d[2];
    }
  };
  const BoxStep &box_step() const { return boxstep; }

  int maxslot;           // most records an atom may hold (pair_style keyword)
  int capacity;          // records stored per atom now: grows on demand up to maxslot
  int *nrec;             // number of records per atom
  int ncomp;             // doubles per spring: 1 (SHEAR_PLANAR) or 3 (SHEAR_VECTOR)
  double *spring;        // shear springs, ncomp * capacity per atom
  tagint *partner;       // tag of the higher-tag particle, capacity per atom
  LatticeBondState *state;    // capacity per atom
  int bonds_created;     // 1 once the initial bonds exist; never reset (survives restart)
  double step_limit;     // longest step along an axis that is not an instability (pair style)
  // how the records hold the shear spring: SHEAR_VECTOR, a 3-vector in the
  // tangent plane, ncomp = 3 (3D; also 2D records read from a bond file or an older
  // restart file, until the pair style turns them into scalars), or
  // SHEAR_PLANAR, the signed length along t = z x n, ncomp = 1 (2D).
  // Read only: change it with set_shear_layout()
  enum { SHEAR_VECTOR = 0, SHEAR_PLANAR = 1 };
  int shear_layout;

 private:
  // one triple per atom (nmax x 3 in one block), in one of two roles: the
  // position at the last force evaluation, or this step's displacement (from
  // the moment it is formed until the evaluation is over; with fix lattice/nve
  // measuring, until the next drift, the last positions being the current
  // ones).  One array in two roles instead of two saves 32 bytes per particle
  double *motion;
  bool motion_is_step;       // motion holds displacements
  bool step_from_pass;       // ... formed by update_displacements (end_evaluation restores)
  bigint integrated_step;    // the step whose displacements fix lattice/nve measured, or -1
  int integrated_ok;         // and whether none of them was longer than step_limit
  int nmax_store;
  // the box (domain->h: xprd, yprd, zprd, yz, xz, xy) at the last force
  // evaluation, and its change to this one (see BoxStep)
  double h_eval[6];
  BoxStep boxstep;
  void form_box_step();
  static constexpr int RECORD_DOUBLES = 5;    // packed size of one record (always 3 shear values)
  static constexpr int ATOM_DOUBLES = 4;      // count + last position (exchange: motion)
  // 1: records with the old separation; 2: no shear layout (vectors); 3: no box
  // of the last force evaluation
  static constexpr int RESTART_FORMAT = 4;
  void positions_to_motion();    // motion = current positions (local atoms)
  void set_capacity(int n);
  void relayout(int new_capacity, int new_ncomp);
  void replace_records(double *, tagint *, LatticeBondState *);
  template <int DIM> int orthogonal_steps(double limit);
  int first_beyond(double limit, int dim) const;
  // record count, the given triple, the records
  int pack_atom(int, double *, const double *triple) const;
  int unpack_atom(int, const double *);
};

}    // namespace LAMMPS_NS

#endif
#endif
