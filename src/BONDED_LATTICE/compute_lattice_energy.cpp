/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   compute lattice/energy, global vector (Liu et al. 2017, section 4):
   [1] elastic energy of the bond and contact springs and of fix lattice/wall
   [2] kinetic energy   [3] gravitational energy (fix gravity)
   [4] viscous heat (fix lattice/viscous)
   [5] breaking heat, normal springs   [6] breaking heat, shear springs
   [7] frictional heat (sliding contacts and walls)
   [8] external work (moving walls, prescribed groups)
   [9] total = [1] + ... + [7]   [10] balance error = [9] - [8] - [9] at start

   The kinetic and gravitational energies are evaluated here; the springs'
   energy and the heat and work tallies live in the styles that produce them
   (LatticeEnergySource) and are switched on by the internal fix
   LATTICE/ENERGY this compute creates, so that without this compute the
   force loops do no accounting at all.
------------------------------------------------------------------------- */

#include "compute_lattice_energy.h"

#include "atom.h"
#include "error.h"
#include "fix.h"
#include "fix_lattice_energy.h"
#include "force.h"
#include "group.h"
#include "lattice_energy_source.h"
#include "modify.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   compute ID all lattice/energy [work group-ID ...]
------------------------------------------------------------------------- */

ComputeLatticeEnergy::ComputeLatticeEnergy(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), fix(nullptr)
{
  if (igroup != 0)
    error->all(FLERR, "compute lattice/energy needs group all (it is {}): the energy balance is "
               "global", arg[1]);
  std::string groups;
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "work") == 0) {
      if (iarg + 1 >= narg)
        error->all(FLERR, "compute lattice/energy keyword work needs at least one group ID");
      for (iarg++; iarg < narg && strcmp(arg[iarg], "work") != 0; iarg++) {
        if (group->find(arg[iarg]) < 0)
          error->all(FLERR, "compute lattice/energy work group {} does not exist: define it with "
                     "the group command first", arg[iarg]);
        groups += std::string(" ") + arg[iarg];
      }
    } else {
      error->all(FLERR, "Unknown compute lattice/energy keyword {}: the only keyword is work",
                 arg[iarg]);
    }
  }
  vector_flag = 1;
  size_vector = 10;
  extvector = 1;
  vector = values;
  std::memset(values, 0, sizeof(values));

  fix_id = std::string(id) + "_LATTICE_ENERGY";
  fix = dynamic_cast<FixLatticeEnergy *>(
      modify->add_fix(fix_id + " all LATTICE/ENERGY " + id + groups));
}

/* ---------------------------------------------------------------------- */

ComputeLatticeEnergy::~ComputeLatticeEnergy()
{
  if (modify && modify->nfix && modify->get_fix_by_id(fix_id)) modify->delete_fix(fix_id);
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeEnergy::init()
{
  // (the fix finds the energy sources and needs pair_style lattice/bond)
  fix = dynamic_cast<FixLatticeEnergy *>(modify->get_fix_by_id(fix_id));
  if (!fix) error->all(FLERR, "compute lattice/energy lost its fix {}", fix_id);
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeEnergy::stored_parts(double *parts)
{
  double kinetic = 0.0;
  double **v = atom->v;
  // per-atom masses (atom_style sphere) or per-type ones (mass command)
  const double *rmass = atom->rmass;
  const double *mass = atom->mass;
  const int *type = atom->type;
  for (int i = 0; i < atom->nlocal; i++) {
    const double m = rmass ? rmass[i] : mass[type[i]];
    kinetic += 0.5 * m * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
  }
  // mass x velocity^2 in energy units, as compute ke (1 in si, cgs, micro, nano, lj)
  kinetic *= force->mvv2e;
  MPI_Allreduce(&kinetic, &parts[1], 1, MPI_DOUBLE, MPI_SUM, world);
  // the springs of the pair style and the walls, and gravity: global sums
  parts[0] = 0.0;
  for (auto *source : fix->sources()) parts[0] += source->elastic_energy();
  parts[2] = 0.0;
  for (auto *g : fix->gravity_fixes()) parts[2] += g->compute_scalar();
}

/* ---------------------------------------------------------------------- */

double ComputeLatticeEnergy::stored_energy()
{
  if (!fix) init();
  double parts[3];
  stored_parts(parts);
  return parts[0] + parts[1] + parts[2];
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeEnergy::compute_vector()
{
  invoked_vector = update->ntimestep;
  stored_parts(values);
  double tally[FixLatticeEnergy::NTALLY];
  fix->totals(tally);
  for (int k = 0; k < FixLatticeEnergy::NTALLY; k++) values[3 + k] = tally[k];
  values[8] = 0.0;
  for (int k = 0; k < 7; k++) values[8] += values[k];
  values[9] = fix->started() ? values[8] - values[7] - fix->start_energy() : 0.0;
}
