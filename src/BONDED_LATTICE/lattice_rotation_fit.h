/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   pair_style lattice/bond shear_frame corotational (docs/pair_lattice_bond.rst,
   "Rigid rotation"): each particle's rotation increment in a step, fitted to
   the motion of its intact bonds (fit()), and the two per-record operations
   the force loop inlines: the step's relative displacement without the
   pair's share of the local rigid rotation (remove_rigid_rotation) and the
   3D shear spring turned with the pair (rotate_spring).  Nothing is kept
   between steps.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_ROTATION_FIT_H
#define LMP_LATTICE_ROTATION_FIT_H

#include "lattice_comm.h"
#include "pointers.h"

#include <vector>

namespace LAMMPS_NS {

class FixLatticeBondStore;

class LatticeRotationFit : protected Pointers, public LatticeForwardPart, public LatticeReversePart {
 public:
  explicit LatticeRotationFit(LAMMPS *lmp);
  ~LatticeRotationFit();

  // values per particle the fit sums from the ghosts to their owners (2D, 3D)
  static int reverse_values(int dimension);
  // each local and ghost particle's rotation increment this step from the
  // displacements of the store's intact records (partner index idx with the
  // given stride: see LatticeBondRecords); collective
  void fit(FixLatticeBondStore *store, const int *idx, int stride, LatticeCommCarrier &carrier);
  // the rotations: 3 per particle (2D: about z, [2] only)
  const double *const *spin() const { return rotation; }

  int pack_forward(int n, const int *list, double *buf) override;
  void unpack_forward(int n, int first, const double *buf) override;
  int pack_reverse(int n, int first, double *buf) override;
  void unpack_reverse(int n, const int *list, const double *buf) override;
  double memory_usage() const;

 private:
  double **rotation;            // per particle (local and ghost), nmax x 3
  int rotation_nmax;
  std::vector<double> sums;     // per particle: the sums of the fit (see fit)
  int values;                   // values per particle in sums
  template <bool PLANAR>
  void sums_over_bonds(FixLatticeBondStore *store, const int *idx, int stride);
  void solve();
};

/* ----------------------------------------------------------------------
   per record (inlined into the force loop): the step's relative
   displacement u of the pair without its share of the local rigid
   rotation, u -= wbar x m, wbar = (w_i + w_j)/2, m = r_ij - u/2 (exact for
   a rigid rotation, see fit(); it is the relative displacement of the
   contact point if each particle turned with its neighbourhood)
------------------------------------------------------------------------- */

template <bool PLANAR>
static inline __attribute__((always_inline)) void
remove_rigid_rotation(const double *wi, const double *wj, double dx, double dy, double dz,
                      double &ux, double &uy, double &uz)
{
  const double wz = 0.5 * (wi[2] + wj[2]);
  const double mx = dx - 0.5 * ux, my = dy - 0.5 * uy;
  if constexpr (PLANAR) {
    ux += wz * my;
    uy -= wz * mx;
  } else {
    const double wx = 0.5 * (wi[0] + wj[0]), wy = 0.5 * (wi[1] + wj[1]);
    const double mz = dz - 0.5 * uz;
    ux -= wy * mz - wz * my;
    uy -= wz * mx - wx * mz;
    uz -= wx * my - wy * mx;
  }
}

/* ----------------------------------------------------------------------
   3D: the shear spring s turned by the pair's rotation, whose Gibbs vector
   is g = wbar/2 = (w_i + w_j)/4 (Rodrigues): s += 2/(1 + g.g) (g x s +
   g x (g x s)).  A 2D spring is a signed length along the pair's tangent and
   turns with the pair by itself
------------------------------------------------------------------------- */

static inline __attribute__((always_inline)) void rotate_spring(const double *wi, const double *wj,
                                                                double &sx, double &sy, double &sz)
{
  const double gx = 0.5 * (0.5 * (wi[0] + wj[0])), gy = 0.5 * (0.5 * (wi[1] + wj[1]));
  const double gz = 0.5 * (0.5 * (wi[2] + wj[2]));
  const double c = 2.0 / (1.0 + (gx * gx + gy * gy + gz * gz));
  const double ax = gy * sz - gz * sy, ay = gz * sx - gx * sz, az = gx * sy - gy * sx;
  const double bx = gy * az - gz * ay, by = gz * ax - gx * az, bz = gx * ay - gy * ax;
  sx += c * (ax + bx);
  sy += c * (ay + by);
  sz += c * (az + bz);
}

}    // namespace LAMMPS_NS

#endif
