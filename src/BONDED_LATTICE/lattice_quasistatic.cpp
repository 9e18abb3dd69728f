/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   lattice/quasistatic ftol F [relax minimize|run N|local|direct] [omega W]
                              [maxsteps M] [break one|all] [maxbreak K] [quiet yes|no]
                              [threads N]

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
     runs of N steps until the largest force component is below ftol;
   - local: over-relaxation of the particles whose force exceeds ftol only
     (LatticeLocalRelax), so that a break costs work where it changes the
     forces; central springs only, as minimize;
   - direct: exact linear equilibria with a sparse Cholesky factor kept
     from one break to the next by rank-one changes (LatticeDirectRelax),
     passes ended by the pair style's forces; central springs only.
------------------------------------------------------------------------- */

#include "lattice_quasistatic.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "exceptions.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "lattice_direct_relax.h"
#include "lattice_local_relax.h"
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
  pair = PairLatticeBond::find(force);
  if (!pair) error->all(FLERR, "lattice/quasistatic requires pair_style lattice/bond");
  if (narg < 2 || strcmp(arg[0], "ftol") != 0)
    error->all(FLERR, "lattice/quasistatic needs: ftol F [relax minimize|run N|local|direct] [omega W] "
               "[maxsteps M] [break one|all] [maxbreak K] [quiet yes|no] [threads N]");
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
      direct = false;
      if (value == "minimize") {
        minimize = true;
        local = false;
      } else if (value == "local") {
        minimize = false;
        local = true;
      } else if (value == "direct") {
        minimize = false;
        local = false;
        direct = true;
      } else if (value == "run") {
        if (iarg + 2 >= narg)
          error->all(FLERR, "lattice/quasistatic relax run needs the steps between force checks");
        minimize = false;
        local = false;
        chunk = utils::bnumeric(FLERR, arg[iarg + 2], false, lmp);
        if (chunk < 1)
          error->all(FLERR, "lattice/quasistatic relax run {} is out of range: need >= 1 step",
                     chunk);
        iarg++;
      } else {
        error->all(FLERR, "lattice/quasistatic relax {} is not valid: use minimize, run N, local or direct",
                   value);
      }
    } else if (key == "omega") {
      omega = utils::numeric(FLERR, value, false, lmp);
      if (!(omega > 0.0 && omega < 2.0))
        error->all(FLERR, "lattice/quasistatic omega {} is out of range: need 0 < omega < 2 (the "
                   "over-relaxation factor of relax local; 1 is Gauss-Seidel)", omega);
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
    } else if (key == "breaks") {
      breaks_file = value;
    } else if (key == "quiet") {
      quiet = utils::logical(FLERR, value, false, lmp);
    } else if (key == "threads") {
      threads = utils::inumeric(FLERR, value, false, lmp);
      if (threads < 1)
        error->all(FLERR, "lattice/quasistatic threads {} is out of range: need >= 1 (the threads "
                   "of relax direct's factor and solves on rank 0)", threads);
    } else {
      error->all(FLERR, "Unknown lattice/quasistatic keyword {}: valid are relax, omega, maxsteps, "
                 "break, maxbreak, breaks, quiet, threads", key);
    }
    iarg += 2;
  }

  if (!breaks_file.empty() && comm->me == 0) {
    breaks_fp = fopen(breaks_file.c_str(), "a");
    if (!breaks_fp)
      error->one(FLERR, "lattice/quasistatic breaks: cannot open {} for appending: {}", breaks_file,
                 utils::getsyserror());
  }
  pair->enable_breaking(false);
  bigint steps = 0, relaxations = 0, broken = 0, moves = 0;
  int tension = 0, shear = 0;
  double worst = 0.0;
  if (local) {
    run_local(broken, tension, shear, relaxations, steps, moves, worst);
  } else if (direct) {
    run_direct(broken, tension, shear, relaxations, steps, moves, worst);
  } else {
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
        record_break(owner, partner, mode, worst);
        broken++;
        (mode == BreakMode::Tension ? tension : shear)++;
      }
    }
  }
  if (breaks_fp) {
    fclose(breaks_fp);
    breaks_fp = nullptr;
  }
  pair->enable_breaking(true);

  if (comm->me == 0)
    utils::logmesg(lmp, "lattice/quasistatic: {} bonds broke ({} in tension, {} in shear) in {} "
                   "relaxations ({} {}); largest remaining ratio to the threshold {:.6g}\n",
                   broken, tension, shear, relaxations, steps,
                   local ? fmt::format("sweeps, {} particle moves", moves)
                         : direct ? fmt::format("solves, {} factorisations", moves)
                         : (minimize ? "minimiser iterations" : "time steps"), worst);
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
   is printed once the output streams are back.  Its warnings do not count
   against the limit of thermo_modify warn (100 by default): a run without
   time integration warns once per relaxation, and after the limit LAMMPS
   drops every warning, later ones of this command and of the input included
------------------------------------------------------------------------- */

void LatticeQuasistatic::command_quietly(const std::string &line)
{
  struct KeepWarnings {
    Error *error;
    int numwarn;
    ~KeepWarnings() { error->set_numwarn(numwarn); }
  } keep{error, error->get_numwarn()};
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
  owner = best_owner;
  partner = best_partner;
  mode = best_mode;
  return reduce_worst(best, owner, partner, mode);
}

