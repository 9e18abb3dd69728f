/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The force loop of pair_style lattice/bond, PairLatticeBond::eval<F, Tally>,
   as a template that pair_lattice_bond_kernel.cpp (the serial style) and
   OPENMP/pair_lattice_bond_omp.cpp (the threaded one) compile: one loop, two
   ways to run it.  Include it only there.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_LATTICE_BOND_EVAL_H
#define LMP_PAIR_LATTICE_BOND_EVAL_H

#include "pair_lattice_bond.h"

#include "atom.h"
#include "fix_lattice_bond_store.h"
#include "lattice_bond_physics.h"
#include "lattice_bond_records.h"
#include "lattice_heterogeneity.h"
#include "lattice_rotation_fit.h"

#include <cmath>
#include <cstddef>

namespace LAMMPS_NS {
namespace LatticeEval {

// branches of the force loop taken by few records (breaking, contacts, fast
// rotation): laid out off the straight path of an intact bond
#define LB_RARE(cond) __builtin_expect(static_cast<bool>(cond), 0)
// records whose geometry the force loop forms in one pass (or one particle's, if more)
constexpr int BATCH_RECORDS = 24;
// how many particles ahead the 3D force loop requests the records (4 to 16 measured
// alike), and from which size of the spring array on (below, the requests cost more
// than they save: 3D blocks of 11k particles (1.6 MB) lost 2-4%, 49k (7 MB) were
// unchanged, 203k (29 MB) gained 25-35%; docs/performance.md)
constexpr int PREFETCH_AHEAD = 8;
constexpr double PREFETCH_MIN_BYTES = 10.0e6;

// request the cache lines of bytes at p (for writing if write)
inline void prefetch_bytes(const void *p, size_t bytes, bool write)
{
  const char *c = static_cast<const char *>(p);
  for (size_t b = 0; b < bytes; b += 64) {
    if (write) __builtin_prefetch(c + b, 1, 3);
    else __builtin_prefetch(c + b, 0, 3);
  }
}

/* ----------------------------------------------------------------------
   a spring of NC components let go
------------------------------------------------------------------------- */

template <int NC> inline void clear_spring(double *sh)
{
  for (int k = 0; k < NC; k++) sh[k] = 0.0;
}

}    // namespace LatticeEval

/* ----------------------------------------------------------------------
   the loop variant that runs feature set F: see pair_lattice_bond_kernel.cpp
------------------------------------------------------------------------- */

constexpr int PairLatticeBond::loop_variant(int F)
{
  // a step without energy/virial tallies: friction matters only with shear springs
  const int plain = (F & (LB_SHEAR_ALL | LB_SHEAR_SOME)) ? F : (F & ~LB_FRICTION);
  const int general = LB_SHEAR_SOME | LB_FRICTION |
      (F & (LB_EV | LB_TALLY | LB_PLANAR | LB_COROTATE | LB_HETERO | LB_EQUAL));
  const bool both_shear = (F & LB_SHEAR_ALL) && (F & LB_SHEAR_SOME);
  // without shear springs there is nothing to corotate (corotational() is false)
  const bool idle_corotate = (F & LB_COROTATE) && !(F & (LB_SHEAR_ALL | LB_SHEAR_SOME | LB_EV));
  if ((F & LB_EV) || both_shear) return general;
  if (idle_corotate) return plain & ~LB_COROTATE;
  return plain;
}

/* ----------------------------------------------------------------------
   the force loop over records (docs/theory.md, "The model"), compiled per feature
   set F (see scene_features):
   LB_EV: tally energy/virial; LB_TALLY: accumulate breaking and frictional
   heat (compute lattice/energy); LB_PLANAR: 2D, no z components;
   LB_UNIFORM: one parameter set for all type pairs; LB_SHEAR_ALL / _SOME:
   every / some type pair has Ks > 0 (neither: no shear springs);
   LB_FRICTION: some type pair has mu_p > 0 (without it broken bonds and
   contacts are frictionless and carry no shear spring); LB_EQUAL: every
   particle has the same radius (no per-partner radius load); LB_HETERO:
   each bond scales its type pair's parameters by its stiffness and
   strength factors (scaled_params).

   The physics of a record (stretch, break tests, the 2D and 3D spring
   updates, Coulomb sliding, the heat of each event, the energy) is in
   lattice_bond_physics.h, with the formulas; this loop decides which of them
   a record needs and applies the forces.

   It runs over the records of the local particles ifrom <= i < ito (each
   record belongs to one particle, so ranges are independent), adds the
   forces on both particles of a record to f (atom->f, or one thread's copy
   in pair_style lattice/bond/omp), and hands the energy/virial of a record
   and the heat of the range to the tally (SerialTally, or the /omp style's
   per-thread one).
------------------------------------------------------------------------- */

template <int F, class Sink>
void PairLatticeBond::eval(int ifrom, int ito, double (*const f)[3], Sink &tally)
{
  using namespace LatticeBondPhysics;
  using namespace LatticeEval;
  constexpr bool EVFLAG = F & LB_EV;
  constexpr bool TALLY = F & LB_TALLY;
  constexpr bool PLANAR = F & LB_PLANAR;
  constexpr bool UNIFORM = F & LB_UNIFORM;
  constexpr bool SHEAR = F & (LB_SHEAR_ALL | LB_SHEAR_SOME);
  constexpr bool SHEAR_ALL = F & LB_SHEAR_ALL;
  constexpr bool FRICTION = F & LB_FRICTION;
  constexpr bool EQUAL = F & LB_EQUAL;
  constexpr bool COROTATE = F & LB_COROTATE;
  constexpr bool HETERO = F & LB_HETERO;

  // LAMMPS keeps x and f contiguous: index them as arrays of triples
  const auto *const x = reinterpret_cast<const double(*)[3]>(atom->x[0]);
  const double *const radius = atom->radius;
  const int *const type = atom->type;
  const int nlocal = atom->nlocal;
  const int *const nrec = fix_store->record_counts();
  const auto *const disp = reinterpret_cast<const double(*)[3]>(fix_store->displacements());
  const int *const partner_idx = records->partner_index();
  const int stride = records->stride();
  const BondParams p_uniform = params[1][1];
  const double touch_equal = 2.0 * equal_radius;    // r + r is exact: the same bits
  const auto *const w = COROTATE ? reinterpret_cast<const double(*)[3]>(rotation_fit->spin()[0]) : nullptr;
  const double *const bond_factor = HETERO ? hetero->bond_factors(0, stride) : nullptr;
  const bool can_break = breaking_enabled;    // off while lattice/quasistatic relaxes
  // the springs: a signed length in 2D (compute() converts loaded vectors first)
  constexpr int NC = PLANAR ? 1 : 3;
  double q_break_n = 0.0, q_break_s = 0.0, q_friction = 0.0;
  const bool prefetch = !PLANAR && sizeof(double) * NC * stride * (double) nlocal >= PREFETCH_MIN_BYTES;

  // geometry of a batch of particles first (about BATCH_RECORDS records), then
  // their records: the lengths and directions come from one loop without
  // indexing, which the compiler turns into paired square roots and divisions,
  // and the processor overlaps them with the batch's record updates (a record
  // otherwise waits for the divider, docs/performance.md); the positions do
  // not change in between, so the bits are those of one record at a time
  double sep[3][MAX_RECORDS], dist[MAX_RECORDS], dinv[MAX_RECORDS];
  for (int i0 = ifrom; i0 < ito;) {
    int nb = 0, i1 = i0;
    for (; i1 < ito && (nb == 0 || nb + nrec[i1] <= BATCH_RECORDS); i1++) {
      const int *__restrict idx = partner_idx + (bigint) i1 * stride;
      const double xi = x[i1][0], yi = x[i1][1], zi = PLANAR ? 0.0 : x[i1][2];
      for (int s = 0; s < nrec[i1]; s++, nb++) {
        const int j = idx[s];
        // a far-away partner: any finite values (unit length)
        sep[0][nb] = (j < 0) ? 1.0 : xi - x[j][0];
        sep[1][nb] = (j < 0) ? 0.0 : yi - x[j][1];
        if (!PLANAR) sep[2][nb] = (j < 0) ? 0.0 : zi - x[j][2];
      }
    }
    for (int k = 0; k < nb; k++) {
      const double sx = sep[0][k], sy = sep[1][k], sz = PLANAR ? 0.0 : sep[2][k];
      const double rr = sqrt(sx * sx + sy * sy + sz * sz);
      const double rinv = 1.0 / rr;
      dist[k] = rr;
      dinv[k] = rinv;
      sep[0][k] = sx * rinv;    // now the unit vector
      sep[1][k] = sy * rinv;
      if (!PLANAR) sep[2][k] = sz * rinv;
    }
    int base = 0;
    for (int i = i0; i < i1; base += nrec[i], i++) {
      const int nr = nrec[i];
      // the springs and partner indices of the particle PREFETCH_AHEAD places on
      // are requested now, so that they arrive while this one computes: a large
      // 3D block otherwise waits on memory for each particle's records
      if (prefetch && i + PREFETCH_AHEAD < ito) {
        const int ahead = i + PREFETCH_AHEAD, n = nrec[ahead];
        prefetch_bytes(fix_store->springs(ahead), sizeof(double) * NC * n, true);
        prefetch_bytes(partner_idx + (bigint) ahead * stride, sizeof(int) * n, false);
      }
      if (!nr) continue;
      double *__restrict spr = fix_store->springs(i);
      LatticeBondState *__restrict st = fix_store->states(i);
      const int *__restrict idx = partner_idx + (bigint) i * stride;
      const double *__restrict factors = HETERO ? bond_factor + (size_t) i * stride * 2 : nullptr;
      const double xi = x[i][0], yi = x[i][1], zi = PLANAR ? 0.0 : x[i][2];
      const double dxi = disp[i][0], dyi = disp[i][1], dzi = PLANAR ? 0.0 : disp[i][2];
      const double radi = EQUAL ? 0.0 : radius[i];
      const BondParams *prow = params[type[i]];
      double fxi = 0.0, fyi = 0.0, fzi = 0.0;    // summed here: fewer stores in the loop
      const double *const rlen = dist + base;
      const double *const rinvs = dinv + base;
      const double *const unit[3] = {sep[0] + base, sep[1] + base, sep[2] + base};

      for (int s = 0; s < nr; s++) {
        const int j = idx[s];
        if (LB_RARE(j < 0)) continue;    // broken bond whose partner is far away
        double *const sh = spr + s * NC;    // this record's spring
        const BondParams &p_type = UNIFORM ? p_uniform : prow[type[j]];
        // heterogeneous rock: this bond's own stiffness and strength
        BondParams p_bond;
        if (HETERO) p_bond = scaled_params(p_type, factors[2 * s], factors[2 * s + 1]);
        const BondParams &p = HETERO ? p_bond : p_type;
        const bool has_shear = SHEAR && (SHEAR_ALL || p.ks > 0.0);

        // separation (for the tallies and the corotational frame), its length and direction
        const double dx = xi - x[j][0], dy = yi - x[j][1], dz = PLANAR ? 0.0 : zi - x[j][2];
        const double rr = rlen[s];
        const double nx = unit[0][s], ny = unit[1][s], nz = PLANAR ? 0.0 : unit[2][s];
        const double touch = EQUAL ? touch_equal : radi + radius[j];    // rest length
        const double xn = normal_stretch(rr, touch);    // tension positive
        // this step's relative displacement (dx minus its value at the last step)
        const double ddx = dxi - disp[j][0], ddy = dyi - disp[j][1];
        const double ddz = PLANAR ? 0.0 : dzi - disp[j][2];
        // the increment the shear springs see: with shear_frame corotational
        // without the pair's share of the local rigid rotation
        double ux = ddx, uy = ddy, uz = ddz;
        if (COROTATE) remove_rigid_rotation<PLANAR>(w[i], w[j], dx, dy, dz, ux, uy, uz);

        // 2D: its part along the tangent t = z x n at mid-step
        const double dtan = PLANAR ? planar_increment(nx, ny, ux, uy, rinvs[s]) : 0.0;

        int state = st[s];
        if (LB_RARE(state == LB_INTACT && breaks_in_tension(xn, p.xb) && can_break)) {
          // tensile break: both springs let go
          st[s] = LB_BROKEN_TENSION;
          state = LB_BROKEN_TENSION;
          if (TALLY) {
            q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
            q_break_s += PLANAR ? planar_release(sh, p.ks, dtan) : spring_release(sh, p.ks, ddx, ddy, ddz);
            clear_spring<NC>(sh);
          }
        }
        if (LB_RARE(state != LB_INTACT && contact_open(xn))) {
          // open contact: no force, no memory
          if (TALLY)
            q_friction += PLANAR ? planar_release(sh, p.ks, dtan) : spring_release(sh, p.ks, ddx, ddy, ddz);
          clear_spring<NC>(sh);
          continue;
        }

        const double fn = normal_force(p.kn, xn);    // tension positive
        double fsx = 0.0, fsy = 0.0, fsz = 0.0, es = 0.0;

        if (state == LB_INTACT && !has_shear && coulomb_limit(p.fs0, p.mu_p, fn) < 0.0 &&
            can_break) {
          // no shear spring: the bond fails in shear only when its Coulomb
          // limit itself becomes negative (tension above Fs0/mu_p)
          st[s] = LB_BROKEN_SHEAR;
          state = LB_BROKEN_SHEAR;
          if (contact_open(xn)) {
            if (TALLY)
              q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
            continue;
          }
        }

        // a frictionless contact (closed, mu_p = 0 everywhere) has no shear spring.
        // The 2D and 3D branches differ in the spring's form only (a signed length,
        // a vector) and call the same physics; folded into one branch over a spring
        // type with both forms they gave the same bits but 5.4% more instructions in
        // the 3D loop and 0.8% in the 2D loop (GCC kept the spring in memory;
        // cachegrind, bench_throughput --steps 200), so they stay two
        if (PLANAR && has_shear && (FRICTION || state == LB_INTACT)) {
          // 2D: the spring is a signed length along t, which turns with the
          // pair, so it needs no projection and keeps its length exactly
          const double s1 = sh[0];
          double sig = s1 + dtan;
          const double fs2 = planar_force_squared(p.ks, sig);
          const bool broke_now =
              state == LB_INTACT && LB_RARE(breaks_in_shear(p.fs0, p.mu_p, fn, fs2) && can_break);
          if (broke_now) state = st[s] = LB_BROKEN_SHEAR;
          if (LB_RARE(state != LB_INTACT)) {
            if (contact_open(xn)) {
              // broken in shear while in tension: the contact is open
              if (TALLY) {
                q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
                q_break_s += planar_heat(p.ks, s1, dtan, 0.0);
              }
              sh[0] = 0.0;
              continue;
            }
            if (FRICTION) {
              const double limit = friction_limit(p.mu_p, fn);    // sliding friction of a contact
              if (slides(fs2, limit)) {
                const double slid = planar_slid(p.ks, limit, sig);
                if (TALLY) {
                  const double q = planar_heat(p.ks, s1, dtan, slid);
                  if (broke_now) q_break_s += q;
                  else q_friction += q;
                }
                sig = slid;
              }
            } else {
              // broke in shear just now: a frictionless contact keeps no spring
              if (TALLY) q_break_s += planar_heat(p.ks, s1, dtan, 0.0);
              sig = 0.0;
            }
          }
          sh[0] = sig;
          // force on the owner -Ks sig t
          fsx = p.ks * sig * ny;
          fsy = -p.ks * sig * nx;
          if (EVFLAG) es = planar_spring_energy(p.ks, sig);
        } else if (!PLANAR && has_shear && (FRICTION || state == LB_INTACT)) {
          // compiled only into the 3D loops: the 2D loops' code does not depend on it
          if constexpr (!PLANAR) {
            double s0x = sh[0], s0y = sh[1], s0z = sh[2];
            // shear_frame corotational: the spring turned with the pair's rotation
            if (COROTATE) rotate_spring(w[i], w[j], s0x, s0y, s0z);
            // turned into the new tangent plane, plus the tangential increment
            const SpringStep step = spring_step(nx, ny, nz, s0x, s0y, s0z, ux, uy, uz);
            double sx = step.sx, sy = step.sy, sz = step.sz;
            const double fs2 = shear_force_squared(p.ks, step.s2);
            const bool broke_now =
                state == LB_INTACT && LB_RARE(breaks_in_shear(p.fs0, p.mu_p, fn, fs2) && can_break);
            if (broke_now) state = st[s] = LB_BROKEN_SHEAR;
            if (LB_RARE(state != LB_INTACT)) {
              // the two parts of the step (for the heat): the turned old spring and the increment
              const double s1[3] = {step.s1x, step.s1y, step.s1z}, t[3] = {step.tx, step.ty, step.tz};
              if (contact_open(xn)) {
                // broken in shear while in tension: the contact is open
                if (TALLY) {
                  const double none[3] = {0.0, 0.0, 0.0};
                  q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
                  q_break_s += shear_heat(p.ks, s1, t, none);
                }
                clear_spring<NC>(sh);
                continue;
              }
              if (FRICTION) {
                const double limit = friction_limit(p.mu_p, fn);    // sliding friction of a contact
                if (slides(fs2, limit)) {
                  const double scale = slide_scale(p.ks, limit, step.s2);
                  sx *= scale;
                  sy *= scale;
                  sz *= scale;
                  if (TALLY) {
                    const double s2[3] = {sx, sy, sz};
                    const double q = shear_heat(p.ks, s1, t, s2);
                    if (broke_now) q_break_s += q;
                    else q_friction += q;
                  }
                }
              } else {
                // broke in shear just now: a frictionless contact keeps no spring
                if (TALLY) {
                  const double none[3] = {0.0, 0.0, 0.0};
                  q_break_s += shear_heat(p.ks, s1, t, none);
                }
                sx = sy = sz = 0.0;
              }
            }
            sh[0] = sx;
            sh[1] = sy;
            sh[2] = sz;
            fsx = -p.ks * sx;
            fsy = -p.ks * sy;
            fsz = -p.ks * sz;
            if (EVFLAG) es = spring_energy(p.ks, sx * sx + sy * sy + sz * sz);
          }
        } else if (has_shear) {
          clear_spring<NC>(sh);    // a frictionless closed contact
        }

        // force on the owner i; the partner gets the opposite
        const double fx = -fn * nx + fsx, fy = -fn * ny + fsy;
        const double fz = PLANAR ? 0.0 : -fn * nz + fsz;
        fxi += fx;
        fyi += fy;
        f[j][0] -= fx;
        f[j][1] -= fy;
        if (!PLANAR) {
          fzi += fz;
          f[j][2] -= fz;
        }

        if (EVFLAG) {
          const double e = eflag_either ? normal_energy_from_force(fn, xn) + es : 0.0;
          tally.pair(i, j, nlocal, e, fx, fy, fz, dx, dy, dz);
        }
      }
      f[i][0] += fxi;
      f[i][1] += fyi;
      if (!PLANAR) f[i][2] += fzi;
    }
    i0 = i1;
  }
  if (TALLY) tally.heat(q_break_n, q_break_s, q_friction);
}

}    // namespace LAMMPS_NS

#undef LB_RARE

#endif
