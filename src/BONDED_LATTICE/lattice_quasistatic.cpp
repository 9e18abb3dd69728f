/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   lattice/quasistatic ftol F [relax minimize|run N] [maxsteps M]
                              [break one|all] [maxbreak K] [quiet yes|no]

   Breaking is switched off in pair_style lattice/bond while the command
   runs, so that a relaxation only finds the equilibrium of the network as
   it is; the command then breaks bonds itself, by their break_ratio():
   - break one (the Mike/Elle seed): the single bond with the largest ratio,
     ties broken by the lower pair of atom IDs, so that the order of events
     is the same on any number of ranks;
   - break all: every bond whose ratio exceeds 1.
   Relaxation methods (docs/lattice_quasistatic.rst explains the choice):
   - minimize: LAMMPS' minimiser (min_style as set by the input) with the
     largest force component as its norm.  The energy of a network without
     shear springs (Ks = 0, the seed's central springs) is a function of the
     positions alone, so its minimum is the exact equilibrium; shear springs
     depend on the path and are refused;
   - run N: damped dynamics with the input's integrator and damping fixes, in
     runs of N steps until the largest force component is below ftol.
------------------------------------------------------------------------- */

#include "lattice_quasistatic.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "exceptions.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "input.h"
#include "pair_lattice_bond.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

// a relaxation may move a particle by at most this fraction of the smallest
// radius in one line-search step (min_modify dmax): bonds stay within reach
static constexpr double DMAX_FRACTION = 0.05;

/* ---------------------------------------------------------------------- */

void LatticeQuasistatic::command(int narg, char **arg)
{
  pair = dynamic_cast<PairLatticeBond *>(force->pair_match("lattice/bond", 1));
  if (!pair) error->all(FLERR, "lattice/quasistatic requires pair_style lattice/bond");
  if (narg < 2 || strcmp(arg[0], "ftol") != 0)
    error->all(FLERR, "lattice/quasistatic needs: ftol F [relax minimize|run N] [maxsteps M] "
               "[break one|all] [maxbreak K] [quiet yes|no]");
  ftol = utils::numeric(FLERR, arg[1], false, lmp);
  if (!(ftol > 0.0))
    error->all(FLERR, "lattice/quasistatic ftol {} is out of range: need > 0 (force units, the "
               "largest force component left on a particle)", ftol);
  int iarg = 2;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 1 >= narg) error->all(FLERR, "lattice/quasistatic keyword {} needs a value", key);
    const std::string value = arg[iarg + 1];
    if (key == "relax") {
      if (value == "minimize") {
        minimize = true;
      } else if (value == "run") {
        if (iarg + 2 >= narg)
          error->all(FLERR, "lattice/quasistatic relax run needs the steps between force checks");
        minimize = false;
        chunk = utils::bnumeric(FLERR, arg[iarg + 2], false, lmp);
        if (chunk < 1)
          error->all(FLERR, "lattice/quasistatic relax run {} is out of range: need >= 1 step",
                     chunk);
        iarg++;
      } else {
        error->all(FLERR, "lattice/quasistatic relax {} is not valid: use minimize or run N", value);
      }
    } else if (key == "maxsteps") {
      maxsteps = utils::bnumeric(FLERR, value.c_str(), false, lmp);
      if (maxsteps < 1)
        error->all(FLERR, "lattice/quasistatic maxsteps {} is out of range: need >= 1", maxsteps);
    } else if (key == "break") {
      if (value == "one") break_all = false;
      else if (value == "all") break_all = true;
      else error->all(FLERR, "lattice/quasistatic break {} is not valid: use one or all", value);
    } else if (key == "maxbreak") {
      maxbreak = utils::bnumeric(FLERR, value.c_str(), false, lmp);
      if (maxbreak < 0)
        error->all(FLERR, "lattice/quasistatic maxbreak {} is out of range: need >= 0", maxbreak);
    } else if (key == "quiet") {
      quiet = utils::logical(FLERR, value, false, lmp);
    } else {
      error->all(FLERR, "Unknown lattice/quasistatic keyword {}: valid are relax, maxsteps, break, "
                 "maxbreak, quiet", key);
    }
    iarg += 2;
  }

  pair->enable_breaking(false);
  bigint steps = 0, relaxations = 0, broken = 0;
  int tension = 0, shear = 0;
  double worst = 0.0;
  while (true) {
    steps += relax();
    relaxations++;
    if (maxbreak >= 0 && broken >= maxbreak) break;
    tagint owner = 0, partner = 0;
    BreakMode mode = BreakMode::None;
    worst = worst_bond(owner, partner, mode);
    if (!(worst > 1.0)) break;
    if (break_all) {
      broken += break_beyond_threshold(tension, shear);
    } else {
      const int i = atom->map(owner);
      if (i >= 0 && i < atom->nlocal) {
        const tagint *pt = pair->store()->partners(i);
        for (int s = 0; s < pair->store()->record_count(i); s++)
          if (pt[s] == partner) pair->break_record(i, s, mode);
      }
      broken++;
      (mode == BreakMode::Tension ? tension : shear)++;
    }
  }
  pair->enable_breaking(true);

  if (comm->me == 0)
    utils::logmesg(lmp, "lattice/quasistatic: {} bonds broke ({} in tension, {} in shear) in {} "
                   "relaxations ({} {}); largest remaining ratio to the threshold {:.6g}\n",
                   broken, tension, shear, relaxations, steps,
                   minimize ? "minimiser iterations" : "time steps", worst);
}

