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
// a kept factor is made anew when a spring's direction has turned by more
// than this (radians) since it was made: the linear model's error in a
// ratio change is about this fraction of the change
static constexpr double MAX_TURN = 1.0e-4;
// more changed springs than this fraction of all makes a new factor cheaper
// than one update each
static constexpr double REFACTOR_FRACTION = 0.02;
// rounds of contacts closing and opening after one solve before giving up
static constexpr int MAX_CONTACT_ROUNDS = 100;

// values sent per atom (tag apart): x, f (dim each), held bits
// values per record: the owner-to-partner vector (3), r, touch, kn, xb, fs0, mu_p, intact
static constexpr int RECORD_VALUES = 11;

LatticeDirectRelax::LatticeDirectRelax(LAMMPS *lmp, PairLatticeBond *pair_in) :
    Pointers(lmp), pair(pair_in)
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
                              int nprocs, std::vector<int> *counts_out = nullptr)
{
  int count = (int) mine.size();
  std::vector<int> counts(nprocs, 0), offsets(nprocs, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  for (int p = 1; p < nprocs; p++) offsets[p] = offsets[p - 1] + counts[p - 1];
  std::vector<T> all(offsets[nprocs - 1] + counts[nprocs - 1]);
  MPI_Gatherv(mine.data(), count, type, all.data(), counts.data(), offsets.data(), type, 0, world);
  if (counts_out) *counts_out = counts;
  return all;
}
}    // namespace

