/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The rotation fit of shear_frame corotational: see lattice_rotation_fit.h
------------------------------------------------------------------------- */

#include "lattice_rotation_fit.h"

#include "atom.h"
#include "domain.h"
#include "fix_lattice_bond_store.h"
#include "memory.h"

#include <cstring>

using namespace LAMMPS_NS;

// a particle's fit of its rotation is used only when tr(S) tr(S^-1) <= this
// bound, S the sum of m m^T over its intact bonds (4 for an isotropic 2D and
// 9 for an isotropic 3D neighbourhood, 5.3 and 13.5 for the corner particles
// of hexagonal and fcc blocks; two bonds 11.5 degrees from collinear reach it
// in 2D); otherwise its rotation is taken as zero
static constexpr double ROTATION_FIT_CONDITION = 100.0;
static constexpr double ROTATION_FIT_DET_FLOOR = 1.0e-6;    // det S / (tr S)^3, 3D
static constexpr int FIT_VALUES_2D = 7;     // S: xx xy yy; B: xx xy yx yy
static constexpr int FIT_VALUES_3D = 15;    // S: xx xy xz yy yz zz; B: 9 values

/* ---------------------------------------------------------------------- */

LatticeRotationFit::LatticeRotationFit(LAMMPS *lmp) :
    Pointers(lmp), rotation(nullptr), rotation_nmax(0), values(0)
{
}

LatticeRotationFit::~LatticeRotationFit()
{
  memory->destroy(rotation);
}

/* ---------------------------------------------------------------------- */

int LatticeRotationFit::reverse_values(int dimension)
{
  return (dimension == 2) ? FIT_VALUES_2D : FIT_VALUES_3D;
}

/* ----------------------------------------------------------------------
   each particle's rotation increment in this step, fitted to the motion of
   its intact bonds.  For a bond of particle i with partner j let u = the
   step's relative displacement (disp_i - disp_j) and m = r_ij - u/2 its
   mid-step separation.  The velocity gradient L of the neighbourhood is the
   least-squares fit of u = L m over the particle's intact bonds,
       L = B S^-1,   B = sum u m^T,   S = sum m m^T,
   and the rotation is its antisymmetric part, w = axial vector of (L - L^T)/2.
   A rigid rotation by the angle phi about the axis a moves every separation by
   u = 2 g x m exactly (Cayley: r_new - r_old = g x (r_new + r_old),
   g = tan(phi/2) a), so the fit returns w = 2 g to round-off, and a pure strain
   (symmetric L) returns w = 0 for any neighbourhood geometry.  A particle
   whose bonds do not span the plane (2D) or space (3D), or span it poorly
   (tr S tr S^-1 above ROTATION_FIT_CONDITION: one bond, collinear bonds, in 3D
   coplanar ones), gets w = 0, as in the papers.  Both atoms of a bond receive
   its terms (the products do not change sign with the bond's direction);
   ghosts' sums go back to their owners, and the owners' rotations out to the
   ghosts.
------------------------------------------------------------------------- */

void LatticeRotationFit::fit(FixLatticeBondStore *store, const int *idx, int stride,
                             LatticeCommCarrier &carrier)
{
  const int nall = atom->nlocal + atom->nghost;
  const bool planar = (domain->dimension == 2);
  values = reverse_values(domain->dimension);
  sums.assign((size_t) nall * values, 0.0);
  if (atom->nmax > rotation_nmax) {
    memory->destroy(rotation);
    rotation_nmax = atom->nmax;
    memory->create(rotation, rotation_nmax, 3, "pair:spin");
  }

  if (planar) sums_over_bonds<true>(store, idx, stride);
  else sums_over_bonds<false>(store, idx, stride);
  carrier.carry_reverse(this);
  solve();
  carrier.carry_forward(this);
}

/* ----------------------------------------------------------------------
   the sums S and B of fit() over the intact bonds, on both atoms (the
   owner's in registers, the partner's in sums)
------------------------------------------------------------------------- */

template <bool PLANAR>
void LatticeRotationFit::sums_over_bonds(FixLatticeBondStore *store, const int *partner_idx,
                                         int stride)
{
  constexpr int NV = PLANAR ? FIT_VALUES_2D : FIT_VALUES_3D;
  const auto *const x = reinterpret_cast<const double(*)[3]>(atom->x[0]);
  const auto *const disp = reinterpret_cast<const double(*)[3]>(store->displacements());
  const int *const nrec = store->record_counts();
  double *const all = sums.data();
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    const LatticeBondState *__restrict st = store->states(i);
    const int *__restrict idx = partner_idx + (bigint) i * stride;
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double dxi = disp[i][0], dyi = disp[i][1], dzi = disp[i][2];
    double acc[NV] = {};
    for (int s = 0; s < nrec[i]; s++) {
      const int j = idx[s];
      if (j < 0 || st[s] != LB_INTACT) continue;
      // the same expressions as in the force loop, so that a rigid rotation cancels to round-off
      const double ux = dxi - disp[j][0], uy = dyi - disp[j][1];
      const double mx = (xi - x[j][0]) - 0.5 * ux, my = (yi - x[j][1]) - 0.5 * uy;
      double t[NV];
      if constexpr (PLANAR) {
        const double terms[NV] = {mx * mx, mx * my, my * my, ux * mx, ux * my, uy * mx, uy * my};
        for (int v = 0; v < NV; v++) t[v] = terms[v];
      } else {
        const double uz = dzi - disp[j][2];
        const double mz = (zi - x[j][2]) - 0.5 * uz;
        const double terms[NV] = {mx * mx, mx * my, mx * mz, my * my, my * mz, mz * mz,
                                  ux * mx, ux * my, ux * mz, uy * mx, uy * my, uy * mz,
                                  uz * mx, uz * my, uz * mz};
        for (int v = 0; v < NV; v++) t[v] = terms[v];
      }
      double *__restrict sj = all + (size_t) j * NV;
      for (int v = 0; v < NV; v++) {
        acc[v] += t[v];
        sj[v] += t[v];
      }
    }
    double *si = all + (size_t) i * NV;
    for (int v = 0; v < NV; v++) si[v] += acc[v];
  }
}

