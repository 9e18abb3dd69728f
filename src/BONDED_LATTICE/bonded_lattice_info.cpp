/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: the `bonded_lattice` command.
------------------------------------------------------------------------- */

#include "bonded_lattice_info.h"

#include "bonded_lattice_config.h"
#include "comm.h"
#include "error.h"

using namespace LAMMPS_NS;

void BondedLatticeInfo::command(int narg, char **)
{
  if (narg != 0)
    error->all(FLERR, "The bonded_lattice command takes no arguments, got {}", narg);
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "BONDED_LATTICE {} ({}, built for LAMMPS {}): pair_style lattice/bond, fix "
                   "lattice/nve, fix lattice/viscous, fix lattice/wall, compute lattice/bonds, "
                   "compute lattice/bond/local, compute lattice/energy, write_lattice_bonds, "
                   "read_lattice_bonds, lattice/quasistatic\n",
                   BONDED_LATTICE_VERSION,
                   BONDED_LATTICE_BUILT_IN ? "compiled into LAMMPS" : "plugin",
                   BONDED_LATTICE_LAMMPS_VERSION);
}
