/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   fix lattice/nve: velocity Verlet for the particles' translations.

   The lattice model's particles do not rotate, so only x and v are
   integrated, with the same arithmetic as fix nve (v += dt/2 f/m, then
   x += dt v): trajectories are identical to the last bit.  A loop compiled
   for 2D updates x and y only, so that a 2D model needs no fix enforce2d
   and pays for two components instead of three plus a second pass; the
   group all takes a loop without the mask test.
------------------------------------------------------------------------- */

#include "fix_lattice_nve.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "pair_lattice_bond.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixLatticeNVE::FixLatticeNVE(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dtv(0.0), dtf(0.0), store(nullptr)
{
  if (narg != 3)
    error->all(FLERR, "Illegal fix lattice/nve command: expected 'fix ID group lattice/nve' "
               "with no further arguments (got {} more)", narg - 3);
  dynamic_group_allow = 1;
  time_integrate = 1;
}

/* ---------------------------------------------------------------------- */

int FixLatticeNVE::setmask()
{
  return INITIAL_INTEGRATE | FINAL_INTEGRATE;
}

/* ---------------------------------------------------------------------- */

void FixLatticeNVE::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "fix lattice/nve does not support run_style respa; use run_style verlet");
  if (!atom->rmass_flag && !atom->mass_setflag)
    error->all(FLERR, "fix lattice/nve needs particle masses: set them with 'set ... mass' "
               "(atom_style sphere) or the mass command");
  reset_dt();
  group_runs.invalidate();
  store = measuring_store();
  if (store && comm->me == 0) {
    if (igroup == 0)
      utils::logmesg(lmp, "fix {}: moves every atom and measures the steps for pair_style "
                     "lattice/bond (no separate displacement pass)\n", style);
    else
      utils::logmesg(lmp, "fix {}: measures the steps of group {} for pair_style lattice/bond; "
                     "the steps of the other atoms follow from their positions\n", style,
                     group->names[igroup]);
  }
}

/* ----------------------------------------------------------------------
   a run's setup: the group's members or the atoms' order may have changed
------------------------------------------------------------------------- */

void FixLatticeNVE::setup(int /*vflag*/)
{
  group_runs.invalidate();
}

/* ----------------------------------------------------------------------
   the record store of pair_style lattice/bond if this fix may measure the
   displacement over the step of each atom of its group while it moves it,
   else nullptr.  The store's own pass (x - last position) then has only the
   atoms outside the group left (platens moved by fix move, atoms at rest),
   or nothing for the group all.  Only when nothing else moves an atom of
   the group between two force evaluations: no other integrator or
   position-changing fix (initial/post-integrate hooks) acting on one of its
   atoms, no other fix lattice/nve (the store keeps one measured group), no
   box deformation remapping atoms, no fix acting before atoms migrate other
   than those known to leave the positions of existing atoms alone (Monte
   Carlo moves happen there), and no dynamic group (its atoms change
   between steps).  Collective: the groups' overlap is counted over all ranks
------------------------------------------------------------------------- */

