/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   Per-atom bond and contact records owned by pair_style lattice/bond.

   The fix is created by pair_style lattice/bond at the first run.  It keeps
   the records with their atoms when atoms migrate between ranks, are sorted,
   or are written to and read from restart files.  Memory follows need: each
   atom has room for `capacity` records, which starts small and grows (up to
   maxslot) when an atom needs more; the pair style fits it to the largest
   count after creating the bonds.  It also keeps each atom's position at the
   last force evaluation, from which the step's displacements follow, in the
   same array as those displacements (see motion in the header).
------------------------------------------------------------------------- */

#include "fix_lattice_bond_store.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lattice_atom_history.h"
#include "lattice_errors.h"
#include "memory.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

static constexpr int INITIAL_CAPACITY = 4;
static constexpr int CAPACITY_STEP = 2;    // small steps: memory follows need

FixLatticeBondStore::FixLatticeBondStore(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), nmaxslot(0), ncapacity(0), nrec(nullptr), ncomp(3), spring(nullptr),
    partner(nullptr), state(nullptr), bonds_made(false), limit_step(0.0), layout(SHEAR_VECTOR),
    motion(nullptr), motion_phase(Phase::LAST_POSITIONS), measured_step(-1), measured_ok(1),
    measured_bit(1), nmax_store(0)
{
  if (narg != 4) error->all(FLERR, "Illegal fix {} command: expected one argument (maxslot)", style);
  nmaxslot = utils::inumeric(FLERR, arg[3], false, lmp);
  if (nmaxslot < 1) error->all(FLERR, "Fix {} maxslot {} must be >= 1", style, nmaxslot);
  ncapacity = std::min(nmaxslot, INITIAL_CAPACITY);

  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange = ATOM_DOUBLES + nmaxslot * RECORD_DOUBLES;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
  for (int k = 0; k < 6; k++) h_eval[k] = domain->h[k];
  boxstep = BoxStep{false, 0, 0, 0, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}};
}

/* ---------------------------------------------------------------------- */

FixLatticeBondStore::~FixLatticeBondStore()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(nrec);
  replace_records(nullptr, nullptr, nullptr);
  memory->sfree(motion);
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::setmask()
{
  return POST_RUN;
}

/* ----------------------------------------------------------------------
   the phases of motion (see the header): the moves each phase allows
------------------------------------------------------------------------- */

const char *FixLatticeBondStore::phase_name(Phase p)
{
  switch (p) {
    case Phase::LAST_POSITIONS: return "LAST_POSITIONS";
    case Phase::PASS_STEP: return "PASS_STEP";
    case Phase::MEASURING: return "MEASURING";
    case Phase::MEASURED_STEP: return "MEASURED_STEP";
  }
  return "unknown";
}

// each move names the phases it may start from (see the header's table)
void FixLatticeBondStore::move(std::initializer_list<Phase> from, Phase to, const char *action)
{
  for (Phase p : from)
    if (p == motion_phase) {
      motion_phase = to;
      return;
    }
  std::string allowed;
  for (Phase p : from) allowed += std::string(allowed.empty() ? "" : " or ") + phase_name(p);
  error->one(FLERR, "fix {}: internal error at step {}: {} moves the step's displacements to "
             "phase {} from {} only, but they are in phase {} (fix_lattice_bond_store.h)", style,
             update->ntimestep, action, phase_name(to), allowed, phase_name(motion_phase));
}

void FixLatticeBondStore::wrong_phase(const char *action) const
{
  error->one(FLERR, "fix {}: internal error at step {}: {} in phase {}, where the triples do not "
             "hold the step's displacements (fix_lattice_bond_store.h)", style, update->ntimestep,
             action, phase_name(motion_phase));
}

/* ----------------------------------------------------------------------
   fix lattice/nve moves the atoms of its group this step and measures their
   displacements into motion as it goes (new - old position); the other
   atoms' triples keep their last positions
------------------------------------------------------------------------- */

