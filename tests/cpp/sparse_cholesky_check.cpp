// Checks of LatticeSparseCholesky (src/BONDED_LATTICE/lattice_sparse_cholesky.h)
// against a dense Cholesky of the explicitly assembled stiffness matrix.
// Standalone: g++ -std=c++17 -O2 -pthread -I src/BONDED_LATTICE this.cpp lattice_sparse_cholesky.cpp
// Prints "name value" lines (tests/unit/test_sparse_cholesky.py asserts them) and
// "message <text>" lines with the errors caught; exits 1 on an unexpected exception.

#include "lattice_sparse_cholesky.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using LAMMPS_NS::LatticeSparseCholesky;
using LAMMPS_NS::LatticeSpring;

namespace {

struct Net {
  int dim = 2, nnodes = 0;
  std::vector<double> coords;
  std::vector<unsigned char> free;
  std::vector<std::pair<int, int>> pairs;
  std::vector<LatticeSpring> springs;    // one per pair, same order
};

double uniform(std::mt19937_64 &rng)    // [0, 1), the same on every platform
{
  return (double) (rng() >> 11) * (1.0 / 9007199254740992.0);
}

LatticeSpring make_spring(const Net &net, int a, int b, double k)
{
  LatticeSpring s{a, b, k, {0.0, 0.0, 0.0}};
  double len = 0.0;
  for (int c = 0; c < net.dim; ++c) {
    s.n[c] = net.coords[net.dim * b + c] - net.coords[net.dim * a + c];
    len += s.n[c] * s.n[c];
  }
  len = std::sqrt(len);
  for (int c = 0; c < net.dim; ++c) s.n[c] /= len;
  return s;
}

// nx x ny triangular lattice, rows along x, odd rows shifted by 1/2 (scenes.box_lattice)
Net triangular(int nx, int ny)
{
  Net net;
  net.dim = 2;
  net.nnodes = nx * ny;
  const double row = std::sqrt(3.0) / 2.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      net.coords.push_back(i + 0.5 * (j % 2));
      net.coords.push_back(j * row);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int u = j * nx + i;
      if (i + 1 < nx) net.pairs.push_back({u, u + 1});
      if (j + 1 < ny) {
        const int lo = (j % 2) ? i : i - 1;    // the two neighbours in the row above
        for (int ii = lo; ii <= lo + 1; ++ii)
          if (ii >= 0 && ii < nx) net.pairs.push_back({u, (j + 1) * nx + ii});
      }
    }
  net.free.assign(2 * net.nnodes, 1);
  return net;
}

// nc^3 cubic cells of an fcc lattice (4 atoms each), nearest neighbours joined
Net fcc(int nc)
{
  Net net;
  net.dim = 3;
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (int z = 0; z < nc; ++z)
    for (int y = 0; y < nc; ++y)
      for (int x = 0; x < nc; ++x)
        for (const auto &b : basis) {
          net.coords.push_back(x + b[0]);
          net.coords.push_back(y + b[1]);
          net.coords.push_back(z + b[2]);
        }
  net.nnodes = (int) net.coords.size() / 3;
  for (int a = 0; a < net.nnodes; ++a)
    for (int b = a + 1; b < net.nnodes; ++b) {
      double d2 = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double d = net.coords[3 * a + c] - net.coords[3 * b + c];
        d2 += d * d;
      }
      if (std::fabs(d2 - 0.5) < 1e-9) net.pairs.push_back({a, b});
    }
  net.free.assign(3 * net.nnodes, 1);
  return net;
}

void random_springs(Net &net, std::mt19937_64 &rng)
{
  net.springs.clear();
  for (const auto &p : net.pairs)
    net.springs.push_back(make_spring(net, p.first, p.second, 0.5 + uniform(rng)));
}

// the free dofs in dof order, and their index (-1 held)
std::vector<int> free_index(const Net &net, int &nfree)
{
  std::vector<int> idx(net.free.size(), -1);
  nfree = 0;
  for (std::size_t d = 0; d < net.free.size(); ++d)
    if (net.free[d]) idx[d] = nfree++;
  return idx;
}

