/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   LatticeDirectRelax: the seed's loop with exact linear equilibria
   (lattice_direct_relax.h).  The springs are the records of pair_style
   lattice/bond whose owner is local and whose partner is present, as in
   relax local; their stretch and ratios are the force loop's for Ks = 0
   (lattice_bond_physics.h), evaluated at the linear model's displacements.
   Rank 0 holds the network and the factor; the other ranks send their
   atoms and records and receive the displacements and the breaks.
------------------------------------------------------------------------- */

#include "lattice_direct_relax.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "lattice_bond_geometry.h"
#include "lattice_bond_physics.h"
#include "lattice_relax_model.h"
#include "lattice_thread_pool.h"
#include "neighbor.h"
#include "pair_lattice_bond.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

using namespace LAMMPS_NS;
using namespace LAMMPS_NS::LatticeBondPhysics;

// the factor is of K + SHIFT x (mean Kn) I: a part of the network that comes
// loose (no spring to a held particle) keeps a definite matrix.  Its effect on
// a solve is SHIFT over the smallest eigenvalue of the network relative to
// Kn (about 1e-6 for 1000 particles between the walls): far below the
// tolerance, and the next pass's right-hand side is the pair style's force
static constexpr double SHIFT = 1.0e-12;
// a kept factor is made anew at a pass's start when a spring's direction has
// turned by more than this (radians) since it was made: a Newton step with
// the factor then leaves about this fraction of the force it removes
static constexpr double MAX_TURN = 1.0e-3;
// Newton steps of one equilibrium: after NEWTON_REFRESH the factor is made
// anew at the current directions, after NEWTON_MAX the pass ends
static constexpr int NEWTON_REFRESH = 6;
static constexpr int NEWTON_MAX = 30;
// a flop of the factorisation's dense kernels takes this fraction of the time
// of a flop of a solve, which streams the factor from memory (measured by
// bench/sparse_cholesky.py: 1.53 s and 0.067 s at 184,800 particles)
static constexpr double FACTOR_FLOP_SPEED = 0.32;
// the over-relaxation of the local smoothing after a Newton step, and its
// budget of particle moves per unknown before a solve takes over instead
static constexpr double SMOOTH_OMEGA = 1.5;
static constexpr double SMOOTH_BUDGET = 0.25;
// a Newton step moves no particle more than this fraction of the smallest
// radius (relax local's budget between force evaluations); rounds of
// direction updates before a new factor, then a shorter step
static constexpr double STEP_FRACTION = 0.05;
static constexpr int STEP_ROUNDS = 2;
// a Newton step is halved until the springs'
// energy falls by at least ARMIJO of what the step's slope promises, at most
// STEP_HALVINGS times (then the shortest is taken)
static constexpr double ARMIJO = 1.0e-4;
static constexpr int STEP_HALVINGS = 40;
// the loops over the whole network (forces, stretches, energy sums, the
// worst spring, the longest move) run on the factor's threads in blocks of
// this many springs or nodes.  Every value is computed by itself and the
// sums and searches combine them in the order of the serial loop (a node's
// force from its springs in ID order, the energy change spring by spring in
// ID order, the first of the largest ratio), so the results are the same,
// bit for bit, for any number of threads
static constexpr size_t LOOP_BLOCK = 2048;

namespace {
// m x = rhs for the symmetric dim x dim block m (Cramer); false if singular
bool solve_small(const double m[3][3], const double *rhs, double *x, int dim)
{
  if (dim == 2) {
    const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if (!(std::fabs(det) > 0.0)) return false;
    x[0] = (m[1][1] * rhs[0] - m[0][1] * rhs[1]) / det;
    x[1] = (m[0][0] * rhs[1] - m[1][0] * rhs[0]) / det;
    return true;
  }
  auto det3 = [](const double t[3][3]) {
    return t[0][0] * (t[1][1] * t[2][2] - t[1][2] * t[2][1]) -
        t[0][1] * (t[1][0] * t[2][2] - t[1][2] * t[2][0]) +
        t[0][2] * (t[1][0] * t[2][1] - t[1][1] * t[2][0]);
  };
  const double det = det3(m);
  if (!(std::fabs(det) > 0.0)) return false;
  for (int c = 0; c < 3; c++) {
    double t[3][3];
    for (int p = 0; p < 3; p++)
      for (int q = 0; q < 3; q++) t[p][q] = (q == c) ? rhs[p] : m[p][q];
    x[c] = det3(t) / det;
  }
  return true;
}

// the cost of a factorisation in solves, from the blocks of the ordering:
// per tree node the dense partial Cholesky of its n columns, the triangular
// solve of its |R| rows and the update of the |R| x |R| trailing matrix,
// against a solve's two passes over every entry of the factor
double factor_in_solves(const LatticeSparseCholesky &factor)
{
  double fact = 0.0, entries = 0.0;
  for (int t = 0; t < factor.ntree(); t++) {
    const double n = factor.col_end(t) - factor.col_begin(t), r = factor.nrows(t);
    fact += n * n * n / 3.0 + n * n * r + n * r * r;
    entries += n * (n + 1) / 2.0 + n * r;
  }
  return entries > 0.0 ? FACTOR_FLOP_SPEED * fact / (4.0 * entries) : 0.0;
}
}    // namespace

// values sent per atom (tag apart): x (dim), held bits
// values per record: the owner-to-partner vector (3), r, touch, kn, xb, fs0, mu_p, intact
static constexpr int RECORD_VALUES = 10;