/* ----------------------------------------------------------------------
   one relaxation to the force tolerance
------------------------------------------------------------------------- */

bigint LatticeQuasistatic::relax()
{
  const bigint start = update->ntimestep;
  if (minimize) {
    if (pair->has_shear_springs())
      error->all(FLERR, "lattice/quasistatic relax minimize needs bonds without shear springs "
                 "(Ks = 0 for every type pair): a shear spring depends on the path, not only on "
                 "the positions, so a minimiser's line search changes it. Use relax run N with "
                 "fix lattice/nve and fix lattice/viscous (damped dynamics)");
    // line-search steps no longer than a small part of a particle
    const double radius = pair->smallest_radius();
    if (radius > 0.0)
      command_quietly(fmt::format("min_modify dmax {:.17g} norm max", DMAX_FRACTION * radius));
    else command_quietly("min_modify norm max");
    command_quietly(fmt::format("minimize 0.0 {:.17g} {} {}", ftol, maxsteps, 10 * maxsteps));
    if (largest_force() > ftol && comm->me == 0)
      error->warning(FLERR, "lattice/quasistatic: the minimiser stopped with a force component of "
                     "{:.6g} above ftol {:.6g} (raise maxsteps, or check min_style)",
                     largest_force(), ftol);
    return update->ntimestep - start;
  }
  bigint done = 0;
  bool first = true;
  while (done < maxsteps) {
    const bigint n = MIN(chunk, maxsteps - done);
    command_quietly(fmt::format("run {} pre {} post no", n, first ? "yes" : "no"));
    first = false;
    done += n;
    if (largest_force() <= ftol) return done;
  }
  if (comm->me == 0)
    error->warning(FLERR, "lattice/quasistatic: {} steps did not relax the largest force component "
                   "({:.6g}) below ftol {:.6g}; raise maxsteps or the damping", maxsteps,
                   largest_force(), ftol);
  return done;
}

/* ----------------------------------------------------------------------
   one input line; with quiet yes its output (echo, thermo, the minimiser's
   and the run's summaries) goes nowhere.  An error still stops the input and
   is printed once the output streams are back
------------------------------------------------------------------------- */