void LatticeDirectRelax::gather(Network &net)
{
  const int dim = domain->dimension;
  const int nlocal = atom->nlocal, nprocs = comm->nprocs;
  const tagint *tag = atom->tag;
  double **x = atom->x, **f = atom->f;

  std::unordered_map<tagint, int> held;
  for (size_t e = 0; e + 1 < held_ids.size(); e += 2) held[held_ids[e]] |= (int) held_ids[e + 1];

  std::vector<tagint> atom_tags(nlocal);
  std::vector<double> atom_values;
  atom_values.reserve((size_t) nlocal * (2 * dim + 1));
  for (int i = 0; i < nlocal; i++) {
    atom_tags[i] = tag[i];
    for (int c = 0; c < dim; c++) atom_values.push_back(x[i][c]);
    for (int c = 0; c < dim; c++) atom_values.push_back(f[i][c]);
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
                                       p.xb, p.fs0, p.mu_p, st[s] == LB_INTACT ? 1.0 : 0.0, 0.0};
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
  net.force.assign(natoms * dim, 0.0);
  net.free.assign(natoms * dim, 1);
  std::unordered_map<tagint, int> node;
  node.reserve(natoms);
  const size_t per_atom = 2 * dim + 1;
  for (size_t n = 0; n < natoms; n++) {
    const size_t g = order[n];
    net.tags[n] = all_tags[g];
    node[all_tags[g]] = (int) n;
    const double *v = &all_values[g * per_atom];
    const int bits = (int) v[2 * dim];
    for (int c = 0; c < dim; c++) {
      net.coords[n * dim + c] = v[c];
      const bool fixed = bits & (1 << c);
      net.free[n * dim + c] = fixed ? 0 : 1;
      net.force[n * dim + c] = fixed ? 0.0 : v[dim + c];
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
  for (size_t k = 0; k < nrec; k++) {
    const size_t g = rorder[k];
    const tagint owner = all_record_tags[2 * g], partner = all_record_tags[2 * g + 1];
    const double *v = &all_record_values[g * RECORD_VALUES];
    Spring &s = net.springs[k];
    s.a = node.at(owner);
    s.b = node.at(partner);
    const double r = v[3];
    for (int c = 0; c < 3; c++) s.n[c] = (r > 0.0) ? v[c] / r : 0.0;
    s.e0 = normal_stretch(r, v[4]);
    s.kn = v[5];
    s.xb = v[6];
    s.fs0 = v[7];
    s.mu_p = v[8];
    s.intact = v[9] != 0.0;
    s.active = s.intact || !contact_open(s.e0);
    s.e = s.e0;
    net.keys[k] = {owner, partner};
  }
}

/* ----------------------------------------------------------------------
   a spring as a term of the matrix, and its ratio to the threshold
------------------------------------------------------------------------- */

LatticeSpring LatticeDirectRelax::term(const Spring &s) const
{
  LatticeSpring t;
  t.a = s.a;
  t.b = s.b;
  t.k = s.kn;
  for (int c = 0; c < 3; c++) t.n[c] = s.n[c];
  return t;
}

// PairLatticeBond::bond_load with no shear spring (fs = 0), at the stretch e
double LatticeDirectRelax::ratio(const Spring &s, BreakMode &mode) const
{
  const double tension = tensile_ratio(s.e, s.xb);
  const double shear = shear_ratio(0.0, s.mu_p, normal_force(s.kn, s.e), s.fs0);
  mode = (tension >= shear) ? BreakMode::Tension : BreakMode::Shear;
  return MAX(tension, shear);
}

void LatticeDirectRelax::stretches(Network &net, const std::vector<double> &u) const
{
  const int dim = net.dim;
  for (Spring &s : net.springs) {
    double e = s.e0;
    for (int c = 0; c < dim; c++) e += s.n[c] * (u[(size_t) s.b * dim + c] - u[(size_t) s.a * dim + c]);
    s.e = e;
  }
}

/* ----------------------------------------------------------------------
   the factor of the active springs: the kept one, brought up to date by
   rank-one changes, if it is of the same atoms, records and stiffness and
   no spring has turned by more than MAX_TURN; else a new one
------------------------------------------------------------------------- */

bool LatticeDirectRelax::prepare_factor(Network &net, LatticeDirectState &state, bigint &solves)
{
  (void) solves;
  const size_t ns = net.springs.size();
  bool same = state.dim == net.dim && state.tags == net.tags && state.keys == net.keys &&
      state.free == net.free && state.kn.size() == ns;
  std::vector<int> changed;
  if (same) {
    for (size_t k = 0; k < ns && same; k++) {
      const Spring &s = net.springs[k];
      if (state.kn[k] != s.kn) same = false;
      double turn = 0.0;
      for (int c = 0; c < 3; c++) turn += (s.n[c] - state.n[3 * k + c]) * (s.n[c] - state.n[3 * k + c]);
      if (turn > MAX_TURN * MAX_TURN) same = false;
      if ((state.in_factor[k] != 0) != s.active) changed.push_back((int) k);
    }
    if (changed.size() > REFACTOR_FRACTION * (double) ns) same = false;
  }
  if (same) {
    // the linear model of the pass is the factor's: its directions, so that each solve is
    // exact for the model; the model differs from the tangent at the pass's start by less
    // than MAX_TURN of a displacement, and the next pass starts from the pair style's forces
    for (size_t k = 0; k < ns; k++)
      for (int c = 0; c < 3; c++) net.springs[k].n[c] = state.n[3 * k + c];
    for (const int k : changed) {
      const Spring &s = net.springs[k];
      state.factor.modify(term(s), s.active ? 1 : -1);
      state.in_factor[k] = s.active ? 1 : 0;
    }
    return false;
  }

  state.dim = net.dim;
  state.tags = net.tags;
  state.keys = net.keys;
  state.free = net.free;
  state.kn.resize(ns);
  state.n.resize(3 * ns);
  state.in_factor.resize(ns);
  std::vector<std::pair<int, int>> pairs(ns);
  std::vector<LatticeSpring> active;
  double mean = 0.0;
  for (size_t k = 0; k < ns; k++) {
    const Spring &s = net.springs[k];
    pairs[k] = {s.a, s.b};
    state.kn[k] = s.kn;
    for (int c = 0; c < 3; c++) state.n[3 * k + c] = s.n[c];
    state.in_factor[k] = s.active ? 1 : 0;
    if (s.active) active.push_back(term(s));
    mean += s.kn;
  }
  mean = ns ? mean / (double) ns : 1.0;
  state.shift = SHIFT * mean;
  state.factor.analyse(net.dim, (int) net.tags.size(), net.coords.data(), net.free, pairs);
  state.factor.factorise(active, state.shift);
  state.factorisations++;
  return true;
}

/* ----------------------------------------------------------------------
   u += K^-1 (the force the changed springs now add): a spring that left the
   factor no longer pulls (+Kn e g), one that joined pushes (-Kn e g)
------------------------------------------------------------------------- */

void LatticeDirectRelax::solve_released(Network &net, LatticeDirectState &state,
                                        std::vector<double> &u, const std::vector<int> &changed,
                                        bigint &solves)
{
  const int dim = net.dim;
  std::vector<double> rhs(u.size(), 0.0);
  for (const int k : changed) {
    const Spring &s = net.springs[k];
    const double sign = s.active ? -1.0 : 1.0;
    const double f = sign * normal_force(s.kn, s.e);
    for (int c = 0; c < dim; c++) {
      rhs[(size_t) s.a * dim + c] -= f * s.n[c];
      rhs[(size_t) s.b * dim + c] += f * s.n[c];
    }
  }
  for (size_t d = 0; d < rhs.size(); d++)
    if (!net.free[d]) rhs[d] = 0.0;
  state.factor.solve(rhs.data());
  solves++;
  for (size_t d = 0; d < rhs.size(); d++)
    if (net.free[d]) u[d] += rhs[d];
  stretches(net, u);
}

bool LatticeDirectRelax::settle_contacts(Network &net, LatticeDirectState &state,
                                         std::vector<double> &u, bigint &solves)
{
  bool any = false;
  for (int round = 0; round < MAX_CONTACT_ROUNDS; round++) {
    std::vector<int> changed;
    for (size_t k = 0; k < net.springs.size(); k++) {
      Spring &s = net.springs[k];
      if (s.intact) continue;
      const bool closed = !contact_open(s.e);
      if (closed == s.active) continue;
      s.active = closed;
      state.factor.modify(term(s), closed ? 1 : -1);
      state.in_factor[k] = closed ? 1 : 0;
      changed.push_back((int) k);
    }
    if (changed.empty()) return any;
    any = true;
    solve_released(net, state, u, changed, solves);
  }
  error->warning(FLERR, "lattice/quasistatic relax direct: contacts still closing and opening after "
                 "{} solves; the next pass goes on from the pair style's forces", MAX_CONTACT_ROUNDS);
  return any;
}

/* ----------------------------------------------------------------------
   the seed's loop in the linear model (rank 0)
------------------------------------------------------------------------- */

void LatticeDirectRelax::break_loop(Network &net, LatticeDirectState &state, std::vector<double> &u,
                                    bigint maxbreak, bool break_all, Outcome &out)
{
  u = net.force;
  state.factor.solve(u.data());
  out.solves++;
  for (size_t d = 0; d < u.size(); d++)
    if (!net.free[d]) u[d] = 0.0;
  stretches(net, u);
  settle_contacts(net, state, u, out.solves);

  while (maxbreak < 0 || (bigint) out.breaks.size() < maxbreak) {
    // the intact spring with the largest ratio; ties: the lowest IDs (springs are in ID order)
    int worst = -1;
    double best = 0.0;
    BreakMode best_mode = BreakMode::None;
    for (size_t k = 0; k < net.springs.size(); k++) {
      const Spring &s = net.springs[k];
      if (!s.intact) continue;
      BreakMode m;
      const double r = ratio(s, m);
      if (r > best) {
        best = r;
        worst = (int) k;
        best_mode = m;
      }
    }
    if (worst < 0 || !(best > 1.0)) break;
    std::vector<int> changed;
    auto take = [&](int k, BreakMode m, double r) {
      Spring &s = net.springs[k];
      s.intact = false;
      out.breaks.push_back({net.keys[k].first, net.keys[k].second, m, r});
      if (s.active && contact_open(s.e)) {
        s.active = false;
        state.factor.modify(term(s), -1);
        state.in_factor[k] = 0;
        changed.push_back(k);
      }
    };
    if (break_all) {
      for (size_t k = 0; k < net.springs.size(); k++) {
        if (!net.springs[k].intact) continue;
        BreakMode m;
        const double r = ratio(net.springs[k], m);
        if (r > 1.0) take((int) k, m, r);
      }
    } else {
      take(worst, best_mode, best);
    }
    if (!changed.empty()) solve_released(net, state, u, changed, out.solves);
    settle_contacts(net, state, u, out.solves);
  }
}

/* ----------------------------------------------------------------------
   one pass: gather, solve and break on rank 0, then move and break everywhere
------------------------------------------------------------------------- */

LatticeDirectRelax::Outcome LatticeDirectRelax::pass(bigint maxbreak, bool break_all)
{
  Outcome out;
  Network net;
  gather(net);
  const int dim = domain->dimension;
  std::vector<double> u;
  std::string failure;
  if (comm->me == 0) {
    auto &state = pair->direct_state();
    if (!state) state = std::make_shared<LatticeDirectState>();
    try {
      out.factorised = prepare_factor(net, *state, out.solves);
      break_loop(net, *state, u, maxbreak, break_all, out);
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
  MPI_Bcast(&out.solves, 1, MPI_LMP_BIGINT, 0, world);
  int factorised = out.factorised ? 1 : 0;
  MPI_Bcast(&factorised, 1, MPI_INT, 0, world);
  out.factorised = factorised != 0;
  out.breaks.resize(nbreaks);
  for (bigint b = 0; b < nbreaks; b++)
    out.breaks[b] = {ids[2 * b], ids[2 * b + 1], static_cast<BreakMode>((int) info[2 * b]),
                     info[2 * b + 1]};

  // move the local atoms
  double **x = atom->x;
  double largest = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    const auto it = std::lower_bound(tags.begin(), tags.end(), atom->tag[i]);
    if (it == tags.end() || *it != atom->tag[i]) continue;
    const size_t n = it - tags.begin();
    for (int c = 0; c < dim; c++) {
      x[i][c] += u[n * dim + c];
      largest = MAX(largest, std::fabs(u[n * dim + c]));
    }
  }
  MPI_Allreduce(&largest, &out.largest_move, 1, MPI_DOUBLE, MPI_MAX, world);

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