LatticeDirectRelax::LatticeDirectRelax(LAMMPS *lmp, PairLatticeBond *pair_in, double ftol_in,
                                       int threads_in) :
    Pointers(lmp), pair(pair_in), ftol(ftol_in), threads(threads_in), max_step(0.0), max_travel(0.0)
{
}

void LatticeDirectRelax::check_model()
{
  LatticeRelaxModel::check(lmp, pair, "relax direct");
}

void LatticeDirectRelax::probe_fixes()
{
  held_ids = LatticeRelaxModel::held_components(lmp, "relax direct");
}

/* ----------------------------------------------------------------------
   the atoms and records of every rank on rank 0, nodes in ID order and
   springs in (owner, partner) order, whatever the decomposition
------------------------------------------------------------------------- */

namespace {
template <typename T>
std::vector<T> gather_to_root(const std::vector<T> &mine, MPI_Datatype type, MPI_Comm world,
                              int nprocs)
{
  int count = (int) mine.size();
  std::vector<int> counts(nprocs, 0), offsets(nprocs, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  for (int p = 1; p < nprocs; p++) offsets[p] = offsets[p - 1] + counts[p - 1];
  std::vector<T> all(offsets[nprocs - 1] + counts[nprocs - 1]);
  // LAMMPS' serial MPI stubs take the send buffer as void *
  MPI_Gatherv(const_cast<T *>(mine.data()), count, type, all.data(), counts.data(), offsets.data(),
              type, 0, world);
  return all;
}
}    // namespace

void LatticeDirectRelax::gather(Network &net)
{
  const int dim = domain->dimension;
  const int nlocal = atom->nlocal, nprocs = comm->nprocs;
  const tagint *tag = atom->tag;
  double **x = atom->x;

  std::unordered_map<tagint, int> held;
  for (size_t e = 0; e + 1 < held_ids.size(); e += 2) held[held_ids[e]] |= (int) held_ids[e + 1];

  std::vector<tagint> atom_tags(nlocal);
  std::vector<double> atom_values;
  atom_values.reserve((size_t) nlocal * (dim + 1));
  for (int i = 0; i < nlocal; i++) {
    atom_tags[i] = tag[i];
    for (int c = 0; c < dim; c++) atom_values.push_back(x[i][c]);
    const auto it = held.find(tag[i]);
    atom_values.push_back(it == held.end() ? 0.0 : (double) it->second);
  }

  FixLatticeBondStore *store = pair->store();
  const int *pidx = pair->partner_index();
  const int stride = pair->partner_index_stride();
  const auto radius = pair->radii();
  std::vector<tagint> record_tags;
  std::vector<double> record_values;
  for (int i = 0; i < nlocal && pidx; i++) {
    const LatticeBondState *st = store->states(i);
    for (int s = 0; s < store->record_count(i); s++) {
      const int j = pidx[(bigint) i * stride + s];
      if (j < 0) continue;    // a broken bond whose partner is far away: open
      const PairSeparation d = pair_separation(x, i, j);
      const auto p = pair->bond_params(i, j);
      record_tags.push_back(tag[i]);
      record_tags.push_back(tag[j]);
      const double v[RECORD_VALUES] = {-d.dx, -d.dy, -d.dz, d.length(), radius.touch(i, j), p.kn,
                                       p.xb, p.fs0, p.mu_p, st[s] == LB_INTACT ? 1.0 : 0.0};
      record_values.insert(record_values.end(), v, v + RECORD_VALUES);
    }
  }

  const auto all_tags = gather_to_root(atom_tags, MPI_LMP_TAGINT, world, nprocs);
  const auto all_values = gather_to_root(atom_values, MPI_DOUBLE, world, nprocs);
  const auto all_record_tags = gather_to_root(record_tags, MPI_LMP_TAGINT, world, nprocs);
  const auto all_record_values = gather_to_root(record_values, MPI_DOUBLE, world, nprocs);
  net.dim = dim;
  if (comm->me != 0) return;

  // nodes in ID order
  const size_t natoms = all_tags.size();
  std::vector<size_t> order(natoms);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return all_tags[a] < all_tags[b]; });
  net.tags.resize(natoms);
  net.coords.assign(natoms * dim, 0.0);
  net.free.assign(natoms * dim, 1);
  std::unordered_map<tagint, int> node;
  node.reserve(natoms);
  const size_t per_atom = dim + 1;
  for (size_t n = 0; n < natoms; n++) {
    const size_t g = order[n];
    net.tags[n] = all_tags[g];
    node[all_tags[g]] = (int) n;
    const double *v = &all_values[g * per_atom];
    const int bits = (int) v[dim];
    for (int c = 0; c < dim; c++) {
      net.coords[n * dim + c] = v[c];
      net.free[n * dim + c] = (bits & (1 << c)) ? 0 : 1;
    }
  }

  // springs in (owner, partner) order
  const size_t nrec = all_record_tags.size() / 2;
  std::vector<size_t> rorder(nrec);
  std::iota(rorder.begin(), rorder.end(), 0);
  std::sort(rorder.begin(), rorder.end(), [&](size_t a, size_t b) {
    const tagint *ta = &all_record_tags[2 * a], *tb = &all_record_tags[2 * b];
    return ta[0] < tb[0] || (ta[0] == tb[0] && ta[1] < tb[1]);
  });
  net.springs.resize(nrec);
  net.keys.resize(nrec);
  net.intact.resize(nrec);
  net.e.resize(nrec);
  for (size_t k = 0; k < nrec; k++) {
    const size_t g = rorder[k];
    const tagint owner = all_record_tags[2 * g], partner = all_record_tags[2 * g + 1];
    const double *v = &all_record_values[g * RECORD_VALUES];
    Spring &s = net.springs[k];
    s.a = node.at(owner);
    s.b = node.at(partner);
    for (int c = 0; c < 3; c++) s.d[c] = v[c];
    s.touch = v[4];
    s.kn = v[5];
    s.xb = v[6];
    s.fs0 = v[7];
    s.mu_p = v[8];
    net.intact[k] = v[9] != 0.0;
    net.e[k] = normal_stretch(v[3], s.touch);
    net.keys[k] = {owner, partner};
  }
}

