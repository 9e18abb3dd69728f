/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   lattice/quasistatic: quasi-static loading in the manner of the Mike/Elle
   spring lattice.  Relax to a force tolerance, break the most over-stressed
   bond (or all bonds past their threshold), relax again, until no intact
   bond exceeds its threshold.  The strain step between calls is the input
   script's (change_box ... remap is the seed's affine pre-displacement).
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(lattice/quasistatic,LatticeQuasistatic);
// clang-format on
#else

#ifndef LMP_LATTICE_QUASISTATIC_H
#define LMP_LATTICE_QUASISTATIC_H

#include "command.h"

#include <string>

namespace LAMMPS_NS {

class PairLatticeBond;
enum class BreakMode : unsigned char;    // fix_lattice_bond_store.h

class LatticeQuasistatic : public Command {
 public:
  LatticeQuasistatic(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;

 private:
  PairLatticeBond *pair = nullptr;
  double ftol = 0.0;            // force tolerance (force units): largest |f| of a particle
  bool minimize = true;         // relax by the minimiser, else by damped dynamics
  bool local = false;           // relax local: over-relaxation where forces exceed ftol
  bool direct = false;          // relax direct: exact linear equilibria, sparse factor
  double omega = 1.95;          // relax local: over-relaxation factor, 0 < omega < 2
  bigint chunk = 100;           // relax run: steps between force checks
  bigint maxsteps = 100000;     // per relaxation: minimiser iterations or time steps
  bool break_all = false;       // break every bond past its threshold, else the worst one
  bigint maxbreak = -1;         // most bonds broken in one call, -1: no limit
  bool quiet = false;           // no output of the relaxations (minimiser and run summaries)
  int threads = 1;              // relax direct: threads of the factor and solves (rank 0)
  std::string breaks_file;      // keyword breaks: a line per broken bond appended there
  FILE *breaks_fp = nullptr;    // (rank 0)

  void record_break(tagint owner, tagint partner, BreakMode mode, double ratio);

  void command_quietly(const std::string &line);

  bigint relax();               // returns the iterations or steps taken
  double largest_force() const;
  double worst_bond(tagint &owner, tagint &partner, BreakMode &mode) const;
  // the largest of every rank's best ratio; equal ratios go to the lowest IDs
  double reduce_worst(double best, tagint &owner, tagint &partner, BreakMode &mode) const;
  // relax local: relaxations and breaks until no bond exceeds its threshold
  void run_local(bigint &broken, int &tension, int &shear, bigint &relaxations, bigint &sweeps,
                 bigint &moves, double &worst);
  // relax direct: passes of exact linear relaxation and breaks until no force
  // exceeds ftol and no bond its threshold
  void run_direct(bigint &broken, int &tension, int &shear, bigint &relaxations, bigint &solves,
                  bigint &factorisations, double &worst);
  bigint break_beyond_threshold(int &tension, int &shear);
};

}    // namespace LAMMPS_NS

#endif
#endif
