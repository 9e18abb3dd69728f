/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The physics of one record (a bond or a contact) of pair_style lattice/bond
   and of a particle's contact with fix lattice/wall, in one place: the normal
   spring and its tensile break, the Coulomb limit and the shear break, the
   shear spring's update in 2D (a signed length) and in 3D (a vector), Coulomb
   sliding, the heat of each event and the energy of a record.  The pair's
   force loop (every compiled variant), its bond_load() and
   local_elastic_energy(), and fix lattice/wall call these functions; none of
   them keeps a copy.

   Papers: Liu, Pollard & Shi (2013) "Liu 2013", Liu et al. (2017) "Liu 2017",
   Li et al. (2018) "Li 2018" (docs/pair_lattice_bond.rst, "Force law";
   docs/compute_lattice_energy.rst for the heat).

   The order of operations in every function is part of the results: the
   build forbids fused multiply-add contraction (-ffp-contract=off), so one
   expression gives the same bits in every caller and in every variant of the
   force loop.  Reordering a sum or a product here changes the trajectories in
   the last bits (bench/compare_bits.py tells).  Functions the force loop calls
   for every record are forced inline and take and return values, with no
   reference or pointer out-parameters: with those (an earlier form of this
   header) GCC kept more in memory and the 3D loop ran 5% more instructions,
   the 2D loop 2% (valgrind --tool=cachegrind); with values the 3D loop's
   instructions are those of the code before the header.  The loop applies the
   forces itself.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_BOND_PHYSICS_H
#define LMP_LATTICE_BOND_PHYSICS_H

#include <cmath>

#define LB_PHYSICS_INLINE inline __attribute__((always_inline))