/* ----------------------------------------------------------------------
   a spring as a term of the factor (its direction in the factor), and its
   ratio to the threshold at its stretch
------------------------------------------------------------------------- */

LatticeSpring LatticeDirectRelax::term(const LatticeDirectState &state, int k) const
{
  LatticeSpring t;
  t.a = state.ends[k].first;
  t.b = state.ends[k].second;
  t.k = state.kn[k];
  for (int c = 0; c < 3; c++) t.n[c] = state.n[3 * (size_t) k + c];
  return t;
}

namespace {
// the unit directions across the unit vector n: one in 2D (z x n), two in 3D
int directions_across(const double n[3], int dim, double t[2][3])
{
  if (dim == 2) {
    t[0][0] = -n[1];
    t[0][1] = n[0];
    t[0][2] = 0.0;
    return 1;
  }
  // the axis least along n, made normal to it, then n x that
  int axis = 0;
  for (int c = 1; c < 3; c++)
    if (std::fabs(n[c]) < std::fabs(n[axis])) axis = c;
  double a[3] = {0.0, 0.0, 0.0};
  a[axis] = 1.0;
  double len = 0.0;
  for (int c = 0; c < 3; c++) {
    t[0][c] = a[c] - n[axis] * n[c];
    len += t[0][c] * t[0][c];
  }
  len = std::sqrt(len);
  for (int c = 0; c < 3; c++) t[0][c] /= len;
  t[1][0] = n[1] * t[0][2] - n[2] * t[0][1];
  t[1][1] = n[2] * t[0][0] - n[0] * t[0][2];
  t[1][2] = n[0] * t[0][1] - n[1] * t[0][0];
  return 2;
}
}    // namespace

int LatticeDirectRelax::modify_across(LatticeDirectState &state, int a, int b, double kx,
                                      const double *n, int sign)
{
  if (!(kx > 0.0)) return 0;
  double t[2][3];
  const int count = directions_across(n, state.dim, t);
  for (int q = 0; q < count; q++) state.factor.modify({a, b, kx, {t[q][0], t[q][1], t[q][2]}}, sign);
  return count;
}

// PairLatticeBond::bond_load with no shear spring (fs = 0), at the stretch e
double LatticeDirectRelax::ratio(const Spring &s, double e, BreakMode &mode) const
{
  const double tension = tensile_ratio(e, s.xb);
  const double shear = shear_ratio(0.0, s.mu_p, normal_force(s.kn, e), s.fs0);
  mode = (tension >= shear) ? BreakMode::Tension : BreakMode::Shear;
  return MAX(tension, shear);
}

/* ----------------------------------------------------------------------
   the springs' stretches and the forces on the free components at the
   displacements u: the force loop's for Ks = 0 (an intact bond pulls and
   pushes, a broken one or a contact only pushes); returns the largest
   free force component
------------------------------------------------------------------------- */

void LatticeDirectRelax::offset(const Spring &s, int dim, const std::vector<double> &u, double d[3])
{
  for (int c = 0; c < 3; c++) d[c] = s.d[c];
  for (int c = 0; c < dim; c++) d[c] += u[(size_t) s.b * dim + c] - u[(size_t) s.a * dim + c];
}

void LatticeDirectRelax::spring_state(const Spring &s, bool intact, int dim,
                                      const std::vector<double> &u, double &e, double *f)
{
  double d[3];
  offset(s, dim, u, d);
  const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  e = normal_stretch(r, s.touch);
  // on the owner along the owner-to-partner vector, tension positive; an open contact none
  const double scale = (!intact && contact_open(e)) ? 0.0 : normal_force(s.kn, e) / r;
  for (int c = 0; c < 3; c++) f[c] = scale * d[c];
}

void LatticeDirectRelax::update_spring(Network &net, size_t k, const std::vector<double> &u)
{
  spring_state(net.springs[k], net.intact[k] != 0, net.dim, u, net.e[k], &net.f[3 * k]);
}

