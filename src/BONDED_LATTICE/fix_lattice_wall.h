/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   fix lattice/wall: flat platen with a normal spring, a frictional shear
   spring and optional motion along its normal.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(lattice/wall,FixLatticeWall);
// clang-format on
#else

#ifndef LMP_FIX_LATTICE_WALL_H
#define LMP_FIX_LATTICE_WALL_H

#include "fix_lattice_atom_history.h"
#include "lattice_energy_source.h"

#include <string>

namespace LAMMPS_NS {

class FixLatticeWall : public FixLatticeAtomHistory, public LatticeEnergySource {
 public:
  FixLatticeWall(class LAMMPS *, int, char **);
  ~FixLatticeWall() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void min_setup(int) override;
  void post_force(int) override;
  void min_post_force(int) override;
  double compute_scalar() override;
  double compute_vector(int) override;

  void set_arrays(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  double position() const;    // wall coordinate at the current step

  // energy accounting (LatticeEnergySource), on this rank: heat of its sliding
  // contacts (FRICTION) and work done by the wall on the particles as it moves
  // (WORK); its springs' energy is compute_scalar()
  void enable_energy_tallies(bool on) override { tally_flag = on ? 1 : 0; }
  void add_energy_tallies(double *tally) const override
  {
    tally[FRICTION] += heat;
    tally[WORK] += work;
  }
  double elastic_energy() override { return compute_scalar(); }

 protected:
  int dim;          // 0, 1, 2 for x, y, z
  int inward;       // +1 for a lo face (particles above it), -1 for a hi face
  std::string pos_var_name;    // equal-style variable giving the position, or empty
  int pos_var;                 // its index, -1 for none
  double pos0;      // position at time t0
  double t0;        // simulation time at which the wall was at pos0
  double vel;       // speed along +axis
  double kn, ks, mu;
  int servo;              // 1: the wall moves to hold a normal stress
  double servo_force;     // target normal force (stress x area), compression positive
  double servo_gain;      // fraction of the force error corrected per step
  double uniform_radius;  // every particle's radius without per-atom radii (init), else 0

  // hist[i][0..2]: shear-spring displacement against the wall,
  // hist[i][3..5]: position at the last force evaluation
  int history_ready;

  double wall_force[4];    // force the particles exert on the wall (x, y, z), contacts
  double wall_energy;
  int force_flag;
  double total[5];

  int tally_flag;
  double work, heat;
  double fnormal_prev;    // this rank's normal force on the particles at the last step
  double wall_prev;       // the wall's position at the last step

  double current_time() const;
  void find_position_variable();
  void apply_forces(bool step_taken);
};

}    // namespace LAMMPS_NS

#endif
#endif