/* ----------------------------------------------------------------------
   the local particles' rotations from their summed S and B
------------------------------------------------------------------------- */

void LatticeRotationFit::solve()
{
  const int nlocal = atom->nlocal;
  const bool planar = (domain->dimension == 2);
  const int nv = values;
  const double *const all = sums.data();
  for (int i = 0; i < nlocal; i++) {
    const double *f = all + (size_t) i * nv;
    double *wi = rotation[i];
    wi[0] = wi[1] = wi[2] = 0.0;
    if (planar) {
      const double tr = f[0] + f[2];
      if (!(tr > 0.0)) continue;
      const double q = 1.0 / tr;    // scale S and B by 1/tr S: no under- or overflow
      const double a = f[0] * q, b = f[1] * q, c = f[2] * q;
      const double det = a * c - b * b;    // tr S tr S^-1 = tr^2 / det = 1 / det here
      if (!(det * ROTATION_FIT_CONDITION >= 1.0)) continue;
      const double bxx = f[3] * q, bxy = f[4] * q, byx = f[5] * q, byy = f[6] * q;
      // (L_yx - L_xy) / 2 with L = B S^-1, S^-1 = [c -b; -b a] / det
      wi[2] = 0.5 * ((c * byx - b * byy) - (a * bxy - b * bxx)) / det;
    } else {
      const double tr = f[0] + f[3] + f[5];
      if (!(tr > 0.0)) continue;
      const double q = 1.0 / tr;
      const double sxx = f[0] * q, sxy = f[1] * q, sxz = f[2] * q;
      const double syy = f[3] * q, syz = f[4] * q, szz = f[5] * q;
      // adjugate of S (symmetric) and its determinant
      const double axx = syy * szz - syz * syz, axy = sxz * syz - sxy * szz;
      const double axz = sxy * syz - sxz * syy, ayy = sxx * szz - sxz * sxz;
      const double ayz = sxy * sxz - sxx * syz, azz = sxx * syy - sxy * sxy;
      const double det = sxx * axx + sxy * axy + sxz * axz;
      // tr S tr S^-1 = (axx + ayy + azz) / det, tr S = 1 here.  Below the bound
      // every eigenvalue of S is at least 1/100, so det >= 1e-4: the floor only
      // rejects round-off, where S has rank 1 (one bond, collinear bonds) and
      // both det and the adjugate are noise of order 1e-17
      if (!(det >= ROTATION_FIT_DET_FLOOR && det * ROTATION_FIT_CONDITION >= axx + ayy + azz))
        continue;
      const double bm[3][3] = {{f[6] * q, f[7] * q, f[8] * q},
                               {f[9] * q, f[10] * q, f[11] * q},
                               {f[12] * q, f[13] * q, f[14] * q}};
      const double adj[3][3] = {{axx, axy, axz}, {axy, ayy, ayz}, {axz, ayz, azz}};
      // L det = B adj; w = axial vector of the antisymmetric part of L
      auto l = [&](int a, int b) {
        return bm[a][0] * adj[0][b] + bm[a][1] * adj[1][b] + bm[a][2] * adj[2][b];
      };
      const double h = 0.5 / det;
      wi[0] = (l(2, 1) - l(1, 2)) * h;
      wi[1] = (l(0, 2) - l(2, 0)) * h;
      wi[2] = (l(1, 0) - l(0, 1)) * h;
    }
  }
}

/* ----------------------------------------------------------------------
   forward communication: the owners' rotations (2D: about z only)
------------------------------------------------------------------------- */

int LatticeRotationFit::pack_forward(int n, const int *list, double *buf)
{
  const int c0 = (domain->dimension == 2) ? 2 : 0;
  int m = 0;
  for (int k = 0; k < n; k++)
    for (int c = c0; c < 3; c++) buf[m++] = rotation[list[k]][c];
  return m;
}

/* ---------------------------------------------------------------------- */

void LatticeRotationFit::unpack_forward(int n, int first, const double *buf)
{
  const int c0 = (domain->dimension == 2) ? 2 : 0;
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int c = c0; c < 3; c++) rotation[i][c] = buf[m++];
}

/* ----------------------------------------------------------------------
   reverse communication: the ghosts' sums to their owners
------------------------------------------------------------------------- */

int LatticeRotationFit::pack_reverse(int n, int first, double *buf)
{
  const int nv = values;
  std::memcpy(buf, sums.data() + (size_t) first * nv, sizeof(double) * n * nv);
  return n * nv;
}

/* ---------------------------------------------------------------------- */

void LatticeRotationFit::unpack_reverse(int n, const int *list, const double *buf)
{
  const int nv = values;
  for (int k = 0; k < n; k++) {
    double *s = sums.data() + (size_t) list[k] * nv;
    for (int v = 0; v < nv; v++) s[v] += buf[k * nv + v];
  }
}

/* ---------------------------------------------------------------------- */

double LatticeRotationFit::memory_usage() const
{
  return (double) rotation_nmax * 3 * sizeof(double) + (double) sums.capacity() * sizeof(double);
}
