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
  // 2D: x and y only (the z velocity of a 2D particle is zero)
  if (domain->dimension == 2) damp_components<2>(step_taken);
  else damp_components<3>(step_taken);
  fdamp_valid = 1;
}

template <int DIM> void FixLatticeViscous::damp_components(bool step_taken)
{
  const auto *const v = reinterpret_cast<const double(*)[3]>(atom->v[0]);
  auto *const f = reinterpret_cast<double(*)[3]>(atom->f[0]);
  auto *const h = reinterpret_cast<double(*)[3]>(hist[0]);
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  if (nlocal == 0) return;
  if (tally_flag && step_taken) {
    double work = 0.0;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        double wi = 0.0;
        for (int k = 0; k < DIM; k++) wi += (h[i][k] - eta * v[i][k]) * v[i][k];
        work += wi;
      }
    heat -= 0.5 * update->dt * work;
  }
  const bool all = (igroup == 0);    // group all: no mask test
  for (int i = 0; i < nlocal; i++) {
    if (!all && !(mask[i] & groupbit)) continue;
    for (int k = 0; k < DIM; k++) {
      h[i][k] = -eta * v[i][k];
      f[i][k] += h[i][k];
    }
  }
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
