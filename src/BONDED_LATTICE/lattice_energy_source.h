/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   LatticeEnergySource: a style whose forces turn energy into heat, or do
   work on the particles, or store it in springs, and that keeps the account
   itself for compute lattice/energy (Liu et al. 2017, section 4).
   pair_style lattice/bond, fix lattice/viscous and fix lattice/wall
   implement it; the internal fix LATTICE/ENERGY finds them by this type
   (the pair style and every fix, dynamic_cast), not by their names.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_ENERGY_SOURCE_H
#define LMP_LATTICE_ENERGY_SOURCE_H

namespace LAMMPS_NS {

class LatticeEnergySource {
 public:
  // the tallies, in the order of compute lattice/energy's vector elements 4-8:
  // viscous heat, breaking heat of the normal and of the shear springs,
  // frictional heat, and the external work done on the particles
  enum Tally { VISCOUS, BREAK_NORMAL, BREAK_SHEAR, FRICTION, WORK, NTALLY };

  // switch the accumulation of the tallies on (compute lattice/energy's fix,
  // at every init) or off; off, the source's loops do no accounting at all
  virtual void enable_energy_tallies(bool on) = 0;
  // add this rank's tallies since the source was created to tally[NTALLY]
  // (each a plain per-rank sum that starts at 0; the caller takes differences)
  virtual void add_energy_tallies(double *tally) const = 0;
  // the elastic energy stored in the source's springs now, summed over all
  // ranks (collective: every rank calls it); 0 for a source without springs
  virtual double elastic_energy() = 0;

 protected:
  // the styles are deleted as what they are (LAMMPS' destructors may throw),
  // never through this interface
  ~LatticeEnergySource() = default;
};

}    // namespace LAMMPS_NS

#endif
