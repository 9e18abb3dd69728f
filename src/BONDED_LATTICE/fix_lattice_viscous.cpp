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
#include "error.h"
#include "update.h"

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
  return POST_FORCE;
}

/* ---------------------------------------------------------------------- */

void FixLatticeViscous::setup(int vflag)
{
  if (!fdamp_valid) {
    damp(false);
    return;
  }
  double **f = atom->f;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) {
      f[i][0] += hist[i][0];
      f[i][1] += hist[i][1];
      f[i][2] += hist[i][2];
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
  double **v = atom->v;
  double **f = atom->f;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  if (tally_flag && step_taken) {
    double work = 0.0;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        const double fx = -eta * v[i][0], fy = -eta * v[i][1], fz = -eta * v[i][2];
        work += (hist[i][0] + fx) * v[i][0] + (hist[i][1] + fy) * v[i][1] +
            (hist[i][2] + fz) * v[i][2];
      }
    heat -= 0.5 * update->dt * work;
  }
  if (igroup == 0) {
    // group all: one straight pass over the contiguous arrays
    const double *vv = v[0];
    double *ff = f[0], *hh = hist[0];
    const int n = 3 * nlocal;
    for (int m = 0; m < n; m++) {
      hh[m] = -eta * vv[m];
      ff[m] += hh[m];
    }
  } else {
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        hist[i][0] = -eta * v[i][0];
        hist[i][1] = -eta * v[i][1];
        hist[i][2] = -eta * v[i][2];
        f[i][0] += hist[i][0];
        f[i][1] += hist[i][1];
        f[i][2] += hist[i][2];
      }
  }
  fdamp_valid = 1;
}

/* ----------------------------------------------------------------------
   an atom created during a run: damp it with its own velocity
------------------------------------------------------------------------- */

void FixLatticeViscous::set_arrays(int i)
{
  for (int k = 0; k < 3; k++) hist[i][k] = -eta * atom->v[i][k];
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
