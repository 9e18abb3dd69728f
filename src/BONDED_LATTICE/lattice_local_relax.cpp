/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   LatticeLocalRelax: multicolour over-relaxation of a central-spring
   network on a work queue (lattice_local_relax.h).  The springs are the
   records of pair_style lattice/bond whose owner is local and whose
   partner is present; their force is the force loop's for Ks = 0
   (lattice_bond_physics.h).  The forces on a local particle from springs
   owned on other ranks arrive by reverse communication; the particles'
   displacements go to their ghosts by forward communication.
------------------------------------------------------------------------- */

#include "lattice_local_relax.h"
#include "lattice_relax_model.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "modify.h"
#include "neigh_list.h"
#include "pair_lattice_bond.h"
#include "lattice_bond_geometry.h"
#include "lattice_bond_physics.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;
using namespace LAMMPS_NS::LatticeBondPhysics;

// a particle may move at most this fraction of the smallest radius between
// two force evaluations (the pair style's step limit is a tenth of it)
static constexpr double BUDGET_FRACTION = 0.05;

namespace {
// the colouring's priority of a particle: a hash of its ID (splitmix64)
uint64_t priority(tagint tag)
{
  uint64_t z = (uint64_t) tag + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

bool precedes(tagint a, tagint b)    // a is coloured before b
{
  const uint64_t pa = priority(a), pb = priority(b);
  return pa > pb || (pa == pb && a < b);
}
}    // namespace

/* ---------------------------------------------------------------------- */

LatticeLocalRelax::LatticeLocalRelax(LAMMPS *lmp, PairLatticeBond *pair_in, double ftol_in,
                                     double omega_in) :
    Pointers(lmp), pair(pair_in), ftol(ftol_in), omega(omega_in), budget(0.0), ncolours(0),
    phase_stamp(0), leaves(1), max_move(0.0), comm_mode(Comm::DISP), stiff_part(0)
{
}

/* ----------------------------------------------------------------------
   what the method cannot treat, and the components the fixes hold
   (lattice_relax_model.h)
------------------------------------------------------------------------- */

void LatticeLocalRelax::check_model()
{
  LatticeRelaxModel::check(lmp, pair, "relax local");
}

void LatticeLocalRelax::probe_fixes()
{
  held_ids = LatticeRelaxModel::held_components(lmp, "relax local");
}

/* ---------------------------------------------------------------------- */

void LatticeLocalRelax::set_up()
{
  const int nlocal = atom->nlocal;
  held.assign(nlocal, domain->dimension == 2 ? 4 : 0);
  for (size_t e = 0; e + 1 < held_ids.size(); e += 2) {
    const int i = atom->map(held_ids[e]);
    if (i >= 0 && i < nlocal) held[i] |= (unsigned char) held_ids[e + 1];
  }
  budget = BUDGET_FRACTION * pair->smallest_radius();
  if (!(budget > 0.0))
    error->all(FLERR, "lattice/quasistatic relax local needs particles of positive radius (the "
               "smallest is {}): a particle may move a twentieth of it between force "
               "evaluations", pair->smallest_radius());
  max_move = 0.0;
  build_springs();
  build_colours();
  queue.assign(ncolours, std::vector<int>());
  queued.assign(atom->nlocal, 0);
  for (int a = 0; a < atom->nlocal; a++)
    if (free_force_above(a)) enqueue(a);
}

/* ----------------------------------------------------------------------
   the springs (local owners, partner present), their adjacency, the forces
   on the local particles and their stiffness blocks D
------------------------------------------------------------------------- */

void LatticeLocalRelax::build_springs()
{
  FixLatticeBondStore *store = pair->store();
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  colour.clear();
  const int *pidx = pair->partner_index();
  const int stride = pair->partner_index_stride();
  const auto radius = pair->radii();
  springs.clear();
  for (int i = 0; i < nlocal && pidx; i++) {
    const LatticeBondState *st = store->states(i);
    for (int s = 0; s < store->record_count(i); s++) {
      const int j = pidx[(bigint) i * stride + s];
      if (j < 0) continue;    // a broken bond whose partner is far away
      Spring sp;
      sp.i = i;
      sp.j = j;
      sp.slot = s;
      const auto params = pair->bond_params(i, j);
      sp.kn = params.kn;
      sp.xb = params.xb;
      sp.fs0 = params.fs0;
      sp.mu_p = params.mu_p;
      sp.touch = radius.touch(i, j);
      sp.intact = (st[s] == LB_INTACT);
      sp.f[0] = sp.f[1] = sp.f[2] = 0.0;
      springs.push_back(sp);
    }
  }
  const int ns = (int) springs.size();
  adj_start.assign(nall + 1, 0);
  for (const Spring &s : springs) {
    adj_start[s.i + 1]++;
    adj_start[s.j + 1]++;
  }
  for (int a = 0; a < nall; a++) adj_start[a + 1] += adj_start[a];
  adj.assign(adj_start[nall], 0);
  std::vector<int> fill(adj_start.begin(), adj_start.end() - 1);
  for (int k = 0; k < ns; k++) {
    adj[fill[springs[k].i]++] = k;
    adj[fill[springs[k].j]++] = k;
  }

  // positions at set_up and the displacements since
  disp.assign(3 * (size_t) nall, 0.0);
  stamp.assign(ns, 0);
  phase_stamp = 0;

  // forces: every spring on both ends, the ghosts' parts to their owners
  fnet.assign(3 * (size_t) nlocal, 0.0);
  ghost_force.assign(3 * (size_t) (nall - nlocal), 0.0);
  queued.assign(nlocal, 0);
  queue.assign(1, std::vector<int>());
  ratio.assign(ns, -1.0);
  for (int k = 0; k < ns; k++) {
    double f[3];
    BreakMode m;
    ratio[k] = spring_force(springs[k], f, m);
    for (int c = 0; c < 3; c++) springs[k].f[c] = f[c];
    const double minus[3] = {-f[0], -f[1], -f[2]};
    add_force(springs[k].i, f);
    add_force(springs[k].j, minus);
  }
  exchange_forces();
  queue.clear();

  // D = sum over every record (intact, broken or contact) of Kn n n^T, plus
  // for an intact bond in tension the stiffness its tension gives across it,
  // Kn Xn / r (I - n n^T): an upper bound of the particle's stiffness (a
  // compressed spring's term across is negative), so each move lowers the
  // energy.  Without the tension's part a particle on a kinked chain in
  // tension has almost no stiffness across it and was sent out of the box
  double **x = atom->x;
  stiff.assign(6 * (size_t) nlocal, 0.0);
  std::vector<double> ghost_stiff(6 * (size_t) (nall - nlocal), 0.0);
  for (const Spring &s : springs) {
    const PairSeparation d = pair_separation(x, s.i, s.j);
    const double n[3] = {d.dx, d.dy, d.dz};
    const double inv = 1.0 / d.rsq;
    const double b[6] = {n[0] * n[0], n[1] * n[1], n[2] * n[2], n[0] * n[1], n[0] * n[2], n[1] * n[2]};
    const double r = std::sqrt(d.rsq);
    const double xn = normal_stretch(r, s.touch);
    const double across = tension_stiffness_across(s.kn, xn, r, s.intact);
    const double g[6] = {1.0 - b[0] * inv, 1.0 - b[1] * inv, 1.0 - b[2] * inv, -b[3] * inv,
                         -b[4] * inv, -b[5] * inv};
    for (const int a : {s.i, s.j}) {
      double *out = (a < nlocal) ? &stiff[6 * (size_t) a] : &ghost_stiff[6 * (size_t) (a - nlocal)];
      for (int c = 0; c < 6; c++) out[c] += s.kn * b[c] * inv + across * g[c];
    }
  }
  comm_mode = Comm::STIFF;
  for (stiff_part = 0; stiff_part < 2; stiff_part++) {
    for (int g = 0; g < nall - nlocal; g++)
      for (int c = 0; c < 3; c++) ghost_force[3 * (size_t) g + c] = ghost_stiff[6 * (size_t) g + 3 * stiff_part + c];
    pair->carry_reverse(this, 3);
  }

  // the ratio tournament
  leaves = 1;
  while (leaves < ns) leaves *= 2;
  tree.assign(2 * (size_t) leaves, -1);
  for (int k = 0; k < ns; k++) tree[leaves + k] = k;
  dirty.clear();
  is_dirty.assign(ns, 0);
  for (int p = leaves - 1; p >= 1; p--)
    tree[p] = better(tree[2 * p], tree[2 * p + 1]) ? tree[2 * p] : tree[2 * p + 1];
}

/* ----------------------------------------------------------------------
   Jones-Plassmann colouring of the particles: in each round a particle
   whose priority beats every uncoloured neighbour's takes the smallest
   colour none of its neighbours has.  The neighbours are the pairs of the
   pair style's neighbour list and the springs; the result depends on the
   IDs and the positions only, not on the ranks
------------------------------------------------------------------------- */

void LatticeLocalRelax::build_colours()
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const tagint *tag = atom->tag;
  NeighList *list = pair->list;
  // symmetric adjacency of the local particles
  std::vector<int> start(nlocal + 1, 0), nb;
  auto visit = [&](auto &&add) {
    if (list)
      for (int ii = 0; ii < list->inum; ii++) {
        const int a = list->ilist[ii];
        if (a >= nlocal) continue;
        const int *jlist = list->firstneigh[a];
        for (int jj = 0; jj < list->numneigh[a]; jj++) add(a, jlist[jj] & NEIGHMASK);
      }
    for (const Spring &s : springs) add(s.i, s.j);
  };
  visit([&](int a, int b) {
    start[a + 1]++;
    if (b < nlocal) start[b + 1]++;
  });
  for (int a = 0; a < nlocal; a++) start[a + 1] += start[a];
  nb.assign(start[nlocal], 0);
  std::vector<int> fill(start.begin(), start.end() - 1);
  visit([&](int a, int b) {
    nb[fill[a]++] = b;
    if (b < nlocal) nb[fill[b]++] = a;
  });

