/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Heterogeneous rock for pair_style lattice/bond (keywords stiffness, grain,
   strength, strength_factor, seed, boundary_strength;
   docs/pair_lattice_bond.rst, "Heterogeneous rock"): per-particle stiffness
   factors, strength factors and grain IDs (fix property/atom), their ghost
   values, and each bond's stiffness and
   strength factors, cached per record after every reneighbouring so that
   the force loop needs neither the hash nor the partner's properties.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_HETEROGENEITY_H
#define LMP_LATTICE_HETEROGENEITY_H

#include "lattice_bond_physics.h"
#include "lattice_comm.h"
#include "pointers.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

/* ----------------------------------------------------------------------
   a bond's parameters: the type pair's; with heterogeneity the stiffnesses
   scale with the stiffness factor s, the breaking force Kn*Xb and the shear
   strength Fs0 with the strength factor g (so Xb becomes Xb g / s)
------------------------------------------------------------------------- */

inline LatticeBondParams scaled_params(const LatticeBondParams &p, double s, double g)
{
  return {p.kn * s, p.ks * s, p.xb * (g / s), p.fs0 * g, p.mu_p};
}

class LatticeHeterogeneity : protected Pointers, public LatticeForwardPart {
 public:
  explicit LatticeHeterogeneity(LAMMPS *lmp);

  // pair_style keywords: how many words of arg from iarg on (key and values)
  // the keyword there takes if it is one of this class's, else 0
  int parse_keyword(int narg, char **arg, int iarg);
  void check_keywords() const;    // after the keywords: their combinations
  bool enabled() const { return flag; }    // some keyword given

  // the per-atom properties, checked on every run (init_style); fetch()
  // takes their arrays anew at every step (they move when the atom arrays grow)
  void find();
  void fetch();
  // the ghosts' stiffness factors and grain IDs, once per reneighbouring
  void share_ghosts(LatticeCommCarrier &carrier);

  // the bond's stiffness factor (mean of the particles' factors) and strength
  // factor (uniform in [strength_min, strength_max] from a hash of seed and
  // tags, times the mean of the particles' strength factors, times
  // boundary_strength across grain boundaries)
  double bond_stiffness_factor(int i, int j) const;
  double bond_strength_factor(int i, int j) const;
  LatticeBondParams bond_params(const LatticeBondParams &p, int i, int j) const
  {
    return scaled_params(p, bond_stiffness_factor(i, j), bond_strength_factor(i, j));
  }

  // the stiffness and strength factors of local atom i's nrec records, 2 per
  // record with the stride of the partner index (idx: atom i's row, nmax rows)
  void cache_bond_factors(int i, const int *idx, int nrec, int stride, int nmax);
  const double *bond_factors(int i, int stride) const
  {
    return bond_factor.data() + (size_t) i * stride * 2;
  }

  // restart settings (format 3 on): the keywords; format 5 adds the keyword
  // strength_factor, written after the pair style's own format-4 word
  void write_restart(FILE *fp) const;
  void read_restart(FILE *fp, bool present);    // absent (older files): none
  void write_restart_strength_factor(FILE *fp) const;
  void read_restart_strength_factor(FILE *fp, bool present);

  int pack_forward(int n, const int *list, double *buf) override;
  void unpack_forward(int n, int first, const double *buf) override;
  double memory_usage() const;

 private:
  int flag;                           // 1 if any keyword is given
  std::string stiffness_name;         // per-particle stiffness factor, d_ property or ""
  std::string grain_name;             // per-particle grain ID, i_ property or ""
  std::string strength_name;          // per-particle strength factor, d_ property or ""
  double strength_min, strength_max;  // per-bond strength factor range
  double boundary_strength;           // strength factor of bonds between grains
  bigint seed;
  int stiffness_index, grain_index, strength_index;    // their indices among the custom
                                                       // properties, or -1
  double *stiffness_factor;           // their arrays (see fetch)
  int *grain_id;
  double *particle_strength;
  std::vector<double> bond_factor;    // see cache_bond_factors
};

}    // namespace LAMMPS_NS

#endif
