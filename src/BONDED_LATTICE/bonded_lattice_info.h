/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The input command that reports the package: its version, the LAMMPS it
   was built for, how it reached this LAMMPS (compiled in, or a plugin) and
   its styles.  Built in, it is the command `bonded_lattice`; the plugin
   registers it as `bonded_lattice/<version>`, so that `plugin list` shows
   which version is loaded.
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(bonded_lattice,BondedLatticeInfo);
// clang-format on
#else

#ifndef LMP_BONDED_LATTICE_INFO_H
#define LMP_BONDED_LATTICE_INFO_H

#include "command.h"

namespace LAMMPS_NS {

class BondedLatticeInfo : public Command {
 public:
  BondedLatticeInfo(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