  colour.assign(nall, -1);
  std::vector<std::pair<int, int>> chosen;
  std::vector<char> used;
  bigint left = 1;
  while (left > 0) {
    chosen.clear();
    bigint mine = 0;
    for (int a = 0; a < nlocal; a++) {
      if (colour[a] >= 0) continue;
      bool first = true;
      int top = -1;
      for (int e = start[a]; e < start[a + 1]; e++) {
        const int b = nb[e];
        if (colour[b] < 0 && tag[b] != tag[a] && precedes(tag[b], tag[a])) {
          first = false;
          break;
        }
        top = MAX(top, colour[b]);
      }
      if (!first) {
        mine++;
        continue;
      }
      used.assign(top + 2, 0);
      for (int e = start[a]; e < start[a + 1]; e++)
        if (colour[nb[e]] >= 0) used[colour[nb[e]]] = 1;
      int c = 0;
      while (used[c]) c++;
      chosen.emplace_back(a, c);
    }
    for (const auto &ac : chosen) colour[ac.first] = ac.second;
    comm_mode = Comm::COLOUR;
    pair->carry_forward(this);
    MPI_Allreduce(&mine, &left, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  }
  int top = 0;
  for (int a = 0; a < nlocal; a++) top = MAX(top, colour[a] + 1);
  MPI_Allreduce(&top, &ncolours, 1, MPI_INT, MPI_MAX, world);
}

/* ----------------------------------------------------------------------
   a spring's force on its owner at the current positions (the force loop's
   for Ks = 0: tension pulls the two together, a broken bond or contact only
   pushes)
------------------------------------------------------------------------- */

double LatticeLocalRelax::force_only(const Spring &s, double *f) const
{
  const PairSeparation d = pair_separation(atom->x, s.i, s.j);
  const double r = d.length();
  const double xn = normal_stretch(r, s.touch);
  if (!s.intact && contact_open(xn)) {
    f[0] = f[1] = f[2] = 0.0;
    return xn;
  }
  const double scale = -normal_force(s.kn, xn) / r;
  f[0] = scale * d.dx;
  f[1] = scale * d.dy;
  f[2] = scale * d.dz;
  return xn;
}

double LatticeLocalRelax::spring_force(const Spring &s, double *f, BreakMode &mode) const
{
  mode = BreakMode::None;
  const double xn = force_only(s, f);
  if (!s.intact) return -1.0;
  const double fn = normal_force(s.kn, xn);
  // PairLatticeBond::bond_load with no shear spring (fs = 0)
  const double tension = tensile_ratio(xn, s.xb);
  const double shear = shear_ratio(0.0, s.mu_p, fn, s.fs0);
  mode = (tension >= shear) ? BreakMode::Tension : BreakMode::Shear;
  return MAX(tension, shear);
}

void LatticeLocalRelax::recompute(int k)
{
  Spring &s = springs[k];
  double f[3];
  force_only(s, f);    // its ratio: when worst() brings the tournament up to date
  const double df[3] = {f[0] - s.f[0], f[1] - s.f[1], f[2] - s.f[2]};
  for (int c = 0; c < 3; c++) s.f[c] = f[c];
  const double minus[3] = {-df[0], -df[1], -df[2]};
  add_force(s.i, df);
  add_force(s.j, minus);
  if (!is_dirty[k]) {
    is_dirty[k] = 1;
    dirty.push_back(k);
  }
}

void LatticeLocalRelax::add_force(int a, const double *df)
{
  if (df[0] == 0.0 && df[1] == 0.0 && df[2] == 0.0) return;
  const int nlocal = atom->nlocal;
  double *out = (a < nlocal) ? &fnet[3 * (size_t) a] : &ghost_force[3 * (size_t) (a - nlocal)];
  for (int c = 0; c < 3; c++) out[c] += df[c];
  if (a < nlocal) enqueue(a);
}

void LatticeLocalRelax::enqueue(int a)
{
  if (queued[a] || queue.empty()) return;
  queued[a] = 1;
  queue[colour.empty() ? 0 : colour[a]].push_back(a);
}

bool LatticeLocalRelax::free_force_above(int a) const
{
  for (int c = 0; c < 3; c++)
    if (!(held[a] & (1 << c)) && std::fabs(fnet[3 * (size_t) a + c]) > ftol) return true;
  return false;
}

/* ----------------------------------------------------------------------
   over-relaxed Newton step of particle a on its free components:
   x += omega D_ff^-1 f_f
------------------------------------------------------------------------- */

void LatticeLocalRelax::move(int a)
{
  const double *d = &stiff[6 * (size_t) a];
  if (held[a] == 4) {    // the plane (2D, z held): the 2x2 block of x and y
    const double trace = d[0] + d[1];
    const double mxx = d[0] + 1.0e-12 * trace, myy = d[1] + 1.0e-12 * trace, mxy = d[3];
    const double det = mxx * myy - mxy * mxy;
    if (!(std::fabs(det) > 0.0)) return;
    const double fx = fnet[3 * (size_t) a], fy = fnet[3 * (size_t) a + 1];
    const double dx[3] = {omega * (myy * fx - mxy * fy) / det, omega * (mxx * fy - mxy * fx) / det,
                          0.0};
    displace(a, dx, 2);
    return;
  }
  double m[3][3] = {{d[0], d[3], d[4]}, {d[3], d[1], d[5]}, {d[4], d[5], d[2]}};
  double rhs[3];
  const double trace = d[0] + d[1] + d[2];
  for (int c = 0; c < 3; c++) {
    rhs[c] = fnet[3 * (size_t) a + c];
    if (held[a] & (1 << c)) {
      for (int e = 0; e < 3; e++) m[c][e] = m[e][c] = 0.0;
      m[c][c] = 1.0;
      rhs[c] = 0.0;
    } else {
      m[c][c] += 1.0e-12 * trace;    // a direction no spring resists carries no force
    }
  }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
      m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (!(std::fabs(det) > 0.0)) return;    // no spring at all: no force either
  double dx[3];
  for (int c = 0; c < 3; c++) {
    double t[3][3];
    std::memcpy(t, m, sizeof(t));
    for (int e = 0; e < 3; e++) t[e][c] = rhs[e];
    dx[c] = omega * (t[0][0] * (t[1][1] * t[2][2] - t[1][2] * t[2][1]) -
                     t[0][1] * (t[1][0] * t[2][2] - t[1][2] * t[2][0]) +
                     t[0][2] * (t[1][0] * t[2][1] - t[1][1] * t[2][0])) / det;
  }
  displace(a, dx, 3);
}

// particle a moves by dx (its first n components), by no more than the pass's
// budget: a longer move could pass into a contact the pass does not know of
// (its particles not touching when the pass began), and the next pass would
// push the particle back out as far
void LatticeLocalRelax::displace(int a, const double *dx_in, int n)
{
  double len = 0.0;
  for (int c = 0; c < n; c++) len += dx_in[c] * dx_in[c];
  len = std::sqrt(len);
  const double scale = (len > budget) ? budget / len : 1.0;
  double dx[3] = {0.0, 0.0, 0.0};
  for (int c = 0; c < n; c++) dx[c] = dx_in[c] * scale;
  double **x = atom->x;
  for (int c = 0; c < n; c++) {
    disp[3 * (size_t) a + c] += dx[c];
    x[a][c] += dx[c];
    max_move = MAX(max_move, std::fabs(disp[3 * (size_t) a + c]));
  }
  moved.push_back(a);
}

/* ---------------------------------------------------------------------- */

void LatticeLocalRelax::exchange_forces()
{
  comm_mode = Comm::FORCE;
  pair->carry_reverse(this, 3);
}

LatticeLocalRelax::Outcome LatticeLocalRelax::relax(bigint maxsweeps, bigint &sweeps, bigint &moves)
{
  // one rank and no ghosts (a box without periodic faces): nothing to send
  int mine = (atom->nghost > 0) ? 1 : 0;
  MPI_Allreduce(&mine, &communicate, 1, MPI_INT, MPI_MAX, world);
  if (comm->nprocs > 1) communicate = 1;
  if (communicate) exchange_forces();    // the springs broken since the last relax
  std::vector<int> work;
  bigint my_moves = 0;
  Outcome outcome = Outcome::SWEEPS;
  for (bigint sweep = 0;; sweep++) {
    bigint waiting = 0, all_waiting = 0;
    for (const auto &q : queue) waiting += (bigint) q.size();
    MPI_Allreduce(&waiting, &all_waiting, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    double far = 0.0;
    MPI_Allreduce(&max_move, &far, 1, MPI_DOUBLE, MPI_MAX, world);
    if (all_waiting == 0) {
      outcome = Outcome::RELAXED;
      break;
    }
    if (far > budget) {
      outcome = Outcome::MOVED_FAR;
      break;
    }
    if (sweep >= maxsweeps) break;
    sweeps++;
    for (int c = 0; c < ncolours; c++) {
      work.clear();
      work.swap(queue[c]);
      moved.clear();
      for (const int a : work) {
        queued[a] = 0;
        if (free_force_above(a)) move(a);
      }
      my_moves += (bigint) moved.size();
      comm_mode = Comm::DISP;
      if (communicate) pair->carry_forward(this);    // moved ghosts join `moved`
      phase_stamp++;
      for (const int a : moved)
        for (int e = adj_start[a]; e < adj_start[a + 1]; e++) {
          const int k = adj[e];
          if (stamp[k] == phase_stamp) continue;
          stamp[k] = phase_stamp;
          recompute(k);
        }
      if (communicate) exchange_forces();
    }
  }
  bigint all_moves = 0;
  MPI_Allreduce(&my_moves, &all_moves, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  moves += all_moves;
  return outcome;
}

/* ----------------------------------------------------------------------
   the ratio tournament: springs compared by ratio, then owner and partner IDs
------------------------------------------------------------------------- */

bool LatticeLocalRelax::better(int a, int b) const
{
  if (b < 0) return a >= 0;
  if (a < 0) return false;
  if (ratio[a] != ratio[b]) return ratio[a] > ratio[b];
  const tagint *tag = atom->tag;
  const tagint oa = tag[springs[a].i], ob = tag[springs[b].i];
  if (oa != ob) return oa < ob;
  return tag[springs[a].j] < tag[springs[b].j];
}

void LatticeLocalRelax::tree_update(int k)
{
  for (int p = (leaves + k) / 2; p >= 1; p /= 2)
    tree[p] = better(tree[2 * p], tree[2 * p + 1]) ? tree[2 * p] : tree[2 * p + 1];
}

double LatticeLocalRelax::worst(tagint &owner, tagint &partner, BreakMode &mode)
{
  for (const int k : dirty) {
    is_dirty[k] = 0;
    double f[3];
    BreakMode m;
    ratio[k] = spring_force(springs[k], f, m);    // at the positions of its last recompute
    tree_update(k);
  }
  dirty.clear();
  const int k = tree.empty() ? -1 : tree[1];
  double best = 0.0;
  owner = partner = MAXTAGINT;
  mode = BreakMode::None;
  if (k >= 0 && ratio[k] > 0.0) {
    double f[3];
    best = spring_force(springs[k], f, mode);
    owner = atom->tag[springs[k].i];
    partner = atom->tag[springs[k].j];
  }
  return best;
}

void LatticeLocalRelax::break_spring(tagint owner, tagint partner, BreakMode mode)
{
  const int i = atom->map(owner);
  if (i < 0 || i >= atom->nlocal) return;
  for (int e = adj_start[i]; e < adj_start[i + 1]; e++) {
    const int k = adj[e];
    if (springs[k].i != i || atom->tag[springs[k].j] != partner || !springs[k].intact) continue;
    pair->break_record(i, springs[k].slot, mode);
    springs[k].intact = false;
    recompute(k);
    return;
  }
}

bigint LatticeLocalRelax::break_beyond_threshold(int &tension, int &shear)
{
  int counts[2] = {0, 0}, all[2] = {0, 0};
  for (int k = 0; k < (int) springs.size(); k++) {
    if (!springs[k].intact) continue;
    double f[3];
    BreakMode mode;
    if (!(spring_force(springs[k], f, mode) > 1.0)) continue;
    pair->break_record(springs[k].i, springs[k].slot, mode);
    springs[k].intact = false;
    recompute(k);
    counts[mode == BreakMode::Tension ? 0 : 1]++;
  }
  MPI_Allreduce(counts, all, 2, MPI_INT, MPI_SUM, world);
  tension += all[0];
  shear += all[1];
  return (bigint) all[0] + all[1];
}

double LatticeLocalRelax::largest_force()
{
  double local = 0.0, global = 0.0;
  for (int a = 0; a < atom->nlocal; a++)
    for (int c = 0; c < 3; c++)
      if (!(held[a] & (1 << c))) local = MAX(local, std::fabs(fnet[3 * (size_t) a + c]));
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, world);
  return global;
}

/* ----------------------------------------------------------------------
   communication: displacements and colours to the ghosts, the ghosts'
   forces and stiffness blocks to their owners
------------------------------------------------------------------------- */

int LatticeLocalRelax::pack_forward(int n, const int *list, double *buf)
{
  if (comm_mode == Comm::COLOUR) {
    for (int i = 0; i < n; i++) buf[i] = colour[list[i]];
    return n;
  }
  for (int i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) buf[3 * i + c] = disp[3 * (size_t) list[i] + c];
  return 3 * n;
}

void LatticeLocalRelax::unpack_forward(int n, int first, const double *buf)
{
  if (comm_mode == Comm::COLOUR) {
    for (int i = 0; i < n; i++) colour[first + i] = (int) buf[i];
    return;
  }
  double **x = atom->x;
  for (int i = 0; i < n; i++) {
    const int g = first + i;
    bool changed = false;
    for (int c = 0; c < 3; c++) {
      const double now = buf[3 * i + c];
      if (now == disp[3 * (size_t) g + c]) continue;
      x[g][c] += now - disp[3 * (size_t) g + c];
      disp[3 * (size_t) g + c] = now;
      changed = true;
    }
    if (changed) moved.push_back(g);
  }
}

int LatticeLocalRelax::pack_reverse(int n, int first, double *buf)
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) {
      double &v = ghost_force[3 * (size_t) (first + i - nlocal) + c];
      buf[3 * i + c] = v;
      v = 0.0;
    }
  return 3 * n;
}

// the receiving atom is local, or a ghost that passes the values on in a later swap (the
// corners of a periodic or multi-rank box)
void LatticeLocalRelax::unpack_reverse(int n, const int *list, const double *buf)
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < n; i++) {
    const int a = list[i];
    if (comm_mode == Comm::STIFF) {
      double *out = (a < nlocal) ? &stiff[6 * (size_t) a + 3 * stiff_part]
                                 : &ghost_force[3 * (size_t) (a - nlocal)];
      for (int c = 0; c < 3; c++) out[c] += buf[3 * i + c];
      continue;
    }
    const double df[3] = {buf[3 * i], buf[3 * i + 1], buf[3 * i + 2]};
    add_force(a, df);    // a local atom: its force, and the queue; a ghost: to pass on
  }
}
