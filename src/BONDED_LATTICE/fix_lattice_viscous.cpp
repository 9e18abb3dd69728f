/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   fix lattice/viscous: F = -eta * v on every atom of the group
   (Liu et al. 2013 eq. 7; Li et al. 2018 eq. 8).
------------------------------------------------------------------------- */

#include "fix_lattice_viscous.h"

#include "atom.h"
#include "error.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixLatticeViscous::FixLatticeViscous(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (narg != 4)
    error->all(FLERR, "Illegal fix lattice/viscous command: expected fix ID group lattice/viscous eta");
  eta = utils::numeric(FLERR, arg[3], false, lmp);
  if (!(eta >= 0.0))
    error->all(FLERR, "fix lattice/viscous eta = {} is out of range: need eta >= 0 (force/velocity)",
               eta);
  dynamic_group_allow = 1;
}

/* ---------------------------------------------------------------------- */

int FixLatticeViscous::setmask()
{
  return POST_FORCE;
}

/* ---------------------------------------------------------------------- */

void FixLatticeViscous::setup(int vflag)
{
  post_force(vflag);
}

/* ---------------------------------------------------------------------- */

void FixLatticeViscous::post_force(int /*vflag*/)
{
  double **v = atom->v;
  double **f = atom->f;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) {
      f[i][0] -= eta * v[i][0];
      f[i][1] -= eta * v[i][1];
      f[i][2] -= eta * v[i][2];
    }
}
