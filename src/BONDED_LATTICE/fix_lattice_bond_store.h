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

#include <initializer_list>
#include <vector>

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

// how an intact bond breaks (or would break): the larger of its tensile and
// shear ratios to the threshold (PairLatticeBond::bond_load), None for a
// record that cannot break (a broken bond or a contact).  A broken bond keeps
// its mode as its state (broken_state)
enum class BreakMode : unsigned char { None = 0, Tension = 1, Shear = 2 };

// the state of a bond that broke in mode m (m is Tension or Shear)
inline LatticeBondState broken_state(BreakMode m)
{
  return (m == BreakMode::Tension) ? LB_BROKEN_TENSION : LB_BROKEN_SHEAR;
}

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

  // ---- the records ------------------------------------------------------
  // record s (0 <= s < record_count(i)) of atom i: springs(i)[s*ncomp .. s*ncomp + ncomp-1],
  // partners(i)[s], states(i)[s]; each atom has room for capacity() records.
  // The pointers are the arrays themselves (no copy, no check): the force loop
  // streams them
  double *springs(int i) const { return spring + (bigint) i * ncapacity * ncomp; }
  tagint *partners(int i) const { return partner + (bigint) i * ncapacity; }
  LatticeBondState *states(int i) const { return state + (bigint) i * ncapacity; }
  int record_count(int i) const { return nrec[i]; }
  const int *record_counts() const { return nrec; }    // per atom (the force loop)
  int capacity() const { return ncapacity; }    // records stored per atom now
  int maxslot() const { return nmaxslot; }      // most records an atom may hold
  int spring_components() const { return ncomp; }    // doubles per spring: 1 or 3
  // squared length of the spring of record s of atom i (either layout)
  double spring_squared(int i, int s) const
  {
    const double *sh = springs(i) + s * ncomp;
    double s2 = 0.0;
    for (int k = 0; k < ncomp; k++) s2 += sh[k] * sh[k];
    return s2;
  }
  // a new record with a zero spring, its slot; grows the capacity, error beyond maxslot
  int add_record(int i, tagint partner_tag, LatticeBondState record_state);
  void remove_record(int i, int slot);     // swap-with-last removal
  // how the records hold the shear spring: SHEAR_VECTOR, a 3-vector in the
  // tangent plane, ncomp = 3 (3D; also 2D records read from a bond file or an older
  // restart file, until the pair style turns them into scalars), or
  // SHEAR_PLANAR, the signed length along t = z x n, ncomp = 1 (2D).  The
  // values are those of the restart files
  enum ShearLayout { SHEAR_VECTOR = 0, SHEAR_PLANAR = 1 };
  ShearLayout shear_layout() const { return layout; }
  // change the shear layout; records keep spring component 0 (the signed
  // length when turning vectors into planar springs, see shear_layout)
  void set_shear_layout(ShearLayout new_layout);
  void set_maxslot(int n);                 // new limit; error if an atom holds more
  void fit_capacity(int n);                // capacity = max(n, every atom's count) <= maxslot
  int local_max_records() const;
  int global_max_records() const;          // over all ranks (collective)

  // ---- the bond network's life cycle ----------------------------------------
  // true once the initial bonds exist: made by the pair style's first force
  // evaluation or read by read_lattice_bonds (each calls mark_bonds_created
  // once), or read from a restart file.  Never reset
  bool bonds_created() const { return bonds_made; }
  // the one writer of that flag; an internal error if the bonds exist already
  void mark_bonds_created();

  // ---- the step's displacements: phases of the per-atom triple `motion` -----
  // One triple per atom holds either the atom's position at the last force
  // evaluation or its displacement over this step (one array in two roles
  // saves 32 bytes per particle).  The phase says which, and who may move it
  // on; every move is checked (a wrong one is an internal error naming both
  // phases):
  //   LAST_POSITIONS -> PASS_STEP       update_displacements() (pair compute: x - last position)
  //   PASS_STEP      -> LAST_POSITIONS  end_evaluation() (pair compute) or post_run()
  //   LAST_POSITIONS,
  //   MEASURED_STEP  -> MEASURING       begin_measured_step() (fix lattice/nve, its drift)
  //   MEASURING      -> MEASURED_STEP   end_measured_step() (fix lattice/nve)
  //   MEASURED_STEP  -> MEASURED_STEP   update_displacements() (measured this step: test
  //                                     only), end_evaluation() (the last positions are x)
  //   MEASURED_STEP  -> LAST_POSITIONS  post_run() (x is copied in)
  // In MEASURED_STEP the last positions are the current positions x (after its
  // force evaluation the triple keeps that evaluation's displacements until the
  // next drift, and forming displacements from them is an error); a drift that
  // follows a drift with no force evaluation between (pair_modify compute no)
  // measures again.  All ranks move together (every move is part of a step).
  // A fix lattice/nve of a group other than all measures its group's atoms
  // only (measured_bit); the triples of the other atoms (platens moved by fix
  // move, atoms no fix moves) hold their last positions in MEASURING and
  // MEASURED_STEP too, update_displacements() forms their steps from x and
  // end_evaluation() sets them to x again (holds_last_position())
  enum class Phase { LAST_POSITIONS, PASS_STEP, MEASURING, MEASURED_STEP };
  Phase phase() const { return motion_phase; }
  static const char *phase_name(Phase p);
  // the triple is a displacement (PASS_STEP, MEASURING or MEASURED_STEP), not a position
  bool motion_is_displacement() const { return motion_phase != Phase::LAST_POSITIONS; }

  // pair style, every force evaluation: the longest step along an axis that
  // is not an instability (a tenth of the smallest radius).  Published before
  // the displacements are formed; fix lattice/nve tests its next drift against
  // the value of the last evaluation (0 before the first: no test)
  void publish_step_limit(double limit) { limit_step = limit; }
  double step_limit() const { return limit_step; }

  // pair style: this step's displacements.  Formed from the last positions
  // by the store (disp = x - last position, periodic jumps removed), or, if
  // fix lattice/nve measured them this step, only tested; with limit > 0 the
  // index of an atom that moved more than limit along an axis (or to NaN), else -1
  int update_displacements(double limit);
  // pair style: the force evaluation that used the displacements is over; the
  // store's own displacements give way to the current positions again
  void end_evaluation();
  // fix lattice/nve, integrating every atom: the triples to fill with this
  // step's displacements (new - old position, 3 per atom) while it moves the
  // atoms; then end_measured_step, ok: none longer than step_limit() (nor NaN)
  // groupbit: the group the fix moves (1: all); the triples of atoms outside it
  // keep their last positions
  double *begin_measured_step(int groupbit);
  void end_measured_step(bool ok);
  // whether atom i's triple holds its last position (not a displacement) now
  bool holds_last_position(int i) const;
  // the displacements over the step (3 per atom, ghosts by forward comm of the
  // pair style): the array itself, for the force loop.  Only in the phases
  // PASS_STEP and MEASURED_STEP (internal error otherwise)
  double *displacements() const
  {
    if (motion_phase != Phase::PASS_STEP && motion_phase != Phase::MEASURED_STEP)
      wrong_phase("reading the step's displacements (displacements())");
    return motion;
  }

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

 private:
  int nmaxslot;          // most records an atom may hold (pair_style keyword)
  int ncapacity;         // records stored per atom now: grows on demand up to nmaxslot
  int *nrec;             // number of records per atom
  int ncomp;             // doubles per spring: 1 (SHEAR_PLANAR) or 3 (SHEAR_VECTOR)
  double *spring;        // shear springs, ncomp * ncapacity per atom
  tagint *partner;       // tag of the higher-tag particle, ncapacity per atom
  LatticeBondState *state;    // ncapacity per atom
  bool bonds_made;       // see bonds_created()
  double limit_step;     // see step_limit()
  ShearLayout layout;    // see shear_layout()

  // one triple per atom (nmax x 3 in one block): the position at the last
  // force evaluation or this step's displacement, as motion_phase says
  double *motion;
  Phase motion_phase;
  bigint measured_step;    // the step whose displacements fix lattice/nve measured, or -1
  int measured_ok;         // and whether none of them was longer than step_limit
  int measured_bit;        // the group bit of the atoms measured (1: every atom)
  bool measured_some() const { return measured_bit != 1; }
  // the local atoms outside measured_bit, listed when atoms were last
  // reordered (atoms migrate, are sorted or created only when neighbour
  // lists are rebuilt), so that their passes do not visit every atom
  std::vector<int> unmeasured;
  int unmeasured_nlocal = -1;
  void list_unmeasured();
  // `action` moves the phase to `to`: an internal error unless the phase is one of `from`
  void move(std::initializer_list<Phase> from, Phase to, const char *action);
  [[noreturn]] void wrong_phase(const char *action) const;    // action needs displacements
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
  void step_from_last_position(int i);    // atom i's triple: last position -> step
  // steps of the atoms outside measured_bit (x - last position), as the pass
  // forms them; false if one exceeds limit > 0
  bool unmeasured_steps(double limit);
  void unmeasured_to_positions();
  // record count, the given triple, the records
  int pack_atom(int, double *, const double *triple) const;
  int unpack_atom(int, const double *);
};

}    // namespace LAMMPS_NS

#endif
#endif