double LatticeQuasistatic::reduce_worst(double best, tagint &owner, tagint &partner,
                                        BreakMode &mode) const
{
  const tagint best_owner = owner, best_partner = partner;
  const BreakMode best_mode = mode;
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

/* ----------------------------------------------------------------------
   relax local: passes of (force evaluation, set-up, relax and break until
   no bond exceeds its threshold or a particle moved too far for the ghosts
   and records of that evaluation).  A pass in which something moved or
   broke is followed by another, whose force evaluation checks the state
   with the pair style's own records (new contacts included)
------------------------------------------------------------------------- */

void LatticeQuasistatic::run_local(bigint &broken, int &tension, int &shear, bigint &relaxations,
                                   bigint &sweeps, bigint &moves, double &worst)
{
  LatticeLocalRelax lr(lmp, pair, ftol, omega);
  lr.check_model();
  // passes in a row that broke nothing: each ends because particles moved far (then the
  // next goes on from there) or to check a pass's end state; a thousand means the
  // relaxation does not settle (e.g. contacts that open and close between passes)
  static constexpr int MAX_IDLE_PASSES = 1000;
  int idle = 0;
  bool done = false;
  while (!done) {
    if (++idle > MAX_IDLE_PASSES) {
      if (comm->me == 0)
        error->warning(FLERR, "lattice/quasistatic relax local: {} passes without a break did not "
                       "settle (largest force component {:.6g}, ftol {:.6g}); stopping with the bonds "
                       "as they are (try relax minimize)", MAX_IDLE_PASSES, lr.largest_force(), ftol);
      break;
    }
    lr.probe_fixes();
    command_quietly("run 0 post no");
    lr.set_up();
    bool changed = false;
    while (true) {
      const bigint before = sweeps;
      const auto outcome = lr.relax(maxsteps, sweeps, moves);
      if (sweeps > before) changed = true;
      if (outcome == LatticeLocalRelax::Outcome::MOVED_FAR) break;
      if (outcome == LatticeLocalRelax::Outcome::SWEEPS && comm->me == 0)
        error->warning(FLERR, "lattice/quasistatic: {} sweeps did not relax the largest force "
                       "component ({:.6g}) below ftol {:.6g}; raise maxsteps", maxsteps,
                       lr.largest_force(), ftol);
      relaxations++;
      tagint owner = 0, partner = 0;
      BreakMode mode = BreakMode::None;
      const double best = lr.worst(owner, partner, mode);
      worst = reduce_worst(best, owner, partner, mode);
      if (!(worst > 1.0) || (maxbreak >= 0 && broken >= maxbreak)) {
        done = !changed;
        break;
      }
      changed = true;
      if (break_all) {
        idle = 0;
        broken += lr.break_beyond_threshold(tension, shear);
        continue;
      }
      idle = 0;
      lr.break_spring(owner, partner, mode);
      record_break(owner, partner, mode, worst);
      broken++;
      (mode == BreakMode::Tension ? tension : shear)++;
    }
  }
}

/* ----------------------------------------------------------------------
   keyword breaks: timestep, owner and partner IDs, mode and ratio of a
   bond this command broke (break one), appended to the file
------------------------------------------------------------------------- */

void LatticeQuasistatic::record_break(tagint owner, tagint partner, BreakMode mode, double ratio)
{
  if (!breaks_fp) return;
  fmt::print(breaks_fp, "{} {} {} {} {:.17g}\n", update->ntimestep, owner, partner,
             mode == BreakMode::Tension ? "tension" : "shear", ratio);
}

/* ----------------------------------------------------------------------
   relax direct: passes of (force evaluation, and, unless no force component
   exceeds ftol and no bond its threshold, rank 0's Newton steps and breaks,
   LatticeDirectRelax::pass).  Counts solves in `solves` and factorisations
   in `factorisations`
------------------------------------------------------------------------- */

void LatticeQuasistatic::run_direct(bigint &broken, int &tension, int &shear, bigint &relaxations,
                                    bigint &solves, bigint &factorisations, double &worst)
{
  LatticeDirectRelax dr(lmp, pair, ftol, threads);
  dr.check_model();
  // passes in a row that broke nothing: a pass ends without a break when its
  // end state needs checking (moved particles, new contacts) or an equilibrium
  // took too many Newton steps; a hundred means it does not settle
  static constexpr int MAX_IDLE_PASSES = 100;
  int idle = 0;
  while (true) {
    dr.probe_fixes();
    command_quietly("run 0 post no");
    const double largest = largest_force();
    tagint owner = 0, partner = 0;
    BreakMode mode = BreakMode::None;
    worst = worst_bond(owner, partner, mode);
    const bool more = !(maxbreak >= 0 && broken >= maxbreak) && worst > 1.0;
    if (largest <= ftol && !more) break;
    if (++idle > MAX_IDLE_PASSES) {
      if (comm->me == 0)
        error->warning(FLERR, "lattice/quasistatic relax direct: {} passes without a break did "
                       "not bring the largest force component ({:.6g}) below ftol {:.6g}; stopping "
                       "with the bonds as they are", MAX_IDLE_PASSES, largest, ftol);
      break;
    }
    // the breaks go to the file as rank 0 makes them (flushed: the progress of an avalanche)
    const auto out = dr.pass(maxbreak < 0 ? -1 : maxbreak - broken, break_all,
                             [this](const LatticeDirectRelax::Break &b) {
                               record_break(b.owner, b.partner, b.mode, b.ratio);
                               if (breaks_fp) fflush(breaks_fp);
                             });
    relaxations++;
    solves += out.solves;
    factorisations += out.factorised;
    for (const auto &b : out.breaks) {
      broken++;
      (b.mode == BreakMode::Tension ? tension : shear)++;
    }
    if (!out.breaks.empty()) idle = 0;
  }
}
