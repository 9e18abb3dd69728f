/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   write_lattice_bonds file / read_lattice_bonds file: the bond network of
   pair_style lattice/bond (every bond and contact record: the two atom IDs,
   the state and the shear spring) as a text file, to inspect it and to carry
   it across LAMMPS versions together with a data file.
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(write_lattice_bonds,WriteLatticeBonds);
CommandStyle(read_lattice_bonds,ReadLatticeBonds);
// clang-format on
#else

#ifndef LMP_LATTICE_BONDS_IO_H
#define LMP_LATTICE_BONDS_IO_H

#include "command.h"

namespace LAMMPS_NS {

class WriteLatticeBonds : public Command {
 public:
  WriteLatticeBonds(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

class ReadLatticeBonds : public Command {
 public:
  ReadLatticeBonds(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