// the stiffness matrix on the free dofs (dof order), dense, row-major
std::vector<double> dense_K(const Net &net, const std::vector<LatticeSpring> &springs, double shift,
                            int &nfree)
{
  const std::vector<int> idx = free_index(net, nfree);
  std::vector<double> K((std::size_t) nfree * nfree, 0.0);
  for (const auto &s : springs) {
    int cols[6];
    double vals[6];
    int nv = 0;
    for (int c = 0; c < net.dim; ++c) {
      if (idx[net.dim * s.a + c] >= 0) {
        cols[nv] = idx[net.dim * s.a + c];
        vals[nv++] = -s.n[c];
      }
      if (idx[net.dim * s.b + c] >= 0) {
        cols[nv] = idx[net.dim * s.b + c];
        vals[nv++] = s.n[c];
      }
    }
    for (int a = 0; a < nv; ++a)
      for (int b = 0; b < nv; ++b) K[(std::size_t) cols[a] * nfree + cols[b]] += s.k * vals[a] * vals[b];
  }
  for (int i = 0; i < nfree; ++i) K[(std::size_t) i * nfree + i] += shift;
  return K;
}

// x := K^-1 x with a dense Cholesky (K row-major, n x n, overwritten)
void dense_solve(std::vector<double> K, int n, std::vector<double> &x)
{
  for (int j = 0; j < n; ++j) {
    double d = K[(std::size_t) j * n + j];
    for (int p = 0; p < j; ++p) d -= K[(std::size_t) j * n + p] * K[(std::size_t) j * n + p];
    if (!(d > 0.0)) throw std::runtime_error("dense reference: K not positive definite");
    d = std::sqrt(d);
    K[(std::size_t) j * n + j] = d;
    for (int i = j + 1; i < n; ++i) {
      double s = K[(std::size_t) i * n + j];
      for (int p = 0; p < j; ++p) s -= K[(std::size_t) i * n + p] * K[(std::size_t) j * n + p];
      K[(std::size_t) i * n + j] = s / d;
    }
  }
  for (int i = 0; i < n; ++i) {
    double s = x[i];
    for (int p = 0; p < i; ++p) s -= K[(std::size_t) i * n + p] * x[p];
    x[i] = s / K[(std::size_t) i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    double s = x[i];
    for (int p = i + 1; p < n; ++p) s -= K[(std::size_t) p * n + i] * x[p];
    x[i] = s / K[(std::size_t) i * n + i];
  }
}

double norm(const std::vector<double> &v)
{
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

// a random right-hand side on the free dofs (dim*nnodes entries; held entries 7.0, which
// solve() must leave as they are)
std::vector<double> random_rhs(const Net &net, std::mt19937_64 &rng)
{
  std::vector<double> b(net.free.size(), 7.0);
  for (std::size_t d = 0; d < b.size(); ++d)
    if (net.free[d]) b[d] = 2.0 * uniform(rng) - 1.0;
  return b;
}

std::vector<double> gather_free(const Net &net, const std::vector<double> &full)
{
  std::vector<double> v;
  for (std::size_t d = 0; d < full.size(); ++d)
    if (net.free[d]) v.push_back(full[d]);
  return v;
}

// max |x - y| / max |y| over the free dofs (optionally leaving out one node's dofs)
double rel_diff(const Net &net, const std::vector<double> &x, const std::vector<double> &y,
                int skip_node = -1)
{
  double num = 0.0, den = 0.0;
  for (std::size_t d = 0; d < x.size(); ++d) {
    if (!net.free[d] || (int) d / net.dim == skip_node) continue;
    num = std::max(num, std::fabs(x[d] - y[d]));
    den = std::max(den, std::fabs(y[d]));
  }
  return num / den;
}

// ||K x - b|| / ||b|| on the free dofs, K assembled densely
double residual(const Net &net, const std::vector<LatticeSpring> &springs, double shift,
                const std::vector<double> &x, const std::vector<double> &b)
{
  int n = 0;
  const std::vector<double> K = dense_K(net, springs, shift, n);
  const std::vector<double> xf = gather_free(net, x), bf = gather_free(net, b);
  std::vector<double> r(n);
  for (int i = 0; i < n; ++i) {
    double s = -bf[i];
    for (int j = 0; j < n; ++j) s += K[(std::size_t) i * n + j] * xf[j];
    r[i] = s;
  }
  return norm(r) / norm(bf);
}

// the sparse solution and the dense one of K x = b
void both_solves(const Net &net, LatticeSparseCholesky &chol, const std::vector<LatticeSpring> &springs,
                 double shift, const std::vector<double> &b, std::vector<double> &xs,
                 std::vector<double> &xd)
{
  xs = b;
  chol.solve(xs.data());
  int n = 0;
  const std::vector<double> K = dense_K(net, springs, shift, n);
  std::vector<double> v = gather_free(net, b);
  dense_solve(K, n, v);
  xd = b;
  int q = 0;
  for (std::size_t d = 0; d < b.size(); ++d)
    if (net.free[d]) xd[d] = v[q++];
}

bool held_untouched(const Net &net, const std::vector<double> &x)
{
  for (std::size_t d = 0; d < x.size(); ++d)
    if (!net.free[d] && x[d] != 7.0) return false;
  return true;
}

void report(const char *name, double value) { std::printf("%s %.6e\n", name, value); }

// the documented properties of the tree accessors; returns the number of violations
int tree_violations(const LatticeSparseCholesky &chol)
{
  int bad = 0;
  const int nt = chol.ntree();
  auto is_ancestor = [&](int anc, int t) {
    for (t = chol.parent(t); t >= 0; t = chol.parent(t))
      if (t == anc) return true;
    return false;
  };
  int next_col = 0;
  for (int t = 0; t < nt; ++t) {
    bad += chol.col_begin(t) != next_col;    // contiguous columns in post-order
    next_col = chol.col_end(t);
    bad += chol.parent(t) >= 0 && chol.parent(t) <= t;    // parents after their children
    for (int c = chol.col_begin(t); c < chol.col_end(t); ++c) {
      bad += chol.tree_of_col(c) != t;
      bad += chol.col_of_dof(chol.dof_of_col(c)) != c;
    }
    const int *R = chol.rows(t);
    for (int p = 0; p < chol.nrows(t); ++p) {    // R_t: sorted ancestor columns
      bad += p > 0 && R[p] <= R[p - 1];
      bad += !is_ancestor(chol.tree_of_col(R[p]), t);
    }
    for (int q = 0; q < chol.nchildren(t); ++q) bad += chol.parent(chol.child(t, q)) != t;
    const int fd = chol.first_descendant(t);    // the subtree is [fd, t]
    for (int u = 0; u < nt; ++u) bad += (u == t || is_ancestor(t, u)) != (u >= fd && u <= t);
    const double *L = chol.block(t);    // the strict upper triangle of the diagonal block: 0
    const int n = chol.col_end(t) - chol.col_begin(t), m = n + chol.nrows(t);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < j; ++i) bad += L[(std::size_t) j * m + i] != 0.0;
  }
  bad += next_col != chol.ncols();
  return bad;
}

// accuracy of analyse + factorise + solve against the dense reference
void check_solve(const char *tag, Net &net, int leaf, double shift, std::mt19937_64 &rng)
{
  LatticeSparseCholesky chol;
  chol.set_leaf_size(leaf);
  chol.analyse(net.dim, net.nnodes, net.coords.data(), net.free, net.pairs);
  chol.factorise(net.springs, shift);
  const std::vector<double> b = random_rhs(net, rng);
  std::vector<double> xs, xd;
  both_solves(net, chol, net.springs, shift, b, xs, xd);
  std::string p(tag);
  report((p + "_residual").c_str(), residual(net, net.springs, shift, xs, b));
  report((p + "_vs_dense").c_str(), rel_diff(net, xs, xd));
  report((p + "_held_untouched").c_str(), held_untouched(net, xs) ? 1.0 : 0.0);
  report((p + "_ntree").c_str(), chol.ntree());
  report((p + "_depth").c_str(), chol.depth());
  report((p + "_tree_violations").c_str(), tree_violations(chol));

  // block steps: the forward sweep, then the back steps of one node's path only, give that
  // node's entries of the full solve, to the bit
  std::vector<double> w(chol.ncols()), scratch(chol.max_rows());
  for (int c = 0; c < chol.ncols(); ++c) w[c] = b[chol.dof_of_col(c)];
  for (int t = 0; t < chol.ntree(); ++t) chol.forward_block(t, w.data(), scratch.data());
  int mismatches = 0;
  const int u = chol.dof_of_col(0) / net.dim;    // a node in the first leaf: the longest path
  const std::vector<int> path = chol.path(u, u);
  for (auto it = path.rbegin(); it != path.rend(); ++it) chol.back_block(*it, w.data(), scratch.data());
  for (int c = 0; c < net.dim; ++c) {
    const int col = chol.col_of_dof(net.dim * u + c);
    if (col >= 0) mismatches += w[col] != xs[net.dim * u + c];
  }
  report((p + "_path_back_steps").c_str(), path.size());
  report((p + "_path_back_mismatches").c_str(), mismatches);
  int roots = 0;
  for (int t = 0; t < chol.ntree(); ++t) roots += chol.parent(t) < 0;
  report((p + "_roots").c_str(), roots);
}

// 50 downdates and 10 updates against a fresh factorisation of the changed spring set
void check_modify(const char *tag, Net &net, int leaf, double shift, std::mt19937_64 &rng)
{
  LatticeSparseCholesky chol, fresh;
  chol.set_leaf_size(leaf);
  fresh.set_leaf_size(leaf);
  chol.analyse(net.dim, net.nnodes, net.coords.data(), net.free, net.pairs);
  fresh.analyse(net.dim, net.nnodes, net.coords.data(), net.free, net.pairs);
  chol.factorise(net.springs, shift);
  std::vector<LatticeSpring> now = net.springs, removed;
  for (int q = 0; q < 50; ++q) {
    const std::size_t i = (std::size_t) (uniform(rng) * now.size());
    chol.modify(now[i], -1);
    removed.push_back(now[i]);
    now.erase(now.begin() + i);
  }
  for (int q = 0; q < 10; ++q) {    // re-added with a new stiffness
    LatticeSpring s = removed[(std::size_t) (uniform(rng) * removed.size())];
    s.k = 0.5 + uniform(rng);
    chol.modify(s, +1);
    now.push_back(s);
  }
  fresh.factorise(now, shift);
  const std::vector<double> b = random_rhs(net, rng);
  std::vector<double> xm = b, xf = b, xd;
  chol.solve(xm.data());
  fresh.solve(xf.data());
  both_solves(net, fresh, now, shift, b, xf, xd);
  std::string p(tag);
  report((p + "_modified_vs_fresh").c_str(), rel_diff(net, xm, xf));
  report((p + "_modified_vs_dense").c_str(), rel_diff(net, xm, xd));
  report((p + "_modified_residual").c_str(), residual(net, now, shift, xm, b));
}

// a node cut loose by downdates of all its springs, shift 1e-10
void check_loose(Net &net, int leaf, std::mt19937_64 &rng)
{
  const double shift = 1e-10;
  const int u = (net.nnodes / 2) + 3;    // an interior node
  LatticeSparseCholesky chol;
  chol.set_leaf_size(leaf);
  chol.analyse(net.dim, net.nnodes, net.coords.data(), net.free, net.pairs);
  chol.factorise(net.springs, shift);
  std::vector<LatticeSpring> rest;
  int cut = 0;
  for (const auto &s : net.springs) {
    if (s.a == u || s.b == u) {
      chol.modify(s, -1);
      ++cut;
    } else {
      rest.push_back(s);
    }
  }
  // the reference: the network without node u (its dofs held)
  Net without = net;
  for (int c = 0; c < net.dim; ++c) without.free[net.dim * u + c] = 0;
  for (int zero_on_u = 1; zero_on_u >= 0; --zero_on_u) {
    std::vector<double> b = random_rhs(net, rng);
    if (zero_on_u)
      for (int c = 0; c < net.dim; ++c) b[net.dim * u + c] = 0.0;
    std::vector<double> x = b;
    chol.solve(x.data());
    bool finite = true;
    for (double v : x) finite = finite && std::isfinite(v);
    std::vector<double> bw = b;
    int n = 0;
    const std::vector<double> K = dense_K(without, rest, shift, n);
    std::vector<double> v = gather_free(without, bw);
    dense_solve(K, n, v);
    std::vector<double> xr = b;
    int q = 0;
    for (std::size_t d = 0; d < b.size(); ++d)
      if (without.free[d]) xr[d] = v[q++];
    // on u itself: K_uu = shift I, so x_u = b_u / shift (without a force on u: x_u = 0,
    // relative to the largest displacement of the rest)
    double err_u = 0.0, max_rest = 0.0;
    for (std::size_t d = 0; d < x.size(); ++d)
      if (without.free[d]) max_rest = std::max(max_rest, std::fabs(x[d]));
    for (int c = 0; c < net.dim; ++c)
      if (b[net.dim * u + c] != 0.0)
        err_u = std::max(err_u, std::fabs(x[net.dim * u + c] * shift / b[net.dim * u + c] - 1.0));
      else
        err_u = std::max(err_u, std::fabs(x[net.dim * u + c]) / max_rest);
    const char *tag = zero_on_u ? "loose_zero_force" : "loose_with_force";
    report((std::string(tag) + "_finite").c_str(), finite ? 1.0 : 0.0);
    report((std::string(tag) + "_rest_vs_reference").c_str(), rel_diff(without, x, xr, u));
    report((std::string(tag) + "_node").c_str(), err_u);
  }
  report("loose_springs_cut", cut);
}

// errors: a spring outside the pattern; a downdate making K indefinite
void check_errors(Net &net, std::mt19937_64 &rng)
{
  LatticeSparseCholesky chol;
  chol.set_leaf_size(8);
  // the pattern without its first pair: that pair is then outside it
  std::vector<std::pair<int, int>> pattern(net.pairs.begin() + 1, net.pairs.end());
  chol.analyse(net.dim, net.nnodes, net.coords.data(), net.free, pattern);
  std::vector<LatticeSpring> inside(net.springs.begin() + 1, net.springs.end());
  chol.factorise(inside, 0.0);
  const std::vector<double> b = random_rhs(net, rng);
  std::vector<double> before = b, after = b;

  int caught = 0;
  try {
    chol.modify(net.springs[0], +1);
  } catch (const std::runtime_error &e) {
    std::printf("message %s\n", e.what());
    caught += std::strstr(e.what(), "not in the pattern") != nullptr;
  }
  report("error_modify_outside_pattern", caught);
  caught = 0;
  try {
    LatticeSparseCholesky other;
    other.analyse(net.dim, net.nnodes, net.coords.data(), net.free, pattern);
    other.factorise(net.springs, 0.0);
  } catch (const std::runtime_error &e) {
    std::printf("message %s\n", e.what());
    caught += std::strstr(e.what(), "not in the pattern") != nullptr;
  }
  report("error_factorise_outside_pattern", caught);

  // remove a spring twice, the second time stiffer than what holds its node: with
  // shift 0 the downdate makes K indefinite
  LatticeSpring s = inside[inside.size() / 2];
  chol.modify(s, -1);
  chol.modify(s, +1);    // back to the original K (to rounding)
  chol.solve(before.data());
  s.k = 1e3;
  caught = 0;
  try {
    chol.modify(s, -1);
  } catch (const std::runtime_error &e) {
    std::printf("message %s\n", e.what());
    caught += std::strstr(e.what(), "not positive") != nullptr && std::strstr(e.what(), "node") != nullptr;
  }
  report("error_indefinite_downdate", caught);
  chol.solve(after.data());
  report("error_factor_unchanged_after_failed_downdate", rel_diff(net, after, before));

  // a node held by no spring, shift 0: the pivot error names it
  const int u = net.nnodes / 2 + 1;
  std::vector<LatticeSpring> without_u;
  for (const auto &t : inside)
    if (t.a != u && t.b != u) without_u.push_back(t);
  int named = 0;
  try {
    chol.factorise(without_u, 0.0);
  } catch (const std::runtime_error &e) {
    std::printf("message %s\n", e.what());
    const std::string want = "node " + std::to_string(u) + " component ";
    named = std::strstr(e.what(), want.c_str()) != nullptr;
  }
  report("error_pivot_names_node", named);
  report("error_factorised_after_failure", chol.factorised() ? 1.0 : 0.0);
}

// the same input twice: bit-identical results
void check_deterministic(Net &net, std::mt19937_64 &rng)
{
  const std::vector<double> b = random_rhs(net, rng);
  std::vector<double> x[2];
  for (int run = 0; run < 2; ++run) {
    LatticeSparseCholesky chol;
    chol.set_leaf_size(8);
    chol.analyse(net.dim, net.nnodes, net.coords.data(), net.free, net.pairs);
    chol.factorise(net.springs, 1e-10);
    for (int q = 0; q < 5; ++q) chol.modify(net.springs[7 * q + 3], -1);
    x[run] = b;
    chol.solve(x[run].data());
  }
  report("deterministic", std::memcmp(x[0].data(), x[1].data(), sizeof(double) * b.size()) == 0);
}

// two nx x ny triangular patches side by side with no spring between them (the second
// shifted by nx + 12 along x: a gap of about 12 spacings), the bottom row of each held
Net two_patches(int nx, int ny, std::mt19937_64 &rng)
{
  Net two = triangular(nx, ny);
  const Net right = triangular(nx, ny);
  const int n0 = two.nnodes;
  for (int u = 0; u < right.nnodes; ++u) {
    two.coords.push_back(right.coords[2 * u] + nx + 12.0);
    two.coords.push_back(right.coords[2 * u + 1]);
  }
  for (const auto &pr : right.pairs) two.pairs.push_back({pr.first + n0, pr.second + n0});
  two.nnodes += right.nnodes;
  two.free.assign(2 * two.nnodes, 1);
  for (int i = 0; i < nx; ++i) {
    two.free[2 * i] = two.free[2 * i + 1] = 0;
    two.free[2 * (n0 + i)] = two.free[2 * (n0 + i) + 1] = 0;
  }
  random_springs(two, rng);
  return two;
}

// all blocks of the factor, one after the other
std::vector<double> factor_values(const LatticeSparseCholesky &chol)
{
  std::vector<double> v;
  for (int t = 0; t < chol.ntree(); ++t) {
    const int n = chol.col_end(t) - chol.col_begin(t);
    v.insert(v.end(), chol.block(t), chol.block(t) + (std::size_t) (n + chol.nrows(t)) * n);
  }
  return v;
}

bool same_bits(const std::vector<double> &a, const std::vector<double> &b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// factorise, solve, 20 downdates + 5 updates, solve, factorise afresh, solve on 1, 2, 3
// and 4 threads: every factor and solution bit for bit that of 1 thread.  2 threads are
// set before analyse(), the others after; one object also goes 4 -> 2 -> 1 -> 3 threads
// on the same factor.  Reports the mismatches (0 expected) and the plans' task counts
void check_threads(const char *tag, Net &net, int leaf, double shift, std::mt19937_64 &rng)
{
  const std::vector<double> b = random_rhs(net, rng);
  std::vector<std::pair<LatticeSpring, int>> changes;    // (spring, sign)
  {
    std::vector<LatticeSpring> now = net.springs, removed;
    for (int q = 0; q < 20; ++q) {
      const std::size_t i = (std::size_t) (uniform(rng) * now.size());
      changes.push_back({now[i], -1});
      removed.push_back(now[i]);
      now.erase(now.begin() + i);
    }
    for (int q = 0; q < 5; ++q) {
      LatticeSpring s = removed[(std::size_t) (uniform(rng) * removed.size())];
      s.k = 0.5 + uniform(rng);
      changes.push_back({s, +1});
    }
  }
  std::vector<double> ref[5];    // 1 thread: factor, x, modified factor, its x, fresh x
  int mismatches = 0, switch_mismatches = 0;
  std::string p(tag);
  for (int nt = 1; nt <= 4; ++nt) {
    LatticeSparseCholesky chol;
    chol.set_leaf_size(leaf);
    if (nt == 2) chol.set_threads(nt);
    chol.analyse(net.dim, net.nnodes, net.coords.data(), net.free, net.pairs);
    if (nt != 2) chol.set_threads(nt);
    chol.factorise(net.springs, shift);
    std::vector<double> got[5];
    got[0] = factor_values(chol);
    got[1] = b;
    chol.solve(got[1].data());
    for (const auto &c : changes) chol.modify(c.first, c.second);
    got[2] = factor_values(chol);
    got[3] = b;
    chol.solve(got[3].data());
    chol.factorise(net.springs, shift);    // again on the same object: the same factor
    got[4] = b;
    chol.solve(got[4].data());
    mismatches += !same_bits(factor_values(chol), got[0]);
    for (int q = 0; q < 5; ++q) {
      if (nt == 1) ref[q] = got[q];
      mismatches += !same_bits(got[q], ref[q]);
    }
    report((p + "_threads" + std::to_string(nt) + "_solve_tasks").c_str(), chol.solve_tasks());
    report((p + "_threads" + std::to_string(nt) + "_factorise_tasks").c_str(), chol.factorise_tasks());
    if (nt == 4) {
      for (int other : {2, 1, 3}) {
        chol.set_threads(other);
        std::vector<double> x = b;
        chol.solve(x.data());
        switch_mismatches += !same_bits(x, ref[4]) || chol.threads() != other;
      }
      report((p + "_max_rows").c_str(), chol.max_rows());
    }
  }
  report((p + "_threads_mismatches").c_str(), mismatches);
  report((p + "_threads_switch_mismatches").c_str(), switch_mismatches);
}

// a zero pivot in both halves of the network (two nodes without springs, shift 0): the
// error names the same node on 1 to 4 threads (the first bad pivot in post-order)
void check_threads_error(Net &net)
{
  const int u1 = net.nnodes / 4 + 5, u2 = 3 * net.nnodes / 4 - 25;    // (60 x 50: x 35 and 5)
  std::vector<LatticeSpring> without;
  for (const auto &s : net.springs)
    if (s.a != u1 && s.b != u1 && s.a != u2 && s.b != u2) without.push_back(s);
  std::string first;
  int same = 0, tasks = 0;
  for (int nt = 1; nt <= 4; ++nt) {
    LatticeSparseCholesky chol;
    chol.set_threads(nt);
    chol.analyse(net.dim, net.nnodes, net.coords.data(), net.free, net.pairs);
    tasks = std::max(tasks, chol.factorise_tasks());
    try {
      chol.factorise(without, 0.0);
    } catch (const std::runtime_error &e) {
      if (nt == 1) {
        first = e.what();
        std::printf("message %s\n", e.what());
      }
      same += first == e.what() && !chol.factorised();
    }
  }
  report("threads_error_same", same);
  report("threads_error_tasks", tasks);
  report("threads_error_names_a_node",
         first.find("node " + std::to_string(u1) + " ") != std::string::npos ||
             first.find("node " + std::to_string(u2) + " ") != std::string::npos);
}

void check_set_threads_range()
{
  LatticeSparseCholesky chol;
  int caught = 0;
  for (int bad : {0, -2}) {
    try {
      chol.set_threads(bad);
    } catch (const std::invalid_argument &e) {
      if (bad == 0) std::printf("message %s\n", e.what());
      caught += std::strstr(e.what(), "out of range") != nullptr;
    }
  }
  report("error_set_threads", caught);
  report("default_threads", chol.threads());
}

}    // namespace

int main()
{
  try {
    std::mt19937_64 rng(20261203);

    // 2D triangular 10 x 12: bottom row held, top row held in y, a few random components held
    Net tri = triangular(10, 12);
    for (int i = 0; i < 10; ++i) {
      tri.free[2 * i] = tri.free[2 * i + 1] = 0;
      tri.free[2 * (11 * 10 + i) + 1] = 0;
    }
    for (int q = 0; q < 6; ++q) tri.free[(std::size_t) (uniform(rng) * tri.free.size())] = 0;
    random_springs(tri, rng);
    check_solve("tri", tri, 16, 0.0, rng);
    check_solve("tri_leaf1", tri, 1, 0.0, rng);

    // 3D fcc 4^3 cells (256 nodes): bottom layer held, top layer held in z
    Net f = fcc(4);
    for (int a = 0; a < f.nnodes; ++a) {
      if (f.coords[3 * a + 2] == 0.0) f.free[3 * a] = f.free[3 * a + 1] = f.free[3 * a + 2] = 0;
      if (f.coords[3 * a + 2] == 3.5) f.free[3 * a + 2] = 0;
    }
    random_springs(f, rng);
    report("fcc_nodes", f.nnodes);
    check_solve("fcc", f, 16, 0.0, rng);

    // modifications: a larger 2D net, and the fcc one (shift: some nodes may come loose)
    Net tri2 = triangular(20, 24);
    for (int i = 0; i < 20; ++i) {
      tri2.free[2 * i] = tri2.free[2 * i + 1] = 0;
      tri2.free[2 * (23 * 20 + i)] = tri2.free[2 * (23 * 20 + i) + 1] = 0;
    }
    random_springs(tri2, rng);
    check_modify("tri2", tri2, 8, 1e-3, rng);
    check_modify("fcc", f, 8, 1e-3, rng);

    // two patches with no spring between them: the dissection's first separator is
    // empty and the tree a forest of two
    Net two = two_patches(8, 6, rng);
    check_solve("two_patches", two, 8, 0.0, rng);

    // no free component at all: an empty matrix, solve() a no-op
    {
      Net held = triangular(4, 4);
      held.free.assign(held.free.size(), 0);
      random_springs(held, rng);
      LatticeSparseCholesky chol;
      chol.analyse(2, held.nnodes, held.coords.data(), held.free, held.pairs);
      chol.factorise(held.springs, 0.0);
      chol.modify(held.springs[0], -1);
      std::vector<double> x = random_rhs(held, rng);
      chol.solve(x.data());
      report("all_held_entries", chol.factor_entries() + chol.ncols() + chol.ntree());
      report("all_held_untouched", held_untouched(held, x) ? 1.0 : 0.0);
    }

    check_loose(tri2, 8, rng);
    check_errors(tri2, rng);
    check_deterministic(tri2, rng);

    // threads: a 2D triangular 60 x 50 (bottom row held, a few random components held) and a
    // 3D fcc 6^3 cells (864 nodes, bottom layer held), large enough for the plans to split
    // them into tasks (and the fcc's top fronts for the rank-k updates split in row blocks)
    Net big = triangular(60, 50);
    for (int i = 0; i < 60; ++i) big.free[2 * i] = big.free[2 * i + 1] = 0;
    for (int q = 0; q < 20; ++q) big.free[(std::size_t) (uniform(rng) * big.free.size())] = 0;
    random_springs(big, rng);
    check_threads("tri_big", big, 8, 1e-3, rng);
    check_threads("tri_big_leaf2", big, 2, 1e-3, rng);
    Net f6 = fcc(6);
    for (int a = 0; a < f6.nnodes; ++a)
      if (f6.coords[3 * a + 2] == 0.0) f6.free[3 * a] = f6.free[3 * a + 1] = f6.free[3 * a + 2] = 0;
    random_springs(f6, rng);
    check_threads("fcc_big", f6, 8, 1e-3, rng);
    Net two_big = two_patches(40, 30, rng);    // a forest: the plans start from its two roots
    check_threads("two_big", two_big, 8, 1e-3, rng);
    check_threads_error(big);
    check_set_threads_range();
  } catch (const std::exception &e) {
    std::printf("unexpected %s\n", e.what());
    return 1;
  }
  return 0;
}