void LatticeQuasistatic::command_quietly(const std::string &line)
{
  if (!quiet) {
    input->one(line);
    return;
  }
  struct Restore {
    LAMMPS *lmp;
    FILE *screen, *logfile;
    ~Restore()
    {
      lmp->screen = screen;
      lmp->logfile = logfile;
    }
  } restore{lmp, lmp->screen, lmp->logfile};
  lmp->screen = nullptr;
  lmp->logfile = nullptr;
  try {
    input->one(line);
  } catch (LAMMPSException &e) {
    // the error was not printed (no output streams): print it with them back
    lmp->screen = restore.screen;
    lmp->logfile = restore.logfile;
    if (comm->me == 0) {
      const std::string text = e.what();
      utils::logmesg(lmp, "{}{} (in lattice/quasistatic: {})\n",
                     utils::strmatch(text, "^ERROR") ? "" : "ERROR: ", utils::trim(text), line);
    }
    throw;
  }
}

/* ---------------------------------------------------------------------- */

double LatticeQuasistatic::largest_force() const
{
  double local = 0.0, global = 0.0;
  double **f = atom->f;
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < 3; k++) local = MAX(local, std::fabs(f[i][k]));
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, world);
  return global;
}

/* ----------------------------------------------------------------------
   the intact bond with the largest ratio to its threshold over all ranks;
   equal ratios go to the lowest (owner, partner) IDs
------------------------------------------------------------------------- */

double LatticeQuasistatic::worst_bond(tagint &owner, tagint &partner, BreakMode &mode) const
{
  FixLatticeBondStore *store = pair->store();
  const tagint *tag = atom->tag;
  double best = 0.0;
  tagint best_owner = MAXTAGINT, best_partner = MAXTAGINT;
  BreakMode best_mode = BreakMode::None;
  for (int i = 0; i < atom->nlocal; i++) {
    const tagint *pt = store->partners(i);
    for (int s = 0; s < store->record_count(i); s++) {
      BreakMode m;
      const double ratio = pair->break_ratio(i, s, m);
      if (m == BreakMode::None) continue;
      const bool lower = tag[i] < best_owner || (tag[i] == best_owner && pt[s] < best_partner);
      if (ratio > best || (ratio == best && lower)) {
        best = ratio;
        best_owner = tag[i];
        best_partner = pt[s];
        best_mode = m;
      }
    }
  }
  double worst = 0.0;
  MPI_Allreduce(&best, &worst, 1, MPI_DOUBLE, MPI_MAX, world);
  // among the bonds of that ratio, the lowest IDs (and their mode)
  tagint mine[2] = {best == worst ? best_owner : MAXTAGINT, best == worst ? best_partner : MAXTAGINT};
  tagint low_owner = MAXTAGINT;
  MPI_Allreduce(&mine[0], &low_owner, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  if (mine[0] != low_owner) mine[1] = MAXTAGINT;
  tagint low_partner = MAXTAGINT;
  MPI_Allreduce(&mine[1], &low_partner, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  // (as an int; None = 0 is below both modes)
  int my_mode = (mine[0] == low_owner && mine[1] == low_partner) ? (int) best_mode : 0, the_mode = 0;
  MPI_Allreduce(&my_mode, &the_mode, 1, MPI_INT, MPI_MAX, world);
  owner = low_owner;
  partner = low_partner;
  mode = static_cast<BreakMode>(the_mode);
  return worst;
}

/* ----------------------------------------------------------------------
   break all: every intact bond past its threshold; returns how many (all ranks)
------------------------------------------------------------------------- */

bigint LatticeQuasistatic::break_beyond_threshold(int &tension, int &shear)
{
  FixLatticeBondStore *store = pair->store();
  int counts[2] = {0, 0}, all[2] = {0, 0};
  for (int i = 0; i < atom->nlocal; i++)
    for (int s = 0; s < store->record_count(i); s++) {
      BreakMode m;
      if (pair->break_ratio(i, s, m) > 1.0 && m != BreakMode::None) {
        pair->break_record(i, s, m);
        counts[m == BreakMode::Tension ? 0 : 1]++;
      }
    }
  MPI_Allreduce(counts, all, 2, MPI_INT, MPI_SUM, world);
  tension += all[0];
  shear += all[1];
  return (bigint) all[0] + all[1];
}