double *FixLatticeBondStore::begin_measured_step(int groupbit)
{
  // one measuring fix per step (fix lattice/nve measures only when no other
  // fix moves its atoms, and two fixes lattice/nve move each other's atoms)
  if (motion_phase == Phase::MEASURED_STEP && measured_step == update->ntimestep)
    error->one(FLERR, "fix {}: internal error at step {}: a second measuring drift in one step "
               "(fix_lattice_bond_store.h)", style, update->ntimestep);
  // a group that changed since the last measured step: its atoms that left
  // it hold this step's old displacement, not a last position
  if (motion_phase == Phase::MEASURED_STEP && groupbit != measured_bit)
    error->one(FLERR, "fix {}: internal error at step {}: the measured group changed within a run "
               "(fix_lattice_bond_store.h)", style, update->ntimestep);
  move({Phase::LAST_POSITIONS, Phase::MEASURED_STEP}, Phase::MEASURING,
       "fix lattice/nve's measuring drift (begin_measured_step)");
  measured_bit = groupbit;
  return motion;
}

/* ----------------------------------------------------------------------
   whether atom i's triple is its position at the last force evaluation
------------------------------------------------------------------------- */

bool FixLatticeBondStore::holds_last_position(int i) const
{
  switch (motion_phase) {
    case Phase::LAST_POSITIONS: return true;
    case Phase::PASS_STEP: return false;
    case Phase::MEASURING:
    case Phase::MEASURED_STEP: return measured_some() && !(atom->mask[i] & measured_bit);
  }
  return false;
}

void FixLatticeBondStore::end_measured_step(bool ok)
{
  move({Phase::MEASURING}, Phase::MEASURED_STEP, "fix lattice/nve's measuring drift (end_measured_step)");
  measured_step = update->ntimestep;
  measured_ok = ok ? 1 : 0;
}

/* ----------------------------------------------------------------------
   the last positions are the current ones again when the run ends, so that
   a following run, minimisation or restart file sees no step
------------------------------------------------------------------------- */

void FixLatticeBondStore::post_run()
{
  if (motion_is_displacement()) {
    move({Phase::PASS_STEP, Phase::MEASURED_STEP}, Phase::LAST_POSITIONS, "the end of the run (post_run)");
    positions_to_motion();
  }
  measured_step = -1;
}

/* ----------------------------------------------------------------------
   the last positions are the current ones (a 2D atom's third value stays 0,
   as the displacements of 2D atoms have no z part)
------------------------------------------------------------------------- */

void FixLatticeBondStore::positions_to_motion()
{
  const int dim = domain->dimension;
  const double *x = atom->x[0];
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < dim; k++) motion[3 * i + k] = x[3 * i + k];
}

/* ----------------------------------------------------------------------
   the store's own displacements give way to the positions; displacements
   fix lattice/nve measured stay until its next drift (the last positions
   are the current ones)
------------------------------------------------------------------------- */

void FixLatticeBondStore::end_evaluation()
{
  if (motion_phase == Phase::PASS_STEP) {
    move({Phase::PASS_STEP}, Phase::LAST_POSITIONS, "the end of the force evaluation (end_evaluation)");
    positions_to_motion();
  } else {
    move({Phase::MEASURED_STEP}, Phase::MEASURED_STEP, "the end of the force evaluation (end_evaluation)");
    if (measured_some()) unmeasured_to_positions();
  }
  for (int k = 0; k < 6; k++) h_eval[k] = domain->h[k];
}

/* ----------------------------------------------------------------------
   the pair style creates the initial bonds at its first force evaluation, or
   read_lattice_bonds reads them; a restart file brings the flag with it
------------------------------------------------------------------------- */

void FixLatticeBondStore::mark_bonds_created()
{
  if (bonds_made)
    error->all(FLERR, "fix {}: internal error: the bond network was created a second time", style);
  bonds_made = true;
}

/* ----------------------------------------------------------------------
   the change of the periodic box since the last force evaluation (see
   BoxStep).  A tilt that differs from the last one by about a whole period
   was flipped (fix deform flip yes; a box cannot deform by half a period in
   one step): the flip is undone by adding the period back, so that the
   change is the deformation alone
------------------------------------------------------------------------- */

