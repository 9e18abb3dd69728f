/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   LatticeRelaxModel: what the relaxations of a central-spring network
   accept, and the components the fixes hold (lattice_relax_model.h)
------------------------------------------------------------------------- */

#include "lattice_relax_model.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "modify.h"
#include "pair_lattice_bond.h"

#include <string>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   what the method cannot treat: shear springs (the path matters), other
   force styles, fixes that add forces in a minimisation
------------------------------------------------------------------------- */

void LatticeRelaxModel::check(LAMMPS *lmp, PairLatticeBond *pair, const char *method)
{
  Error *error = lmp->error;
  Force *force = lmp->force;
  if (pair->has_shear_springs())
    error->all(FLERR, "lattice/quasistatic {} needs bonds without shear springs (Ks = 0 "
               "for every type pair): a shear spring depends on the path of the particles, not "
               "only on their positions. Use relax run N with fix lattice/nve and fix "
               "lattice/viscous (damped dynamics)", method);
  if (force->pair != (Pair *) pair)
    error->all(FLERR, "lattice/quasistatic {} needs pair_style lattice/bond alone (not "
               "in pair_style hybrid): it relaxes the forces of the bonds only. Use relax minimize", method);
  if (force->kspace || force->bond || force->angle || force->dihedral || force->improper)
    error->all(FLERR, "lattice/quasistatic {} relaxes the forces of pair_style "
               "lattice/bond only, and this input defines other force styles (kspace, bond, "
               "angle, dihedral or improper). Use relax minimize", method);
  for (const auto &fix : lmp->modify->get_fix_list()) {
    const int mask = fix->setmask();
    const std::string style = fix->style;
    const bool holds = utils::strmatch(style, "^setforce") || utils::strmatch(style, "^enforce2d");
    if ((mask & FixConst::MIN_ENERGY) || ((mask & FixConst::MIN_POST_FORCE) && !holds))
      error->all(FLERR, "lattice/quasistatic {} cannot include the forces of fix {} "
                 "(style {}), which acts in a minimisation: only fix setforce (holding components "
                 "at 0.0) and fix enforce2d are treated. Use relax minimize", method, fix->id, style);
  }
}

/* ----------------------------------------------------------------------
   which force components the fixes hold at zero: each fix that acts in a
   minimisation is given forces of 1 and then 2; a component it keeps is
   free, one it sets to 0 both times is held, anything else is refused.
   Called before a force evaluation (which then recomputes what the fixes
   report, e.g. fix setforce's vector)
------------------------------------------------------------------------- */

std::vector<tagint> LatticeRelaxModel::held_components(LAMMPS *lmp, const char *method)
{
  Atom *atom = lmp->atom;
  Domain *domain = lmp->domain;
  Comm *comm = lmp->comm;
  Error *error = lmp->error;
  MPI_Comm world = lmp->world;
  const int nlocal = atom->nlocal;
  const int planar = (domain->dimension == 2) ? 4 : 0;    // z is held in 2D anyway
  double **f = atom->f;
  std::vector<unsigned char> bits(nlocal, 0);
  std::vector<double> saved(3 * (size_t) nlocal), first(3 * (size_t) nlocal);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) saved[3 * i + k] = f[i][k];
  for (const auto &fix : lmp->modify->get_fix_list()) {
    if (!(fix->setmask() & FixConst::MIN_POST_FORCE)) continue;
    for (int pass = 0; pass < 2; pass++) {
      for (int i = 0; i < nlocal; i++)
        for (int k = 0; k < 3; k++) f[i][k] = pass + 1.0;
      fix->min_post_force(0);
      for (int i = 0; i < nlocal; i++)
        for (int k = 0; k < 3; k++) {
          const double out = f[i][k];
          if (pass == 0) {
            first[3 * i + k] = out;
            continue;
          }
          if (first[3 * i + k] == 1.0 && out == 2.0) continue;
          if (first[3 * i + k] == 0.0 && out == 0.0) {
            bits[i] |= (unsigned char) (1 << k);
            continue;
          }
          error->one(FLERR, "lattice/quasistatic {}: fix {} (style {}) sets force "
                     "component {} of atom {} to {} and {} for forces 1 and 2; {} treats "
                     "only components held at 0.0. Use relax minimize", method, fix->id, fix->style,
                     "xyz"[k], atom->tag[i], first[3 * i + k], out, method);
        }
    }
  }
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) f[i][k] = saved[3 * i + k];

  // (ID, bits) of every particle with a held component, on every rank
  std::vector<tagint> mine;
  for (int i = 0; i < nlocal; i++)
    if (bits[i] & ~planar) {
      mine.push_back(atom->tag[i]);
      mine.push_back((tagint) (bits[i] & ~planar));
    }
  int count = (int) mine.size(), nprocs = comm->nprocs;
  std::vector<int> counts(nprocs), offsets(nprocs, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  for (int p = 1; p < nprocs; p++) offsets[p] = offsets[p - 1] + counts[p - 1];
  std::vector<tagint> held_ids(offsets[nprocs - 1] + counts[nprocs - 1], 0);
  MPI_Allgatherv(mine.data(), count, MPI_LMP_TAGINT, held_ids.data(), counts.data(),
                 offsets.data(), MPI_LMP_TAGINT, world);
  return held_ids;
}