namespace LAMMPS_NS {

// the parameters of a record (SI: N/m, N/m, m, N, -): normal and shear
// stiffness, tensile breaking stretch, shear strength, friction coefficient;
// a type pair's (pair_coeff), scaled per bond in heterogeneous rock
// (scaled_params in lattice_heterogeneity.h)
struct LatticeBondParams {
  double kn, ks, xb, fs0, mu_p;
};

namespace LatticeBondPhysics {

// the shear ratio of a bond without shear strength (Fs0 = 0) that is loaded
constexpr double RATIO_BIG = 1.0e300;
// a 3D spring turned by more than about 1e-6 rad in a step keeps its length
// (|s . n|^2 > TURN_TOLERANCE |s|^2); below, the change of length (less than
// 1e-12 relative) is left out to save a division and a square root
constexpr double TURN_TOLERANCE = 1.0e-12;

/* ======================================================================
   normal spring
   ====================================================================== */

// normal relative displacement Xn = r - (Ri + Rj), tension positive
// (Liu 2013 Fig. 1c); touch = Ri + Rj, the rest length
LB_PHYSICS_INLINE double normal_stretch(double r, double touch)
{
  return r - touch;
}

// normal force Fn = Kn Xn, tension positive (Liu 2013 eq. 1)
LB_PHYSICS_INLINE double normal_force(double kn, double xn)
{
  return kn * xn;
}

// an intact bond breaks in tension when Xn > Xb (Liu 2013 eq. 2,
// Fn,max = Kn Xb)
LB_PHYSICS_INLINE bool breaks_in_tension(double xn, double xb)
{
  return xn > xb;
}

// a broken bond or an unbonded contact with Xn >= 0 is open: no force, and
// its shear spring is reset, so a contact has no memory once separated
// (Liu 2013 eq. 3, Li 2018 eq. 4)
LB_PHYSICS_INLINE bool contact_open(double xn)
{
  return xn >= 0.0;
}

/* ======================================================================
   Coulomb limit, shear break and sliding
   ====================================================================== */

// shear strength of an intact bond Fs,max = Fs0 - mu_p Fn, Fn tension
// positive (Liu 2013 eq. 5, Liu 2017 eq. 1)
LB_PHYSICS_INLINE double coulomb_limit(double fs0, double mu_p, double fn)
{
  return fs0 - mu_p * fn;
}

// an intact bond breaks in shear when its shear force (squared: fs2) exceeds
// the Coulomb limit Fs0 - mu_p Fn, or when that limit itself is negative (a
// tension above Fs0 / mu_p; with Ks = 0 the only way, fs2 = 0)
LB_PHYSICS_INLINE bool breaks_in_shear(double fs0, double mu_p, double fn, double fs2)
{
  const double limit = coulomb_limit(fs0, mu_p, fn);
  return fs2 > limit * limit || limit < 0.0;
}

// sliding friction of a closed contact (broken bond, new contact, wall):
// Ks |S| <= -mu_p Fn, Fn tension positive (< 0 in a closed contact)
// (Liu 2013 eq. 6, Li 2018 eqs. 7-8)
LB_PHYSICS_INLINE double friction_limit(double mu_p, double fn)
{
  return -mu_p * fn;
}

// the shear force of a spring of squared length s2, squared: Ks^2 |S|^2
LB_PHYSICS_INLINE double shear_force_squared(double ks, double s2)
{
  return ks * ks * s2;
}

// the same for a signed 2D spring S: Ks^2 S^2
LB_PHYSICS_INLINE double planar_force_squared(double ks, double s)
{
  return ks * ks * s * s;
}

// the shear force |Fs| = Ks |S| of a spring of squared length s2
inline double shear_force(double ks, double s2)
{
  return ks * sqrt(s2);
}

// Coulomb sliding (Liu 2013 eq. 6, Li 2018 eq. 8): a spring whose force
// (squared: fs2) exceeds the limit slides, and is shortened to the length
// limit / Ks
LB_PHYSICS_INLINE bool slides(double fs2, double limit)
{
  return fs2 > limit * limit;
}

// 3D: the factor that shortens a spring of squared length s2 to limit / Ks
LB_PHYSICS_INLINE double slide_scale(double ks, double limit, double s2)
{
  return (s2 > 0.0) ? limit / (ks * sqrt(s2)) : 0.0;
}

// 2D: the signed spring s after sliding, +-limit / Ks with its sign
LB_PHYSICS_INLINE double planar_slid(double ks, double limit, double s)
{
  return std::copysign(limit / ks, s);
}

// the stiffness across a central spring that its tension gives, the T / r of
// its tangent stiffness Kn n n^T + T / r (I - n n^T) (T = Kn Xn): for an
// intact bond in tension only, so that a sum of these terms stays positive
// (a compressed spring's term across is negative).  The relaxations use it
// for a particle on a kinked chain in tension, which has almost no stiffness
// across its springs from Kn n n^T alone (lattice/quasistatic relax local
// and relax direct)
inline double tension_stiffness_across(double kn, double xn, double r, bool intact)
{
  return (intact && xn > 0.0 && r > 0.0) ? kn * xn / r : 0.0;
}

// ratios to the breaking thresholds (lattice/quasistatic, compute
// lattice/bond/local): tension Fn / (Kn Xb) = Xn / Xb (Liu 2013 eq. 2), shear
// (Fs + mu_p Fn) / Fs0, the Coulomb limit Fs <= Fs0 - mu_p Fn as a ratio
// (Liu 2013 eq. 5); a bond breaks when the larger exceeds 1
inline double tensile_ratio(double xn, double xb)
{
  return xn / xb;
}

inline double shear_ratio(double fs, double mu_p, double fn, double fs0)
{
  const double coulomb = fs + mu_p * fn;
  return (fs0 > 0.0) ? coulomb / fs0 : (coulomb > 0.0 ? RATIO_BIG : 0.0);
}

/* ======================================================================
   shear spring update (incremental, Li 2018 eq. 5)
   ====================================================================== */

// 2D: the spring is a signed length S along t = z x n = (-ny, nx), which
// turns with the pair.  Its increment is the step's relative displacement u
// along the tangent at mid-step, which makes the update time-reversible:
//   t_mid . u = (t . u) r / |r_ij - u/2| = (t . u)(1 + (n . u) / (2 r))
// to second order (rinv = 1/r); S <- S + t_mid . u
LB_PHYSICS_INLINE double planar_increment(double nx, double ny, double ux, double uy, double rinv)
{
  return (uy * nx - ux * ny) * (1.0 + 0.5 * (ux * nx + uy * ny) * rinv);
}

// 3D: one step of the spring vector.  The stored spring s0 is turned into the
// new tangent plane (normal n) and the tangential part of the step's relative
// displacement u is added (Li 2018 eq. 5):
//   s1 = (I - n n) s0, scaled to |s0| if the pair turned noticeably,
//   t  = (I - n n) u,
//   s  = s1 + t
// Without a noticeable turn s comes from one projection of the sum s0 + u.
// (TURN_TOLERANCE above.)
struct SpringStep {
  double sx, sy, sz;       // the new spring
  double s2;               // |s|^2
  double s1x, s1y, s1z;    // the old spring turned into the new tangent plane (for the heat)
  double tx, ty, tz;       // the tangential increment (for the heat)
};

LB_PHYSICS_INLINE SpringStep spring_step(double nx, double ny, double nz, double s0x, double s0y,
                                         double s0z, double ux, double uy, double uz)
{
  SpringStep out;
  const double sn = s0x * nx + s0y * ny + s0z * nz;
  const double dn = ux * nx + uy * ny + uz * nz;
  const double un = sn + dn;
  out.sx = (s0x + ux) - un * nx;
  out.sy = (s0y + uy) - un * ny;
  out.sz = (s0z + uz) - un * nz;
  out.s2 = out.sx * out.sx + out.sy * out.sy + out.sz * out.sz;
  out.s1x = s0x - sn * nx;
  out.s1y = s0y - sn * ny;
  out.s1z = s0z - sn * nz;
  out.tx = ux - dn * nx;
  out.ty = uy - dn * ny;
  out.tz = uz - dn * nz;
  if (__builtin_expect(sn * sn > TURN_TOLERANCE * out.s2, 0)) {
    // the pair turned noticeably in one step (by more than about 1e-6 rad):
    // the turned spring keeps its length
    const double old2 = s0x * s0x + s0y * s0y + s0z * s0z;
    const double new2 = out.s1x * out.s1x + out.s1y * out.s1y + out.s1z * out.s1z;
    if (new2 > 0.0) {
      const double scale = sqrt(old2 / new2);
      out.s1x *= scale;
      out.s1y *= scale;
      out.s1z *= scale;
    }
    out.sx = out.s1x + out.tx;
    out.sy = out.s1y + out.ty;
    out.sz = out.s1z + out.tz;
    out.s2 = out.sx * out.sx + out.sy * out.sy + out.sz * out.sz;
  }
  return out;
}

/* ======================================================================
   heat of each event

   Heat is the energy a record's springs lose other than by doing work on the
   particles, with the work over a step taken by the trapezoidal rule, which
   is what velocity Verlet conserves (docs/compute_lattice_energy.rst).
   ====================================================================== */

// a normal spring that breaks at stretch xn releases Kn/4 (xp^2 + xn^2), its
// energy minus the work it does during that step; xp is its stretch at the
// last step, when the separation was (px, py, pz) (touch = Ri + Rj)
inline double normal_release(double touch, double kn, double xn, double px, double py, double pz)
{
  const double xp = sqrt(px * px + py * py + pz * pz) - touch;
  return 0.25 * kn * (xp * xp + xn * xn);
}

// a shear spring going from s1 (turned into the new tangent plane) through
// the tangential increment t to s2:
//   Q = Ks/2 [(s1 + s2).t - |s2|^2 + |s1|^2],
// 0 while the spring is elastic (s2 = s1 + t), Fs dS of Liu 2017 (eq. 25)
// while it slides, and the spring's energy when it lets go (s2 = 0)
inline double shear_heat(double ks, const double *s1, const double *t, const double *s2)
{
  double q = 0.0;
  for (int k = 0; k < 3; k++) q += (s1[k] + s2[k]) * t[k] - s2[k] * s2[k] + s1[k] * s1[k];
  return 0.5 * ks * q;
}

// a 3D shear spring sh that lets go this step (s2 = 0 above):
// Ks/2 (sh.t + |sh|^2), (tx, ty, tz) the step's relative displacement; its
// normal part is of second order in the step and is kept, the spring is not
// turned
inline double spring_release(const double *sh, double ks, double tx, double ty, double tz)
{
  if (sh[0] == 0.0 && sh[1] == 0.0 && sh[2] == 0.0) return 0.0;
  const double t[3] = {tx, ty, tz};
  const double none[3] = {0.0, 0.0, 0.0};
  return shear_heat(ks, sh, t, none);
}

// the same two heats for a signed 2D spring: Ks/2 [(s1 + s2) t - s2^2 + s1^2]
// and its release (s2 = 0); t the increment along the mid-step tangent
inline double planar_heat(double ks, double s1, double t, double s2)
{
  return 0.5 * ks * ((s1 + s2) * t - s2 * s2 + s1 * s1);
}

inline double planar_release(const double *sh, double ks, double t)
{
  return planar_heat(ks, sh[0], t, 0.0);
}

// fix lattice/wall's forms of the same two heats, in the order of operations
// the wall has always used (its heat tallies keep their bits; the pair's forms
// above round differently in the last bit): a sliding spring, the heat
// Ks/2 [(s1 + s2).t - |s2|^2 + |s1|^2] added to q component by component,
inline void wall_slide_heat(double ks, const double *s1, const double *t, const double *s2,
                            double &q)
{
  for (int k = 0; k < 3; k++) q += 0.5 * ks * ((s1[k] + s2[k]) * t[k] - s2[k] * s2[k] + s1[k] * s1[k]);
}

// and a spring s let go (s2 = 0): Ks/2 s.(s + t)
inline double wall_release(double ks, const double *s, const double *t)
{
  return 0.5 * ks * (s[0] * (s[0] + t[0]) + s[1] * (s[1] + t[1]) + s[2] * (s[2] + t[2]));
}

/* ======================================================================
   energy of a record
   ====================================================================== */

// a normal spring at stretch xn: Kn xn^2 / 2
inline double normal_energy(double kn, double xn)
{
  return 0.5 * kn * xn * xn;
}

// the same from its force fn = Kn xn (the force loop has it at hand): fn xn / 2
LB_PHYSICS_INLINE double normal_energy_from_force(double fn, double xn)
{
  return 0.5 * fn * xn;
}

// a shear spring of squared length s2: Ks |S|^2 / 2
LB_PHYSICS_INLINE double spring_energy(double ks, double s2)
{
  return 0.5 * ks * s2;
}

// a signed 2D spring s: Ks s^2 / 2
LB_PHYSICS_INLINE double planar_spring_energy(double ks, double s)
{
  return 0.5 * ks * s * s;
}

// the change of a central spring's energy when its stretch goes from xn0 to
// xn1: an intact bond both ways, a broken bond or contact only while closed;
// as (a - b)(a + b), so that summed over many springs no two large sums
// cancel (the relaxations' line searches, lattice/quasistatic)
inline double central_energy_change(double kn, bool intact, double xn0, double xn1)
{
  const double a = (intact || !contact_open(xn1)) ? xn1 : 0.0;
  const double b = (intact || !contact_open(xn0)) ? xn0 : 0.0;
  return 0.5 * kn * (a - b) * (a + b);
}

// a record (or a wall contact) at stretch xn with a spring of squared length
// s2: Kn xn^2 / 2 + Ks |S|^2 / 2 (compute lattice/energy, element 1)
inline double record_energy(double kn, double xn, double ks, double s2)
{
  return normal_energy(kn, xn) + spring_energy(ks, s2);
}

}    // namespace LatticeBondPhysics
}    // namespace LAMMPS_NS

#undef LB_PHYSICS_INLINE

#endif