double LatticeDirectRelax::forces(Network &net, const std::vector<double> &u,
                                  std::vector<double> &f) const
{
  const int dim = net.dim;
  const size_t nnodes = net.tags.size();
  // the springs' stretches and forces, unless a Newton step's line search left them at u
  if (!net.current) {
    net.f.resize(3 * net.springs.size());
    for_blocks(pool, net.springs.size(), LOOP_BLOCK, [&](size_t, size_t k0, size_t k1) {
      for (size_t k = k0; k < k1; k++) update_spring(net, k, u);
    });
    net.current = true;
  }
  // each node's force from its springs in ID order: the sum the loop over the springs
  // (owner +f, partner -f) makes
  f.resize(u.size());
  std::vector<double> block_largest((nnodes + LOOP_BLOCK - 1) / LOOP_BLOCK, 0.0);
  for_blocks(pool, nnodes, LOOP_BLOCK, [&](size_t blk, size_t a0, size_t a1) {
    double largest = 0.0;
    for (size_t a = a0; a < a1; a++) {
      double sum[3] = {0.0, 0.0, 0.0};
      for (int e = net.node_start[a]; e < net.node_start[a + 1]; e++) {
        const double *fk = &net.f[3 * (size_t) net.node_springs[e]];
        if (net.node_owns[e])
          for (int c = 0; c < dim; c++) sum[c] += fk[c];
        else
          for (int c = 0; c < dim; c++) sum[c] -= fk[c];
      }
      for (int c = 0; c < dim; c++) {
        const size_t q = a * dim + c;
        f[q] = net.free[q] ? sum[c] : 0.0;
        largest = MAX(largest, std::fabs(f[q]));
      }
    }
    block_largest[blk] = largest;
  });
  double largest = 0.0;
  for (const double v : block_largest) largest = MAX(largest, v);
  return largest;
}

double LatticeDirectRelax::longest_move(const Network &net, const std::vector<double> &v,
                                        double beyond, std::vector<int> *far) const
{
  const int dim = net.dim;
  const size_t nnodes = net.tags.size(), nblocks = (nnodes + LOOP_BLOCK - 1) / LOOP_BLOCK;
  std::vector<double> block_longest(nblocks, 0.0);
  std::vector<std::vector<int>> block_far(far ? nblocks : 0);
  for_blocks(pool, nnodes, LOOP_BLOCK, [&](size_t blk, size_t a0, size_t a1) {
    double longest = 0.0;
    for (size_t a = a0; a < a1; a++) {
      double sq = 0.0;
      for (int c = 0; c < dim; c++) sq += v[a * dim + c] * v[a * dim + c];
      const double move = std::sqrt(sq);
      longest = MAX(longest, move);
      if (far && move > beyond) block_far[blk].push_back((int) a);
    }
    block_longest[blk] = longest;
  });
  double longest = 0.0;
  for (const double l : block_longest) longest = MAX(longest, l);
  if (far) {
    far->clear();
    for (const auto &b : block_far) far->insert(far->end(), b.begin(), b.end());
  }
  return longest;
}

/* ----------------------------------------------------------------------
   the change of the springs' elastic energy from the last force evaluation
   (the stretches it left in the springs) to other displacements (an
   intact bond at any stretch, a broken one or a contact when closed: the
   energy whose gradient forces() returns), and the length of a Newton step:
   halved until the energy falls by at least ARMIJO of what the step's slope
   promises.  The factor holds each spring's material stiffness, Kn n n^T, and
   the stiffness its tension gives across it (T / r) only where a step was
   too long (newton_step): before those terms a particle on
   a kinked chain in tension, whose stiffness across the chain is mostly
   that, overshoots the straight line by far and swings to and fro (three
   particles, a kink of 1e-6 m: 100 passes, 7500 solves, left 95 N out of
   equilibrium); a particle pulled across a straight chain into a contact
   swings into the contact and out (polycrystal at 184,800 particles).  The
   energy is convex in the stretches and falls along a Newton step, so the
   halved step converges; a whole step that lowers the energy is taken whole
------------------------------------------------------------------------- */

double LatticeDirectRelax::energy_change(Network &net, const std::vector<double> &to) const
{
  // spring by spring: no cancellation between two large sums; the stretches at the
  // start are those of the last force evaluation (e)
  const size_t ns = net.springs.size();
  scratch.resize(ns);
  net.e_trial.resize(ns);
  net.f_trial.resize(3 * ns);
  for_blocks(pool, ns, LOOP_BLOCK, [&](size_t, size_t k0, size_t k1) {
    for (size_t k = k0; k < k1; k++) {
      const Spring &s = net.springs[k];
      const bool intact = net.intact[k] != 0;
      spring_state(s, intact, net.dim, to, net.e_trial[k], &net.f_trial[3 * k]);
      scratch[k] = central_energy_change(s.kn, intact, net.e[k], net.e_trial[k]);
    }
  });
  double sum = 0.0;
  for (size_t k = 0; k < ns; k++) sum += scratch[k];
  return sum;
}

double LatticeDirectRelax::step_length(Network &net, const std::vector<double> &u,
                                       const std::vector<double> &f,
                                       const std::vector<double> &step, bool &at_trial) const
{
  at_trial = false;
  double slope = 0.0;    // -dE/dalpha at u along the step
  for (size_t q = 0; q < u.size(); q++)
    if (net.free[q]) slope += f[q] * step[q];
  if (!(slope > 0.0)) return 1.0;
  std::vector<double> trial(u.size());
  double alpha = 1.0;
  for (int h = 0; h < STEP_HALVINGS; h++, alpha *= 0.5) {
    for_blocks(pool, u.size(), LOOP_BLOCK, [&](size_t, size_t q0, size_t q1) {
      for (size_t q = q0; q < q1; q++) trial[q] = net.free[q] ? u[q] + alpha * step[q] : u[q];
    });
    if (energy_change(net, trial) <= -ARMIJO * alpha * slope) {
      at_trial = true;
      return alpha;
    }
  }
  return alpha;
}

