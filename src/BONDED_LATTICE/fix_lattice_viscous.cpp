/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   fix lattice/viscous: F = -eta * v on every atom of the group
   (Liu et al. 2013 section 5, damping value eq. 34; Li et al. 2018 eq. 9).

   As in the papers' leapfrog scheme the force uses the velocity available
   at force time, v(t - dt/2).  At the start of a later run (or after
   read_restart) only v(t) is known, so the force of the last step is kept
   per atom and reapplied: a run split in pieces, or interrupted by a
   restart, follows the same trajectory as one uninterrupted run.
------------------------------------------------------------------------- */

#include "fix_lattice_viscous.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "output.h"
#include "update.h"

#include <type_traits>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixLatticeViscous::FixLatticeViscous(LAMMPS *lmp, int narg, char **arg) :
    FixLatticeAtomHistory(lmp, narg, arg), tally_flag(0), heat(0.0), fdamp_valid(0)
{
  if (narg != 4)
    error->all(FLERR, "Illegal fix lattice/viscous command: expected fix ID group lattice/viscous eta");
  eta = utils::numeric(FLERR, arg[3], false, lmp);
  if (!(eta >= 0.0))
    error->all(FLERR, "fix lattice/viscous eta = {} is out of range: need eta >= 0 (force/velocity)",
               eta);
  dynamic_group_allow = 1;
  restart_global = 1;
  create_history(3);
}

/* ---------------------------------------------------------------------- */

int FixLatticeViscous::setmask()
{
  return POST_FORCE | POST_RUN;
}

/* ---------------------------------------------------------------------- */

void FixLatticeViscous::setup(int vflag)
{
  group_runs.invalidate();    // the group's members or the atoms' order may have changed
  if (!fdamp_valid) {
    damp(false);
    return;
  }
  double **f = atom->f;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) {
      const double *h = history(i);
      f[i][0] += h[0];
      f[i][1] += h[1];
      f[i][2] += h[2];
    }
}

/* ---------------------------------------------------------------------- */

void FixLatticeViscous::post_force(int /*vflag*/)
{
  damp(true);
}

/* ----------------------------------------------------------------------
   F = -eta v with the velocity at force time, v(t - dt/2) = the step's
   displacement / dt; the heat of a step is minus the work of the damping
   force over it, trapezoidal in the old and new force (as velocity Verlet
   conserves energy), counted only for a step actually taken
------------------------------------------------------------------------- */

void FixLatticeViscous::damp(bool step_taken)
{
  // the force is kept only where it is needed: for the heat (trapezoidal in
  // the old and new force), at the setup, and at the steps a run ends on or a
  // restart file is written (the next setup reapplies it); elsewhere writing it
  // would add a third of the loop's memory traffic
  const bigint step = update->ntimestep;
  const bool keep = tally_flag || !step_taken || step == update->laststep ||
      (output->restart_flag && step == output->next_restart);
  const bool all = (igroup == 0);    // group all: no mask test
  // 2D: x and y only (the z velocity of a 2D particle is zero)
  using Loop = void (FixLatticeViscous::*)(bool);
  static constexpr Loop LOOPS[8] = {
      &FixLatticeViscous::damp_components<3, false, false>,
      &FixLatticeViscous::damp_components<3, false, true>,
      &FixLatticeViscous::damp_components<3, true, false>,
      &FixLatticeViscous::damp_components<3, true, true>,
      &FixLatticeViscous::damp_components<2, false, false>,
      &FixLatticeViscous::damp_components<2, false, true>,
      &FixLatticeViscous::damp_components<2, true, false>,
      &FixLatticeViscous::damp_components<2, true, true>};
  (this->*LOOPS[4 * (domain->dimension == 2) + 2 * all + keep])(step_taken);
  fdamp_valid = keep ? 1 : 0;
}

template <int DIM, bool ALL, bool KEEP> void FixLatticeViscous::damp_components(bool step_taken)
{
  const double *__restrict const v = atom->v[0];
  double *__restrict const f = atom->f[0];
  double *__restrict const h = hist;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  if (nlocal == 0) return;
  if (tally_flag && step_taken) {
    double work = 0.0;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        double wi = 0.0;
        for (int k = 0; k < DIM; k++) wi += (h[3 * i + k] - eta * v[3 * i + k]) * v[3 * i + k];
        work += wi;
      }
    heat -= 0.5 * update->dt * work;
  }
  const double minus_eta = -eta;
  // atoms first..last-1 (TEST: only those of the group)
  auto loop = [&](int first, int last, auto test) {
    for (int i = first; i < last; i++) {
      if (decltype(test)::value && !(mask[i] & groupbit)) continue;
      for (int k = 0; k < DIM; k++) {
        const double fd = minus_eta * v[3 * i + k];
        if (KEEP) h[3 * i + k] = fd;
        f[3 * i + k] += fd;
      }
    }
  };
  if (ALL) {
    loop(0, nlocal, std::false_type());
  } else if (group_runs.usable(lmp, igroup, groupbit, nlocal)) {
    // a group in long runs of consecutive atoms: each run without the mask test
    group_runs.each_within(0, nlocal, [&](int first, int last) {
      loop(first, last, std::false_type());
      return true;
    });
  } else {
    loop(0, nlocal, std::true_type());
  }
}

/* ----------------------------------------------------------------------
   a run cut short (fix halt, timer timeout) may end on a step whose force
   was not kept: the next setup then damps with the velocity it has
------------------------------------------------------------------------- */

void FixLatticeViscous::post_run()
{
  if (update->ntimestep != update->laststep && !tally_flag) fdamp_valid = 0;
}

/* ----------------------------------------------------------------------
   an atom created during a run: damp it with its own velocity
------------------------------------------------------------------------- */

void FixLatticeViscous::set_arrays(int i)
{
  for (int k = 0; k < 3; k++) history(i)[k] = -eta * atom->v[i][k];
}

/* ---------------------------------------------------------------------- */

void FixLatticeViscous::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    double list[2] = {(double) fdamp_valid, eta};
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 2, fp);
  }
}

/* ----------------------------------------------------------------------
   the stored force is reused only if eta is unchanged
------------------------------------------------------------------------- */

void FixLatticeViscous::restart(char *buf)
{
  auto list = (double *) buf;
  fdamp_valid = (static_cast<int>(list[0]) == 1 && list[1] == eta) ? 1 : 0;
}