void FixLatticeBondStore::form_box_step()
{
  const double *h = domain->h;
  BoxStep &b = boxstep;
  b.k = b.l = b.m = 0;
  double xy = h[5], yz = h[3], xz = h[4];
  if (domain->triclinic) {
    if (domain->xperiodic) {
      b.k = (int) std::lround((h_eval[5] - xy) / h[0]);
      xy += b.k * h[0];
    }
    if (domain->yperiodic) {
      b.m = (int) std::lround((h_eval[3] - yz) / h[1]);
      yz += b.m * h[1];
      xz += b.m * xy;
    }
    if (domain->xperiodic) {
      b.l = (int) std::lround((h_eval[4] - xz) / h[0]);
      xz += b.l * h[0];
    }
  }
  const double now[6] = {h[0], h[1], h[2], yz, xz, xy};
  b.moved = false;
  for (int k = 0; k < 6; k++) {
    b.d[k] = now[k] - h_eval[k];
    if (b.d[k] != 0.0) b.moved = true;
  }
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::add_record(int i, tagint partner_tag, LatticeBondState record_state)
{
  if (nrec[i] >= ncapacity) {
    if (nrec[i] >= nmaxslot)
      lattice_error_one(lmp, FLERR,
                        fmt::format("Atom {} has more than maxslot = {} bonds and contacts; "
                                    "increase the pair_style lattice/bond keyword maxslot",
                                    atom->tag[i], nmaxslot));
    set_capacity(std::min(nmaxslot, ncapacity + CAPACITY_STEP));
  }
  const int s = nrec[i]++;
  double *sp = springs(i) + s * ncomp;
  for (int k = 0; k < ncomp; k++) sp[k] = 0.0;
  partners(i)[s] = partner_tag;
  states(i)[s] = record_state;
  return s;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::remove_record(int i, int slot)
{
  const int last = --nrec[i];
  if (slot == last) return;
  double *sp = springs(i);
  for (int k = 0; k < ncomp; k++) sp[slot * ncomp + k] = sp[last * ncomp + k];
  partners(i)[slot] = partners(i)[last];
  states(i)[slot] = states(i)[last];
}

/* ----------------------------------------------------------------------
   lay the records out with room for n per atom (n >= every atom's count)
------------------------------------------------------------------------- */

void FixLatticeBondStore::set_capacity(int n)
{
  if (n != ncapacity) relayout(n, ncomp);
}

/* ----------------------------------------------------------------------
   free the record arrays and take the given ones (nullptr: none)
------------------------------------------------------------------------- */

void FixLatticeBondStore::replace_records(double *sp, tagint *pt, LatticeBondState *st)
{
  memory->sfree(spring);
  memory->sfree(partner);
  memory->sfree(state);
  spring = sp;
  partner = pt;
  state = st;
}

/* ----------------------------------------------------------------------
   the local atoms' records copied into arrays with room for n records of
   nc spring components per atom: components beyond the old ones are zero,
   fewer keep the first ones
------------------------------------------------------------------------- */

void FixLatticeBondStore::relayout(int n, int nc)
{
  // nothing to keep (bonding sizes the store before adding records): free
  // first, so that the peak memory never holds both layouts
  if (local_max_records() == 0) replace_records(nullptr, nullptr, nullptr);
  const bigint nslots = (bigint) nmax_store * n;
  auto *sp = (double *) memory->smalloc(nslots * nc * sizeof(double), "lattice/bond/store:spring");
  auto *pt = (tagint *) memory->smalloc(nslots * sizeof(tagint), "lattice/bond/store:partner");
  auto *st = (LatticeBondState *) memory->smalloc(nslots * sizeof(LatticeBondState), "lattice/bond/store:state");
  const int keep = std::min(nc, ncomp);
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    const int nr = nrec[i];
    if (!nr) continue;
    const double *from = springs(i);
    double *to = sp + (bigint) i * n * nc;
    for (int s = 0; s < nr; s++)
      for (int k = 0; k < nc; k++) to[s * nc + k] = (k < keep) ? from[s * ncomp + k] : 0.0;
    std::memcpy(pt + (bigint) i * n, partners(i), nr * sizeof(tagint));
    std::memcpy(st + (bigint) i * n, states(i), nr * sizeof(LatticeBondState));
  }
  replace_records(sp, pt, st);
  ncapacity = n;
  ncomp = nc;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::set_shear_layout(ShearLayout new_layout)
{
  layout = new_layout;
  const int nc = (layout == SHEAR_PLANAR) ? 1 : 3;
  if (nc != ncomp) relayout(ncapacity, nc);
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::fit_capacity(int n)
{
  set_capacity(std::min(nmaxslot, std::max({n, local_max_records(), 1})));
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::local_max_records() const
{
  int most = 0;
  for (int i = 0; i < atom->nlocal; i++) most = std::max(most, nrec[i]);
  return most;
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::global_max_records() const
{
  int most = local_max_records(), most_all = 0;
  MPI_Allreduce(&most, &most_all, 1, MPI_INT, MPI_MAX, world);
  return most_all;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::set_maxslot(int n)
{
  const int most_all = global_max_records();
  if (most_all > n)
    error->all(FLERR, "pair_style lattice/bond maxslot {} is too small: an atom holds {} bonds "
               "and contacts; use maxslot >= {}", n, most_all, most_all);
  nmaxslot = n;
  maxexchange = ATOM_DOUBLES + nmaxslot * RECORD_DOUBLES;
  if (ncapacity > nmaxslot) set_capacity(nmaxslot);
}

/* ----------------------------------------------------------------------
   each local atom's displacement since the last force evaluation, with
   periodic jumps removed, formed in place of the last position (which the
   current position replaces at end_evaluation); the pair style sends them
   to the ghosts.  With limit > 0: the index of an atom that moved more than
   limit along an axis (or to NaN), else -1
------------------------------------------------------------------------- */

int FixLatticeBondStore::update_displacements(double limit)
{
  const int nlocal = atom->nlocal;
  form_box_step();
  // already measured by the integrator this step: only the test is left, and
  // the steps of the atoms it does not move
  if (motion_phase == Phase::MEASURED_STEP && measured_step == update->ntimestep) {
    const bool ok = !measured_some() || unmeasured_steps(limit);
    return (nlocal == 0 || limit <= 0.0 || (measured_ok && ok)) ? -1
                                                                : first_beyond(limit, domain->dimension);
  }
  move({Phase::LAST_POSITIONS}, Phase::PASS_STEP, "forming the step's displacements (update_displacements)");
  if (nlocal == 0) return -1;
  if (domain->triclinic) {
    for (int i = 0; i < nlocal; i++) step_from_last_position(i);
    return (limit > 0.0) ? first_beyond(limit, domain->dimension) : -1;
  }
  // 2D: the force loop reads x and y only (z stays 0)
  return (domain->dimension == 2) ? orthogonal_steps<2>(limit) : orthogonal_steps<3>(limit);
}

/* ----------------------------------------------------------------------
   orthogonal box, DIM components, one pass: a step longer than half the
   box along a periodic axis is a periodic jump
------------------------------------------------------------------------- */

template <int DIM> int FixLatticeBondStore::orthogonal_steps(double limit)
{
  const int nlocal = atom->nlocal;
  const auto *const x = reinterpret_cast<const double(*)[3]>(atom->x[0]);
  auto *const m = reinterpret_cast<double(*)[3]>(motion);
  // half the period along periodic axes, no jump along the others
  const int periodic[3] = {domain->xperiodic, domain->yperiodic, domain->zperiodic};
  const double prd[3] = {domain->xprd, domain->yprd, domain->zprd};
  double half[3];
  for (int k = 0; k < 3; k++) half[k] = periodic[k] ? 0.5 * prd[k] : HUGE_VAL;
  int ok = 1;
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < DIM; k++) {
      double step = x[i][k] - m[i][k];
      if (std::fabs(step) > half[k]) step -= std::copysign(prd[k], step);
      m[i][k] = step;
      ok &= (std::fabs(step) <= limit);    // false for NaN too
    }
  if (limit <= 0.0 || ok) return -1;
  return first_beyond(limit, DIM);
}

/* ----------------------------------------------------------------------
   atom i's triple: its last position -> its step, x - last position with a
   periodic jump removed (lattice_unwrap_step: the same arithmetic as
   orthogonal_steps in an orthogonal box); 2D steps have no z part
------------------------------------------------------------------------- */

void FixLatticeBondStore::step_from_last_position(int i)
{
  const double *const x = atom->x[i];
  double *const m = motion + 3 * i;
  double step[3] = {x[0] - m[0], x[1] - m[1], (domain->dimension == 3) ? x[2] - m[2] : 0.0};
  lattice_unwrap_step(domain, step);
  for (int k = 0; k < 3; k++) m[k] = step[k];
}

/* ----------------------------------------------------------------------
   fix lattice/nve measured the atoms of its group: the others' steps from
   their last positions, as the pass forms them
------------------------------------------------------------------------- */

bool FixLatticeBondStore::unmeasured_steps(double limit)
{
  if (neighbor->ago == 0 || atom->nlocal != unmeasured_nlocal) list_unmeasured();
  const int dim = domain->dimension;
  int ok = 1;
  for (const int i : unmeasured) {
    step_from_last_position(i);
    for (int k = 0; k < dim; k++) ok &= (std::fabs(motion[3 * i + k]) <= limit);    // false for NaN too
  }
  return ok || limit <= 0.0;
}

/* ----------------------------------------------------------------------
   after a measured step's force evaluation: the atoms outside the measured
   group hold their positions again (2D: x and y, z stays 0)
------------------------------------------------------------------------- */

void FixLatticeBondStore::unmeasured_to_positions()
{
  // (the list of this step's unmeasured_steps: nothing reorders atoms in between)
  const int dim = domain->dimension;
  const double *const x = atom->x[0];
  for (const int i : unmeasured)
    for (int k = 0; k < dim; k++) motion[3 * i + k] = x[3 * i + k];
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::list_unmeasured()
{
  const int nlocal = atom->nlocal;
  const int *const mask = atom->mask;
  unmeasured.clear();
  for (int i = 0; i < nlocal; i++)
    if (!(mask[i] & measured_bit)) unmeasured.push_back(i);
  unmeasured_nlocal = nlocal;
}

/* ----------------------------------------------------------------------
   the first local atom whose step exceeds limit along one of the first dim
   axes (or is NaN), -1 if none
------------------------------------------------------------------------- */

int FixLatticeBondStore::first_beyond(double limit, int dim) const
{
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < dim; k++)
      if (!(std::fabs(motion[3 * i + k]) <= limit)) return i;
  return -1;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::grow_arrays(int nmax)
{
  memory->grow(nrec, nmax, "lattice/bond/store:nrec");
  // atoms not yet filled (read_restart unpacks them one by one) hold no records
  for (int i = nmax_store; i < nmax; i++) nrec[i] = 0;
  motion = (double *) memory->srealloc(motion, sizeof(double) * 3 * (bigint) nmax,
                                       "lattice/bond/store:motion");
  const bigint nslots = (bigint) nmax * ncapacity;
  spring = (double *) memory->srealloc(spring, nslots * ncomp * sizeof(double),
                                       "lattice/bond/store:spring");
  partner = (tagint *) memory->srealloc(partner, nslots * sizeof(tagint),
                                        "lattice/bond/store:partner");
  state = (LatticeBondState *) memory->srealloc(state, nslots * sizeof(LatticeBondState),
                                                "lattice/bond/store:state");
  nmax_store = nmax;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::copy_arrays(int i, int j, int /*delflag*/)
{
  nrec[j] = nrec[i];
  if (nrec[i]) {
    std::memcpy(springs(j), springs(i), nrec[i] * ncomp * sizeof(double));
    std::memcpy(partners(j), partners(i), nrec[i] * sizeof(tagint));
    std::memcpy(states(j), states(i), nrec[i] * sizeof(LatticeBondState));
  }
  for (int k = 0; k < 3; k++) motion[3 * j + k] = motion[3 * i + k];
}

/* ----------------------------------------------------------------------
   a new atom: no records, at rest since the last force evaluation
------------------------------------------------------------------------- */

void FixLatticeBondStore::set_arrays(int i)
{
  nrec[i] = 0;
  const int dim = domain->dimension;
  const bool position = holds_last_position(i);
  for (int k = 0; k < 3; k++) motion[3 * i + k] = (!position || k >= dim) ? 0.0 : atom->x[i][k];
}

/* ----------------------------------------------------------------------
   one atom as doubles: record count, a triple (the last position or the
   displacement, see pack_exchange and pack_restart), then 5 values per record
   (partner, state, three spring components: a planar spring is written as
   (s, 0, 0), so that the layout does not depend on shear_layout)
------------------------------------------------------------------------- */

int FixLatticeBondStore::pack_atom(int i, double *buf, const double *triple) const
{
  int m = 0;
  buf[m++] = ubuf(nrec[i]).d;
  for (int k = 0; k < 3; k++) buf[m++] = triple[k];
  const double *sp = springs(i);
  const tagint *pt = partners(i);
  const LatticeBondState *st = states(i);
  for (int s = 0; s < nrec[i]; s++) {
    buf[m++] = ubuf(pt[s]).d;
    buf[m++] = ubuf((int) st[s]).d;
    for (int k = 0; k < 3; k++) buf[m++] = (k < ncomp) ? sp[s * ncomp + k] : 0.0;
  }
  return m;
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::unpack_atom(int i, const double *buf)
{
  int m = 0;
  const int n = (int) ubuf(buf[m++]).i;
  if (n < 0 || n > nmaxslot)
    lattice_error_one(lmp, FLERR,
                      fmt::format("Atom {} carries {} bond records but maxslot is {}; use a "
                                  "pair_style lattice/bond maxslot of at least {}",
                                  atom->tag[i], n, nmaxslot, n));
  if (n > ncapacity) set_capacity(std::min(nmaxslot, n + CAPACITY_STEP));
  nrec[i] = n;
  // (a 2D atom's third value stays 0: the displacements of 2D atoms have no z part)
  for (int k = 0; k < 3; k++) motion[3 * i + k] = (k < domain->dimension) ? buf[m + k] : 0.0;
  m += 3;
  double *sp = springs(i);
  tagint *pt = partners(i);
  LatticeBondState *st = states(i);
  for (int s = 0; s < n; s++) {
    pt[s] = (tagint) ubuf(buf[m++]).i;
    st[s] = (LatticeBondState) ubuf(buf[m++]).i;
    // a planar spring keeps the first value (the others are 0)
    for (int k = 0; k < ncomp; k++) sp[s * ncomp + k] = buf[m + k];
    m += 3;
  }
  return m;
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::pack_exchange(int i, double *buf)
{
  // atoms migrate after the drift and before the force evaluation: motion
  // holds their last positions, or the displacements fix lattice/nve measured
  // (which travel with the atom: recomputed from a periodically wrapped
  // position they could differ in the last bit from those of atoms that
  // stayed); every rank is in the same phase
  return pack_atom(i, buf, motion + 3 * i);
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::unpack_exchange(int nlocal, double *buf)
{
  return unpack_atom(nlocal, buf);
}

/* ----------------------------------------------------------------------
   restart layout per atom: total length (LAMMPS convention), then the
   same layout as pack_exchange
------------------------------------------------------------------------- */

int FixLatticeBondStore::pack_restart(int i, double *buf)
{
  // restart files are written after a complete step: the position of its
  // force evaluation is the current one when motion holds the step
  const int m = pack_atom(i, buf + 1, motion_is_displacement() ? atom->x[i] : motion + 3 * i);
  buf[0] = m + 1;
  return m + 1;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  unpack_atom(nlocal, &extra[nlocal][m + 1]);
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::size_restart(int i)
{
  return 1 + ATOM_DOUBLES + nrec[i] * RECORD_DOUBLES;
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::maxsize_restart()
{
  return 1 + ATOM_DOUBLES + nmaxslot * RECORD_DOUBLES;
}

/* ----------------------------------------------------------------------
   global part: format, whether the bonds exist, maxslot, shear layout, the
   box of the last force evaluation (whose positions the atoms' records hold).
   Files of the first format (records with the old separation) start with
   the bonds_created flag, 0 or 1, and are rejected; files of the second
   format hold shear vectors, which a 2D run turns into scalars; files of the
   third have no box (the box read with them is taken for it)
------------------------------------------------------------------------- */

void FixLatticeBondStore::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    double list[10] = {(double) RESTART_FORMAT, bonds_made ? 1.0 : 0.0, (double) nmaxslot,
                       (double) layout};
    for (int k = 0; k < 6; k++) list[4 + k] = h_eval[k];
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 10, fp);
  }
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::restart(char *buf)
{
  auto list = (double *) buf;
  const int format = static_cast<int>(list[0]);
  if (format < 2 || format > RESTART_FORMAT)
    error->all(FLERR, "This restart file holds pair_style lattice/bond records in format {} "
               "(an {} BONDED_LATTICE version); this version reads formats 2 to {}. Rerun "
               "the model from its data file, or write the restart again with the version that "
               "made it", format < 2 ? 1 : format, format < 2 ? "older" : "newer", RESTART_FORMAT);
  bonds_made = static_cast<int>(list[1]) != 0;
  set_shear_layout((format == 2 || static_cast<int>(list[3]) != SHEAR_PLANAR) ? SHEAR_VECTOR
                                                                              : SHEAR_PLANAR);
  for (int k = 0; k < 6; k++) h_eval[k] = (format >= 4) ? list[4 + k] : domain->h[k];
}

/* ---------------------------------------------------------------------- */

double FixLatticeBondStore::memory_usage()
{
  const double per_record = ncomp * sizeof(double) + sizeof(tagint) + sizeof(LatticeBondState);
  return (double) nmax_store * (sizeof(int) + 3 * sizeof(double) + ncapacity * per_record);
}