/* ----------------------------------------------------------------------
   what a Newton step leaves (the springs' turn since the factor was made,
   mostly near the break) removed locally: Gauss-Seidel over-relaxation of
   the particles whose free force exceeds ftol, in the order they come up
   (relax local's move, D^-1 f with D = sum of Kn n n^T over the springs that
   carry force and, for those in tension, the stiffness across them that
   their tension gives, T / r (I - n n^T); serial on rank 0).  f holds the
   forces at u and is kept up to date.  false if `budget` moves did not bring
   every force below ftol
------------------------------------------------------------------------- */

bool LatticeDirectRelax::smooth(Network &net, std::vector<double> &u, std::vector<double> &f,
                                bigint budget) const
{
  const int dim = net.dim;
  const size_t nnodes = net.tags.size();
  auto above = [&](size_t a) {
    for (int c = 0; c < dim; c++)
      if (std::fabs(f[a * dim + c]) > ftol) return true;
    return false;
  };
  std::vector<int> queue;
  std::vector<unsigned char> queued(nnodes, 0);
  for (size_t a = 0; a < nnodes; a++)
    if (above(a)) {
      queue.push_back((int) a);
      queued[a] = 1;
    }
  size_t head = 0;
  bigint moves = 0;
  while (head < queue.size()) {
    if (moves >= budget) {
      return false;
    }
    const int a = queue[head++];
    queued[a] = 0;
    if (!above(a)) continue;
    // D on the free components (a direction no spring resists carries no force)
    double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int e = net.node_start[a]; e < net.node_start[a + 1]; e++) {
      const size_t k = net.node_springs[e];
      const Spring &s = net.springs[k];
      if (!net.intact[k] && contact_open(net.e[k])) continue;
      double d[3];
      offset(s, dim, u, d);
      const double rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      const double r = std::sqrt(rsq);
      const double across =
          tension_stiffness_across(s.kn, normal_stretch(r, s.touch), r, net.intact[k] != 0);
      for (int p = 0; p < dim; p++)
        for (int q = 0; q < dim; q++)
          m[p][q] += (s.kn - across) * d[p] * d[q] / rsq + (p == q ? across : 0.0);
    }
    double rhs[3] = {0, 0, 0}, trace = 0.0;
    for (int c = 0; c < dim; c++) trace += m[c][c];
    for (int c = 0; c < dim; c++) {
      if (net.free[(size_t) a * dim + c]) {
        rhs[c] = f[(size_t) a * dim + c];
        m[c][c] += 1.0e-12 * trace;
      } else {
        for (int q = 0; q < dim; q++) m[c][q] = m[q][c] = 0.0;
        m[c][c] = 1.0;
      }
    }
    double dx[3] = {0, 0, 0};
    if (!solve_small(m, rhs, dx, dim)) continue;
    // a particle with almost no stiffness across its springs (on a straight chain)
    // moves no further than a Newton step may, and a pass ends once one has gone
    // half the skin (equilibrate)
    double len = 0.0;
    for (int c = 0; c < dim; c++) len += dx[c] * dx[c];
    len = SMOOTH_OMEGA * std::sqrt(len);
    const double scale = (len > max_step) ? max_step / len : 1.0;
    double travel = 0.0;
    for (int c = 0; c < dim; c++) {
      u[(size_t) a * dim + c] += SMOOTH_OMEGA * dx[c] * scale;
      travel += u[(size_t) a * dim + c] * u[(size_t) a * dim + c];
    }
    moves++;
    for (int e = net.node_start[a]; e < net.node_start[a + 1]; e++) {
      const size_t k = net.node_springs[e];
      const Spring &s = net.springs[k];
      const double old[3] = {net.f[3 * k], net.f[3 * k + 1], net.f[3 * k + 2]};
      update_spring(net, k, u);
      for (int c = 0; c < dim; c++) {
        const double df = net.f[3 * k + c] - old[c];
        if (net.free[(size_t) s.a * dim + c]) f[(size_t) s.a * dim + c] += df;
        if (net.free[(size_t) s.b * dim + c]) f[(size_t) s.b * dim + c] -= df;
      }
      for (const int b : {s.a, s.b})
        if (!queued[b] && above(b)) {
          queued[b] = 1;
          queue.push_back(b);
        }
    }
    if (std::sqrt(travel) > max_travel) return false;
    if (head > 4096 && head * 2 > queue.size()) {
      queue.erase(queue.begin(), queue.begin() + (long) head);
      head = 0;
    }
  }
  return true;
}

/* ----------------------------------------------------------------------
   the factor of the springs that carry force: the kept one if it is of the
   same atoms, records and stiffness and no spring has turned by more than
   MAX_TURN since it was made; else a new one (a new ordering only if the
   atoms or records changed)
------------------------------------------------------------------------- */