FixLatticeBondStore *FixLatticeNVE::measuring_store() const
{
  auto *pair = PairLatticeBond::find(force);
  if (!pair || !pair->store() || group->dynamic[igroup]) return nullptr;
  const int nlocal = atom->nlocal;
  const int *const amask = atom->mask;
  for (int i = 0; i < modify->nfix; i++) {
    const Fix *other = modify->fix[i];
    if (other == this) continue;
    const int mask = modify->fmask[i];
    if (other->box_change || dynamic_cast<const FixLatticeNVE *>(other)) return nullptr;
    if ((mask & PRE_EXCHANGE) && !utils::strmatch(other->style, "^(balance|deposit|pour|evaporate)$"))
      return nullptr;
    if (!(mask & (INITIAL_INTEGRATE | POST_INTEGRATE))) continue;
    // another fix that may move atoms: only on atoms outside this group
    if (group->dynamic[other->igroup]) return nullptr;
    const int both = groupbit | other->groupbit;
    bigint shared = 0, shared_all = 0;
    for (int j = 0; j < nlocal; j++) shared += ((amask[j] & both) == both);
    MPI_Allreduce(&shared, &shared_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    if (shared_all > 0) return nullptr;
  }
  return pair->store();
}

/* ---------------------------------------------------------------------- */

void FixLatticeNVE::reset_dt()
{
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
  dtfm_type.assign(atom->ntypes + 1, 0.0);
  if (atom->mass)
    for (int t = 1; t <= atom->ntypes; t++) dtfm_type[t] = dtf / atom->mass[t];
  one_mass = !(atom->rmass_flag && atom->rmass) && atom->mass &&
      std::all_of(dtfm_type.begin() + 1, dtfm_type.end(), [&](double q) { return q == dtfm_type[1]; });
}

/* ---------------------------------------------------------------------- */

void FixLatticeNVE::initial_integrate(int /*vflag*/)
{
  dispatch(true);
}

/* ---------------------------------------------------------------------- */

void FixLatticeNVE::final_integrate()
{
  dispatch(false);
}

/* ----------------------------------------------------------------------
   the loop compiled for this case, over every atom's range (run_ranges)
------------------------------------------------------------------------- */

void FixLatticeNVE::dispatch(bool drift)
{
  const bool planar = domain->dimension == 2;
  const bool rmass = atom->rmass_flag && atom->rmass;
  const bool measure = drift && store;
  RangeFn loop;
  int n = (igroup == atom->firstgroup) ? atom->nfirst : atom->nlocal;
  // a group that is not all: in long runs of consecutive atoms the group-all
  // loop over each run, else the loop with the mask test
  const bool runs = (igroup != 0) && group_runs.usable(lmp, igroup, groupbit, n);
  const bool all = (igroup == 0) || runs;
  if (!planar && all && one_mass) {
    // 3D, every atom, one mass: x, v and f as flat streams of 3 nlocal values
    loop = drift ? (store ? &FixLatticeNVE::stream<true, true> : &FixLatticeNVE::stream<true, false>)
                 : &FixLatticeNVE::stream<false, false>;
  } else if (measure) {
    // 2D or 3D, group all or not, per-atom or per-type mass
    static constexpr RangeFn MEASURED[8] = {
        &FixLatticeNVE::drift_measured<false, false, false>, &FixLatticeNVE::drift_measured<false, false, true>,
        &FixLatticeNVE::drift_measured<false, true, false>,  &FixLatticeNVE::drift_measured<false, true, true>,
        &FixLatticeNVE::drift_measured<true, false, false>,  &FixLatticeNVE::drift_measured<true, false, true>,
        &FixLatticeNVE::drift_measured<true, true, false>,   &FixLatticeNVE::drift_measured<true, true, true>};
    loop = MEASURED[4 * planar + 2 * all + rmass];
  } else {
    // one compiled loop per case: 2D or 3D, group all or not, per-atom or
    // per-type mass, with or without the drift
    static constexpr RangeFn KICKS[16] = {
        &FixLatticeNVE::kick<false, false, false, false>, &FixLatticeNVE::kick<false, false, false, true>,
        &FixLatticeNVE::kick<false, false, true, false>,  &FixLatticeNVE::kick<false, false, true, true>,
        &FixLatticeNVE::kick<false, true, false, false>,  &FixLatticeNVE::kick<false, true, false, true>,
        &FixLatticeNVE::kick<false, true, true, false>,   &FixLatticeNVE::kick<false, true, true, true>,
        &FixLatticeNVE::kick<true, false, false, false>,  &FixLatticeNVE::kick<true, false, false, true>,
        &FixLatticeNVE::kick<true, false, true, false>,   &FixLatticeNVE::kick<true, false, true, true>,
        &FixLatticeNVE::kick<true, true, false, false>,   &FixLatticeNVE::kick<true, true, false, true>,
        &FixLatticeNVE::kick<true, true, true, false>,    &FixLatticeNVE::kick<true, true, true, true>};
    loop = KICKS[8 * planar + 4 * all + 2 * rmass + drift];
  }
  if (runs) {
    run_loop = loop;
    loop = &FixLatticeNVE::over_runs;
  }
  Measure m;
  if (measure) {
    m.disp = store->begin_measured_step(groupbit);
    m.cap = step_cap();
  }
  const bool ok = run_ranges(loop, n, m);
  if (measure) store->end_measured_step(ok);
}

/* ----------------------------------------------------------------------
   the loop over atoms 0..n-1 in one range (fix lattice/nve/omp: one per thread)
------------------------------------------------------------------------- */

bool FixLatticeNVE::run_ranges(RangeFn loop, int n, const Measure &m)
{
  return (this->*loop)(0, n, m);
}

/* ----------------------------------------------------------------------
   the group-all loop run_loop over the group's runs within begin..end-1
------------------------------------------------------------------------- */

bool FixLatticeNVE::over_runs(int begin, int end, const Measure &m)
{
  return group_runs.each_within(begin, end,
                                [&](int first, int last) { return (this->*run_loop)(first, last, m); });
}

/* ----------------------------------------------------------------------
   the longest step along an axis that is not an instability (the pair
   style's limit; a longer one, or NaN, makes the store report the atom)
------------------------------------------------------------------------- */

double FixLatticeNVE::step_cap() const
{
  const double limit = store->step_limit();
  return (limit > 0.0) ? limit : HUGE_VAL;
}

/* ----------------------------------------------------------------------
   3D, group all, one mass: the half kick (and with DRIFT the drift, with
   MEASURE measuring the steps as drift_measured does) over the components
   as one stream, without a per-atom mass or mask; the compiler vectorises
   it (except the step test of MEASURE); the same arithmetic per component
   as the other loops
------------------------------------------------------------------------- */

template <bool DRIFT, bool MEASURE> bool FixLatticeNVE::stream(int begin, int end, const Measure &m)
{
  double *__restrict const x = atom->x[0];
  double *__restrict const v = atom->v[0];
  const double *__restrict const f = atom->f[0];
  double *__restrict const disp = m.disp;
  const double dtfm = dtfm_type[1], dt = dtv;
  const int k0 = 3 * begin, k1 = 3 * end;
  const double cap = m.cap;
  int bad = 0;
  for (int k = k0; k < k1; k++) {
    v[k] += dtfm * f[k];
    if (DRIFT) {
      const double old = x[k];
      x[k] = old + dt * v[k];
      if (MEASURE) {
        const double step = x[k] - old;
        disp[k] = step;
        bad |= !(std::fabs(step) <= cap);    // true for NaN too
      }
    }
  }
  return !bad;
}

/* ----------------------------------------------------------------------
   half kick v += dt/2 f/m; with DRIFT also x += dt v
------------------------------------------------------------------------- */

template <bool PLANAR, bool ALL, bool RMASS, bool DRIFT>
bool FixLatticeNVE::kick(int begin, int end, const Measure &)
{
  double *__restrict const x = atom->x[0];
  double *__restrict const v = atom->v[0];
  const double *__restrict const f = atom->f[0];
  const double *const rmass = atom->rmass;
  const double *const dtfm_of = dtfm_type.data();
  const double dt = dtv;    // a local: the stores to x and v cannot change it
  const int *const type = atom->type;
  const int *const mask = atom->mask;
  MassQuotient quotient{dtf};

  for (int i = begin; i < end; i++) {
    if (!ALL && !(mask[i] & groupbit)) continue;
    const double dtfm = RMASS ? quotient.of(rmass[i]) : dtfm_of[type[i]];
    const int k = 3 * i;
    v[k] += dtfm * f[k];
    v[k + 1] += dtfm * f[k + 1];
    if (!PLANAR) v[k + 2] += dtfm * f[k + 2];
    if (DRIFT) {
      x[k] += dt * v[k];
      x[k + 1] += dt * v[k + 1];
      if (!PLANAR) x[k + 2] += dt * v[k + 2];
    }
  }
  return true;
}

/* ----------------------------------------------------------------------
   the drift half of the step for every atom of the group (ALL: every atom,
   no mask test), measuring each displacement for the record store: new - old
   position (the same operation, so the same bits, as the store's x - last
   position).  The old positions are not kept: the step's force evaluation
   is the next one that needs a last position, and after it that is the
   current one.  The triples of atoms outside the group are left alone: they
   hold those atoms' last positions (FixLatticeBondStore::begin_measured_step)
------------------------------------------------------------------------- */

template <bool PLANAR, bool ALL, bool RMASS>
bool FixLatticeNVE::drift_measured(int begin, int end, const Measure &m)
{
  constexpr int DIM = PLANAR ? 2 : 3;
  double *__restrict const x = atom->x[0];
  double *__restrict const v = atom->v[0];
  const double *__restrict const f = atom->f[0];
  double *__restrict const disp = m.disp;
  const double *const rmass = atom->rmass;
  const double *const dtfm_of = dtfm_type.data();
  const double dt = dtv;    // a local: the stores to x and v cannot change it
  const int *const type = atom->type;
  const int *const mask = atom->mask;
  MassQuotient quotient{dtf};
  const double cap = m.cap;
  int ok = 1;
  for (int i = begin; i < end; i++) {
    if (!ALL && !(mask[i] & groupbit)) continue;
    const double dtfm = RMASS ? quotient.of(rmass[i]) : dtfm_of[type[i]];
    for (int k = 3 * i; k < 3 * i + DIM; k++) {
      v[k] += dtfm * f[k];
      const double old = x[k];
      x[k] = old + dt * v[k];
      const double step = x[k] - old;
      disp[k] = step;
      ok &= (std::fabs(step) <= cap);
    }
  }
  return ok;
}