void LatticeDirectRelax::prepare_factor(Network &net, LatticeDirectState &state,
                                        const std::vector<double> &u, Outcome &out)
{
  const size_t ns = net.springs.size();
  const bool pattern = state.dim == net.dim && state.tags == net.tags && state.keys == net.keys &&
      state.free == net.free;
  bool keep = pattern && state.factor.factorised();
  for (size_t k = 0; k < ns && keep; k++) {
    const Spring &s = net.springs[k];
    if (state.kn[k] != s.kn) keep = false;
    double turn = 0.0, r = 0.0;
    for (int c = 0; c < 3; c++) r += s.d[c] * s.d[c];
    r = std::sqrt(r);
    for (int c = 0; c < 3; c++) {
      const double dn = s.d[c] / r - state.n[3 * k + c];
      turn += dn * dn;
    }
    if (turn > MAX_TURN * MAX_TURN) keep = false;
  }
  if (keep) return;
  if (!pattern) {
    state.dim = net.dim;
    state.tags = net.tags;
    state.keys = net.keys;
    state.free = net.free;
    state.ends.resize(ns);
    std::vector<std::pair<int, int>> pairs(ns);
    for (size_t k = 0; k < ns; k++) pairs[k] = state.ends[k] = {net.springs[k].a, net.springs[k].b};
    state.factor.analyse(net.dim, (int) net.tags.size(), net.coords.data(), net.free, pairs);
    state.factor_in_solves = factor_in_solves(state.factor);
    out.analysed = true;
  }
  factorise(net, state, u);
  out.factorised++;
  if (out.analysed)
    utils::logmesg(lmp, "lattice/quasistatic relax direct: {} unknowns in nested dissection "
                   "order ({} tree nodes, depth {}); factor of {:.4g} entries, {:.0f} MB; a "
                   "factorisation costs about {:.1f} solves\n", state.factor.ncols(),
                   state.factor.ntree(), state.factor.depth(), state.factor.factor_entries(),
                   state.factor.bytes() / 1048576.0, state.factor_in_solves);
}

// a new factor of the springs that carry force at the displacements u, with
// their directions there
void LatticeDirectRelax::factorise(Network &net, LatticeDirectState &state,
                                   const std::vector<double> &u)
{
  const int dim = net.dim;
  const size_t ns = net.springs.size();
  state.kn.resize(ns);
  state.n.resize(3 * ns);
  state.in_factor.assign(ns, 0);
  std::vector<LatticeSpring> active;
  double mean = 0.0;
  for (size_t k = 0; k < ns; k++) {
    const Spring &s = net.springs[k];
    double d[3] = {s.d[0], s.d[1], s.d[2]};
    if (!u.empty()) offset(s, dim, u, d);
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    state.kn[k] = s.kn;
    for (int c = 0; c < 3; c++) state.n[3 * k + c] = (r > 0.0) ? d[c] / r : 0.0;
    mean += s.kn;
    if (net.intact[k] || !contact_open(net.e[k])) {
      state.in_factor[k] = 1;
      active.push_back(term(state, (int) k));
    }
  }
  // the stiffness across the springs in tension only for the springs of a particle whose
  // Newton step was too long, at their tension then (newton_step).  In the whole factor
  // it would be stale in the next pass: a particle left on a single bond whose tension
  // has changed since would be swung across the bond, where the minimiser pulls it along
  state.across.assign(ns, 0.0);
  mean = ns ? mean / (double) ns : 1.0;
  state.shift = SHIFT * mean;
  state.factor.factorise(active, state.shift);
  state.factorisations++;
  state.excess_steps = 0.0;
}

/* ----------------------------------------------------------------------
   Newton steps with the factor until no free force component exceeds ftol:
   the springs that carry force join or leave the factor first (rank-one
   changes).  The factor is made anew at the current directions when the
   steps beyond the first of each equilibrium since it was made have cost as
   much as a factorisation (a rent-or-buy rule on operation counts, so the
   same on every run), or after NEWTON_REFRESH steps of one equilibrium.
   false if NEWTON_MAX steps did not get there
------------------------------------------------------------------------- */

bool LatticeDirectRelax::equilibrate(Network &net, LatticeDirectState &state,
                                     std::vector<double> &u, Outcome &out)
{
  std::vector<double> f;
  bool smoothed = false;
  for (int step = 0; step <= NEWTON_MAX; step++) {
    // the records and neighbour lists of the pass's force evaluation hold while no
    // particle has moved more than half the skin: beyond, the pass ends and the next
    // one's evaluation finds the new contacts (a fragment swinging on its last bonds)
    if (longest_move(net, u, 0.0, nullptr) > max_travel) return false;
    const double largest = forces(net, u, f);
    // the springs that start or stop carrying force, in ID order
    const size_t ns = net.springs.size();
    std::vector<std::vector<int>> flips((ns + LOOP_BLOCK - 1) / LOOP_BLOCK);
    for_blocks(pool, ns, LOOP_BLOCK, [&](size_t blk, size_t k0, size_t k1) {
      for (size_t k = k0; k < k1; k++) {
        const bool carries = net.intact[k] || !contact_open(net.e[k]);
        if (carries != (state.in_factor[k] != 0)) flips[blk].push_back((int) k);
      }
    });
    int changed = 0;
    for (const auto &blk : flips)
      for (const int k : blk) {
        const bool carries = state.in_factor[k] == 0;
        if (!carries) {
          changed += modify_across(state, state.ends[k].first, state.ends[k].second,
                                   state.across[k], &state.n[3 * (size_t) k], -1);
          state.across[k] = 0.0;
        }
        state.factor.modify(term(state, k), carries ? 1 : -1);
        state.in_factor[k] = carries ? 1 : 0;
        changed++;
      }
    out.changes += changed;
    if (largest <= ftol) return true;
    if (step == NEWTON_MAX) break;
    // what a Newton step left: first locally (the forces are then evaluated anew)
    if (step > 0 && !smoothed) {
      smoothed = true;
      smooth(net, u, f, (bigint) (SMOOTH_BUDGET * state.factor.ncols()) + 1);
      step--;
      continue;
    }
    // the steps beyond the first come from the springs' turn since the factor was made:
    // a new factor at the current directions once they have cost as much as one
    if (step > 0) state.excess_steps += 1.0;
    if (step == NEWTON_REFRESH || (step > 0 && state.excess_steps >= state.factor_in_solves)) {
      factorise(net, state, u);
      out.factorised++;
    }
    newton_step(net, state, u, f, out);
  }
  return false;
}

/* ----------------------------------------------------------------------
   u += K^-1 f, with no particle moving more than max_step.  A particle held
   by springs in one line (a particle left on one bond, a chain) has no
   stiffness across them but the shift: a force across them that comes only
   from their turn since the factor was made would move it by that force over
   the shift.  So a particle whose step exceeds max_step has its springs'
   directions brought up to date in the factor (an update and a downdate
   each), with the stiffness across them that their tension gives, T / r
   (I - n n^T) (tension_stiffness_across; kept until the next factorisation),
   and the step is solved again; after STEP_ROUNDS such rounds the
   factor is made anew at the current directions, and a step still too long
   is scaled down to max_step (the Newton steps go on from there).  The step
   is then shortened until the energy falls (step_length)
------------------------------------------------------------------------- */

void LatticeDirectRelax::newton_step(Network &net, LatticeDirectState &state,
                                     std::vector<double> &u, const std::vector<double> &f,
                                     Outcome &out)
{
  const int dim = net.dim;
  std::vector<double> step;
  for (int round = 0;; round++) {
    step = f;
    state.factor.solve(step.data());
    out.solves++;
    std::vector<int> far;
    const double longest = longest_move(net, step, max_step, &far);
    if (far.empty()) break;
    if (round == STEP_ROUNDS) {
      factorise(net, state, u);
      out.factorised++;
      continue;
    }
    if (round > STEP_ROUNDS) {
      const double scale = max_step / longest;
      for (double &v : step) v *= scale;
      break;
    }
    for (const int a : far)
      for (int e = net.node_start[a]; e < net.node_start[a + 1]; e++) {
        const int k = net.node_springs[e];
        const Spring &s = net.springs[k];
        double d[3];
        offset(s, dim, u, d);
        const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(r > 0.0)) continue;
        const LatticeSpring old = term(state, k);
        for (int c = 0; c < 3; c++) state.n[3 * (size_t) k + c] = d[c] / r;
        if (!state.in_factor[k]) continue;
        // the new direction and the stiffness across it that its tension gives now
        // first, then the old ones out: the matrix stays definite
        const double kx =
            tension_stiffness_across(s.kn, normal_stretch(r, s.touch), r, net.intact[k] != 0);
        state.factor.modify(term(state, k), 1);
        out.changes += 1 + modify_across(state, s.a, s.b, kx, &state.n[3 * (size_t) k], 1);
        state.factor.modify(old, -1);
        out.changes += 1 + modify_across(state, s.a, s.b, state.across[k], old.n, -1);
        state.across[k] = kx;
      }
  }
  bool at_trial = false;
  const double alpha = step_length(net, u, f, step, at_trial);
  if (alpha < 1.0)
    for (double &v : step) v *= alpha;
  for_blocks(pool, u.size(), LOOP_BLOCK, [&](size_t, size_t q0, size_t q1) {
    for (size_t q = q0; q < q1; q++)
      if (net.free[q]) u[q] += step[q];
  });
  // the line search's last trial is the new u to the bit (u + alpha step, the same
  // products): its stretches and forces are the springs' now
  if (at_trial) {
    net.e.swap(net.e_trial);
    net.f.swap(net.f_trial);
  }
  net.current = at_trial;
}

/* ----------------------------------------------------------------------
   the seed's loop on rank 0: equilibrium, break the intact spring with the
   largest ratio (ties: the lowest IDs), equilibrium, ...
------------------------------------------------------------------------- */

void LatticeDirectRelax::break_loop(Network &net, LatticeDirectState &state, std::vector<double> &u,
                                    bigint maxbreak, bool break_all, Outcome &out,
                                    const std::function<void(const Break &)> &on_break)
{
  u.assign(net.free.size(), 0.0);
  net.current = false;    // e holds the pair style's stretches, f nothing yet
  // the springs of each node, for the force gather and the local smoothing
  const size_t nnodes = net.tags.size();
  net.node_start.assign(nnodes + 1, 0);
  for (const Spring &s : net.springs) {
    net.node_start[s.a + 1]++;
    net.node_start[s.b + 1]++;
  }
  for (size_t a = 0; a < nnodes; a++) net.node_start[a + 1] += net.node_start[a];
  net.node_springs.assign(net.node_start[nnodes], 0);
  net.node_owns.assign(net.node_start[nnodes], 0);
  std::vector<int> fill(net.node_start.begin(), net.node_start.end() - 1);
  for (size_t k = 0; k < net.springs.size(); k++) {
    net.node_owns[fill[net.springs[k].a]] = 1;
    net.node_springs[fill[net.springs[k].a]++] = (int) k;
    net.node_springs[fill[net.springs[k].b]++] = (int) k;
  }
  prepare_factor(net, state, u, out);
  if (!equilibrate(net, state, u, out)) {
    out.relinearise = true;
    return;
  }
  while (maxbreak < 0 || (bigint) out.breaks.size() < maxbreak) {
    // the springs are in ID order: the first of the largest ratio has the lowest IDs
    struct Worst {
      int k = -1;
      double r = 0.0;
      BreakMode mode = BreakMode::None;
    };
    const size_t ns = net.springs.size();
    std::vector<Worst> block_worst((ns + LOOP_BLOCK - 1) / LOOP_BLOCK);
    for_blocks(pool, ns, LOOP_BLOCK, [&](size_t blk, size_t k0, size_t k1) {
      Worst w;
      for (size_t k = k0; k < k1; k++) {
        if (!net.intact[k]) continue;
        BreakMode m;
        const double r = ratio(net.springs[k], net.e[k], m);
        if (r > w.r) w = {(int) k, r, m};
      }
      block_worst[blk] = w;
    });
    int worst = -1;
    double best = 0.0;
    BreakMode best_mode = BreakMode::None;
    for (const Worst &w : block_worst)
      if (w.r > best) {
        best = w.r;
        worst = w.k;
        best_mode = w.mode;
      }
    if (worst < 0 || !(best > 1.0)) break;
    auto take = [&](int k, BreakMode m, double r) {
      net.intact[k] = 0;
      // a broken spring only pushes: its force at u changes
      if (net.current) update_spring(net, k, u);
      out.breaks.push_back({net.keys[k].first, net.keys[k].second, m, r});
      if (on_break) on_break(out.breaks.back());
    };
    if (break_all) {
      for (size_t k = 0; k < net.springs.size(); k++) {
        if (!net.intact[k]) continue;
        BreakMode m;
        const double r = ratio(net.springs[k], net.e[k], m);
        if (r > 1.0) take((int) k, m, r);
      }
    } else {
      take(worst, best_mode, best);
    }
    if (!equilibrate(net, state, u, out)) {
      out.relinearise = true;
      return;
    }
  }
}

/* ----------------------------------------------------------------------
   one pass: gather, solve and break on rank 0, then move and break everywhere
------------------------------------------------------------------------- */

LatticeDirectRelax::Outcome LatticeDirectRelax::pass(bigint maxbreak, bool break_all,
                                                     const std::function<void(const Break &)> &on_break)
{
  Outcome out;
  // the radii are the pair style's of the force evaluation before the pass
  max_step = STEP_FRACTION * pair->smallest_radius();
  max_travel = MAX(max_step, 0.5 * neighbor->skin);
  if (!(max_step > 0.0))
    error->all(FLERR, "lattice/quasistatic relax direct needs particles of positive radius (the "
               "smallest is {}): a Newton step may move a particle a twentieth of it",
               pair->smallest_radius());
  Network net;
  gather(net);
  const int dim = domain->dimension;
  std::vector<double> u;
  std::string failure;
  if (comm->me == 0) {
    auto &state = pair->direct_state();
    if (!state) state = std::make_shared<LatticeDirectState>();
    try {
      state->factor.set_threads(threads);
      pool = state->factor.pool();
      break_loop(net, *state, u, maxbreak, break_all, out, on_break);
    } catch (std::exception &e) {
      failure = e.what();
      state.reset();
    }
  }
  int failed = failure.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, world);
  if (failed)
    error->one(FLERR, "lattice/quasistatic relax direct: the sparse factor failed: {}", failure);

  // the displacements, in ID order, and the breaks
  bigint nnodes = (bigint) net.tags.size();
  MPI_Bcast(&nnodes, 1, MPI_LMP_BIGINT, 0, world);
  std::vector<tagint> tags = net.tags;
  tags.resize(nnodes);
  u.resize((size_t) nnodes * dim);
  MPI_Bcast(tags.data(), (int) nnodes, MPI_LMP_TAGINT, 0, world);
  MPI_Bcast(u.data(), (int) (nnodes * dim), MPI_DOUBLE, 0, world);
  bigint nbreaks = (bigint) out.breaks.size();
  MPI_Bcast(&nbreaks, 1, MPI_LMP_BIGINT, 0, world);
  std::vector<tagint> ids(2 * nbreaks);
  std::vector<double> info(2 * nbreaks);
  for (bigint b = 0; comm->me == 0 && b < nbreaks; b++) {
    ids[2 * b] = out.breaks[b].owner;
    ids[2 * b + 1] = out.breaks[b].partner;
    info[2 * b] = (double) out.breaks[b].mode;
    info[2 * b + 1] = out.breaks[b].ratio;
  }
  MPI_Bcast(ids.data(), (int) (2 * nbreaks), MPI_LMP_TAGINT, 0, world);
  MPI_Bcast(info.data(), (int) (2 * nbreaks), MPI_DOUBLE, 0, world);
  bigint counts[3] = {out.solves, out.changes, out.factorised};
  MPI_Bcast(counts, 3, MPI_LMP_BIGINT, 0, world);
  out.solves = counts[0];
  out.changes = counts[1];
  out.factorised = counts[2];
  out.breaks.resize(nbreaks);
  for (bigint b = 0; b < nbreaks; b++)
    out.breaks[b] = {ids[2 * b], ids[2 * b + 1], static_cast<BreakMode>((int) info[2 * b]),
                     info[2 * b + 1]};

  // move the local atoms
  double **x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    const auto it = std::lower_bound(tags.begin(), tags.end(), atom->tag[i]);
    if (it == tags.end() || *it != atom->tag[i]) continue;
    const size_t n = it - tags.begin();
    for (int c = 0; c < dim; c++) x[i][c] += u[n * dim + c];
  }

  // break the records on their owners
  FixLatticeBondStore *store = pair->store();
  for (const Break &b : out.breaks) {
    const int i = atom->map(b.owner);
    if (i < 0 || i >= atom->nlocal) continue;
    const tagint *pt = store->partners(i);
    const LatticeBondState *st = store->states(i);
    for (int s = 0; s < store->record_count(i); s++)
      if (pt[s] == b.partner && st[s] == LB_INTACT) pair->break_record(i, s, b.mode);
  }
  return out;
}
