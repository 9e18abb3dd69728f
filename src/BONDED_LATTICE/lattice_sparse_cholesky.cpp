/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   LatticeSparseCholesky: nested-dissection multifrontal Cholesky of a
   central-spring stiffness matrix, with rank-one updates and downdates
   along the elimination tree (lattice_sparse_cholesky.h).  The dense
   kernels (panel Cholesky, packed 4 x 4 symmetric rank-k update) are
   written out here: no BLAS.  Threads: a small pool (LatticeThreadPool)
   runs disjoint subtrees and the row blocks of large rank-k updates; the
   header explains why the results do not depend on the number of threads.
------------------------------------------------------------------------- */

#include "lattice_sparse_cholesky.h"
#include "lattice_thread_pool.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

using namespace LAMMPS_NS;

namespace {

// columns of a panel of the blocked dense Cholesky
constexpr int PANEL = 64;
// rows of packed A (in 4-row blocks) that one pass of the rank-k update keeps in cache
constexpr int SYRK_CHUNK = 64;

// acc[4 jj + ii] = sum_k a[4k + ii] b[4k + jj]: a 4 x 4 block of A A^T from two packed 4-row panels
inline void kernel4x4(const double *a, const double *b, int K, double *acc)
{
  double c[16] = {0.0};
  for (int k = 0; k < K; ++k) {
    const double *ak = a + 4 * k;
    const double *bk = b + 4 * k;
    for (int jj = 0; jj < 4; ++jj)
      for (int ii = 0; ii < 4; ++ii) c[4 * jj + ii] += ak[ii] * bk[jj];
  }
  for (int q = 0; q < 16; ++q) acc[q] = c[q];
}

// fronts whose trailing matrix has fewer rows than this update it on one thread
constexpr int SYRK_PARALLEL_ROWS = 128;

// the 4-row blocks ib0 <= ib < ib1 of C -= A A^T (lower triangle) from the packed A
void syrk_rows(int N, int K, const double *pack, int nb4, int ib0, int ib1, double *C, int ldc)
{
  double acc[16];
  for (int jb0 = 0; jb0 < nb4 && jb0 < ib1; jb0 += SYRK_CHUNK) {
    const int jb1 = std::min(jb0 + SYRK_CHUNK, nb4);
    for (int ib = std::max(jb0, ib0); ib < ib1; ++ib) {
      const double *pa = pack + (std::size_t) ib * 4 * K;
      const int i0 = 4 * ib;
      const int jend = std::min(jb1, ib + 1);
      for (int jb = jb0; jb < jend; ++jb) {
        kernel4x4(pa, pack + (std::size_t) jb * 4 * K, K, acc);
        const int j0 = 4 * jb;
        if (jb < ib && i0 + 4 <= N) {
          for (int jj = 0; jj < 4; ++jj) {
            double *c = C + i0 + (std::size_t) (j0 + jj) * ldc;
            c[0] -= acc[4 * jj];
            c[1] -= acc[4 * jj + 1];
            c[2] -= acc[4 * jj + 2];
            c[3] -= acc[4 * jj + 3];
          }
        } else {
          for (int jj = 0; jj < 4 && j0 + jj < N; ++jj) {
            double *c = C + (std::size_t) (j0 + jj) * ldc;
            for (int ii = 0; ii < 4 && i0 + ii < N; ++ii)
              if (i0 + ii >= j0 + jj) c[i0 + ii] -= acc[4 * jj + ii];
          }
        }
      }
    }
  }
}

// C -= A A^T on the lower triangle of C (N x N, leading dimension ldc);
// A is N x K (leading dimension lda); pack is scratch.  With a pool (and N
// large) the row blocks are split over its threads: each 4 x 4 block of C is
// still one kernel4x4 over all K, subtracted once (the same bits)
void syrk_lower(int N, int K, const double *A, int lda, double *C, int ldc, std::vector<double> &pack,
                LatticeThreadPool *pool)
{
  if (N <= 0 || K <= 0) return;
  const int nb4 = (N + 3) / 4;
  pack.resize((std::size_t) nb4 * 4 * K);
  for (int ib = 0; ib < nb4; ++ib) {
    double *p = pack.data() + (std::size_t) ib * 4 * K;
    const int i0 = 4 * ib;
    if (i0 + 4 <= N) {
      for (int k = 0; k < K; ++k) {
        const double *a = A + i0 + (std::size_t) k * lda;
        p[4 * k] = a[0];
        p[4 * k + 1] = a[1];
        p[4 * k + 2] = a[2];
        p[4 * k + 3] = a[3];
      }
    } else {
      for (int k = 0; k < K; ++k)
        for (int ii = 0; ii < 4; ++ii)
          p[4 * k + ii] = (i0 + ii < N) ? A[i0 + ii + (std::size_t) k * lda] : 0.0;
    }
  }
  if (!pool || pool->size() < 2 || N < SYRK_PARALLEL_ROWS) {
    syrk_rows(N, K, pack.data(), nb4, 0, nb4, C, ldc);
    return;
  }
  // 2 pieces per thread of about equal area of the lower triangle (rows up to ib: ~ ib^2 / 2)
  const int npiece = 2 * pool->size();
  std::vector<int> cut(npiece + 1, nb4);
  for (int q = 0; q < npiece; ++q)
    cut[q] = (int) std::lround(nb4 * std::sqrt((double) q / npiece));
  cut[npiece] = nb4;
  pool->run(npiece, [&](int q, int) {
    // the pieces by decreasing area: the last (largest) first
    const int piece = npiece - 1 - q;
    if (cut[piece] < cut[piece + 1])
      syrk_rows(N, K, pack.data(), nb4, cut[piece], cut[piece + 1], C, ldc);
  });
}

// Cholesky of the first n columns of the m x m lower triangle F (leading
// dimension m): F[:, 0:n] becomes L's columns, F[n:m, n:m] the Schur
// complement.  Returns the first column whose pivot is not positive (or not
// finite), -1 on success; pivot is set to its value
int partial_cholesky(double *F, int m, int n, std::vector<double> &pack, LatticeThreadPool *pool,
                     double &pivot)
{
  for (int k0 = 0; k0 < n; k0 += PANEL) {
    const int k1 = std::min(k0 + PANEL, n);
    for (int j = k0; j < k1; ++j) {
      double *cj = F + (std::size_t) j * m;
      for (int p = k0; p < j; ++p) {
        const double *cp = F + (std::size_t) p * m;
        const double f = cp[j];
        if (f == 0.0) continue;
        for (int i = j; i < m; ++i) cj[i] -= f * cp[i];
      }
      const double d = cj[j];
      if (!(d > 0.0) || !std::isfinite(d)) {
        pivot = d;
        return j;
      }
      const double s = std::sqrt(d);
      cj[j] = s;
      const double inv = 1.0 / s;
      for (int i = j + 1; i < m; ++i) cj[i] *= inv;
    }
    if (k1 < m)
      syrk_lower(m - k1, k1 - k0, F + k1 + (std::size_t) k0 * m, m, F + k1 + (std::size_t) k1 * m,
                 m, pack, pool);
  }
  return -1;
}

// below these totals (block entries; flops) a call runs on one thread
constexpr double MIN_PARALLEL_SOLVE = 2e4;
constexpr double MIN_PARALLEL_FACTOR = 2e6;
// most tasks a plan splits the tree into
constexpr int MAX_TASKS = 64;

}    // namespace

// factorise's working set on one thread: the frontal matrix, the update stack
// (entries: an update matrix, its tree node, the stack's top before it) and scratch
struct LatticeSparseCholesky::Front {
  struct Entry {
    const double *U;
    int tree;
    std::size_t top_before;
  };
  std::vector<double> F, stack, pack;
  std::vector<int> loc;
  std::vector<Entry> entries;
  std::size_t top = 0;
};

/* ---------------------------------------------------------------------- */

LatticeSparseCholesky::LatticeSparseCholesky() = default;
LatticeSparseCholesky::~LatticeSparseCholesky() = default;

void LatticeSparseCholesky::set_threads(int n)
{
  if (n < 1)
    throw std::invalid_argument("LatticeSparseCholesky: threads " + std::to_string(n) +
                                " is out of range (>= 1)");
  if (n == threads_) return;
  threads_ = n;
  pool_.reset();
  if (n > 1) pool_ = std::make_unique<LatticeThreadPool>(n);
  make_plans();
}

/* ---------------------------------------------------------------------- */

void LatticeSparseCholesky::set_leaf_size(int nodes)
{
  if (nodes < 1)
    throw std::invalid_argument("LatticeSparseCholesky: leaf size " + std::to_string(nodes) +
                                " is out of range (>= 1)");
  leaf_size_ = nodes;
}

/* ---------------------------------------------------------------------- */

void LatticeSparseCholesky::analyse(int dim, int nnodes, const double *coords,
                                    const std::vector<unsigned char> &free,
                                    const std::vector<std::pair<int, int>> &pairs)
{
  if (dim != 2 && dim != 3)
    throw std::invalid_argument("LatticeSparseCholesky::analyse: dim " + std::to_string(dim) +
                                " is out of range (2 or 3)");
  if (nnodes < 0)
    throw std::invalid_argument("LatticeSparseCholesky::analyse: nnodes " +
                                std::to_string(nnodes) + " is out of range (>= 0)");
  if (free.size() != (std::size_t) dim * nnodes)
    throw std::invalid_argument("LatticeSparseCholesky::analyse: free has " +
                                std::to_string(free.size()) + " entries, dim * nnodes = " +
                                std::to_string((std::size_t) dim * nnodes) + " expected");
  if (nnodes > 0 && !coords)
    throw std::invalid_argument("LatticeSparseCholesky::analyse: coords is null");
  factorised_ = false;
  dim_ = dim;
  nnodes_ = nnodes;
  ncols_ = 0;
  depth_ = 0;
  factor_.clear();
  factor_.shrink_to_fit();
  tree_.clear();
  rows_.clear();
  col_dof_.clear();
  col_tree_.clear();
  dof_col_.assign((std::size_t) dim * nnodes, -1);

  // the pattern: symmetric adjacency, sorted, without repeats
  std::vector<int> deg(nnodes + 1, 0);
  for (const auto &p : pairs) {
    if (p.first < 0 || p.first >= nnodes || p.second < 0 || p.second >= nnodes ||
        p.first == p.second)
      throw std::invalid_argument("LatticeSparseCholesky::analyse: pair (" +
                                  std::to_string(p.first) + ", " + std::to_string(p.second) +
                                  ") is out of range (two different nodes in [0, " +
                                  std::to_string(nnodes) + "))");
    ++deg[p.first + 1];
    ++deg[p.second + 1];
  }
  for (int i = 0; i < nnodes; ++i) deg[i + 1] += deg[i];
  std::vector<int> fill(deg.begin(), deg.end() - 1);
  std::vector<int> adj(deg[nnodes]);
  for (const auto &p : pairs) {
    adj[fill[p.first]++] = p.second;
    adj[fill[p.second]++] = p.first;
  }
  adj_off_.assign(nnodes + 1, 0);
  adj_.clear();
  adj_.reserve(adj.size());
  for (int i = 0; i < nnodes; ++i) {
    std::sort(adj.begin() + deg[i], adj.begin() + deg[i + 1]);
    auto last = std::unique(adj.begin() + deg[i], adj.begin() + deg[i + 1]);
    adj_.insert(adj_.end(), adj.begin() + deg[i], last);
    adj_off_[i + 1] = (int) adj_.size();
  }

  // nested dissection of the nodes with a free component
  std::vector<int> nodes;
  for (int i = 0; i < nnodes; ++i)
    for (int c = 0; c < dim; ++c)
      if (free[(std::size_t) dim * i + c]) {
        nodes.push_back(i);
        break;
      }
  for (int i : nodes)
    for (int c = 0; c < dim; ++c)
      if (!std::isfinite(coords[(std::size_t) dim * i + c]))
        throw std::invalid_argument("LatticeSparseCholesky::analyse: coordinate " +
                                    std::to_string(c) + " of node " + std::to_string(i) +
                                    " is not finite");
  std::vector<int> mark(nnodes, 0), roots, node_tree(nnodes, -1);
  int stamp = 0;
  for (int c = 0; c < dim * nnodes; ++c)
    if (free[c]) dof_col_[c] = -2;    // free, not numbered yet
  dissect(nodes, coords, mark, stamp, roots, node_tree);
  symbolic();
  make_plans();
}

/* ----------------------------------------------------------------------
   dissect the node set: a leaf, or two halves and their separator; appends
   the roots of the subtrees it makes to roots
------------------------------------------------------------------------- */

void LatticeSparseCholesky::dissect(std::vector<int> &nodes, const double *coords,
                                    std::vector<int> &mark, int &stamp, std::vector<int> &roots,
                                    std::vector<int> &node_tree)
{
  if (nodes.empty()) return;
  double lo[3], hi[3];
  for (int c = 0; c < dim_; ++c) lo[c] = hi[c] = coords[(std::size_t) dim_ * nodes[0] + c];
  for (int u : nodes)
    for (int c = 0; c < dim_; ++c) {
      const double x = coords[(std::size_t) dim_ * u + c];
      lo[c] = std::min(lo[c], x);
      hi[c] = std::max(hi[c], x);
    }
  int axis = 0;
  for (int c = 1; c < dim_; ++c)
    if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
  if ((int) nodes.size() <= leaf_size_ || !(hi[axis] > lo[axis])) {
    roots.push_back(add_tree_node(nodes, {}, node_tree));
    return;
  }
  auto key = [&](int u) { return coords[(std::size_t) dim_ * u + axis]; };
  const std::size_t half = nodes.size() / 2;
  std::nth_element(nodes.begin(), nodes.begin() + half, nodes.end(), [&](int u, int v) {
    return key(u) < key(v) || (key(u) == key(v) && u < v);
  });
  // split between coordinates, not inside a row of equal ones
  const double median = key(nodes[half]);
  auto mid = std::partition(nodes.begin(), nodes.end(), [&](int u) { return key(u) < median; });
  if (mid == nodes.begin())
    mid = std::partition(nodes.begin(), nodes.end(), [&](int u) { return key(u) <= median; });
  std::sort(nodes.begin(), mid);
  std::sort(mid, nodes.end());

  // the nodes of one side with a neighbour on the other: the smaller set
  auto boundary = [&](std::vector<int>::iterator b0, std::vector<int>::iterator b1,
                      std::vector<int>::iterator o0, std::vector<int>::iterator o1) {
    ++stamp;
    for (auto it = o0; it != o1; ++it) mark[*it] = stamp;
    std::vector<int> sep;
    for (auto it = b0; it != b1; ++it) {
      const int u = *it;
      for (int q = adj_off_[u]; q < adj_off_[u + 1]; ++q)
        if (mark[adj_[q]] == stamp) {
          sep.push_back(u);
          break;
        }
    }
    return sep;
  };
  std::vector<int> sep_left = boundary(nodes.begin(), mid, mid, nodes.end());
  std::vector<int> sep_right = boundary(mid, nodes.end(), nodes.begin(), mid);
  std::vector<int> &sep = (sep_left.size() <= sep_right.size()) ? sep_left : sep_right;
  ++stamp;
  for (int u : sep) mark[u] = stamp;
  std::vector<int> left, right;
  for (auto it = nodes.begin(); it != mid; ++it)
    if (mark[*it] != stamp) left.push_back(*it);
  for (auto it = mid; it != nodes.end(); ++it)
    if (mark[*it] != stamp) right.push_back(*it);
  std::vector<int> children;
  dissect(left, coords, mark, stamp, children, node_tree);
  dissect(right, coords, mark, stamp, children, node_tree);
  if (sep.empty())
    roots.insert(roots.end(), children.begin(), children.end());
  else
    roots.push_back(add_tree_node(sep, children, node_tree));
}

/* ---------------------------------------------------------------------- */

int LatticeSparseCholesky::add_tree_node(const std::vector<int> &nodes,
                                         const std::vector<int> &children,
                                         std::vector<int> &node_tree)
{
  const int t = (int) tree_.size();
  TreeNode tn;
  tn.col0 = ncols_;
  for (int u : nodes) {
    node_tree[u] = t;
    for (int c = 0; c < dim_; ++c) {
      const int dof = dim_ * u + c;
      if (dof_col_[dof] == -2) {
        dof_col_[dof] = ncols_++;
        col_dof_.push_back(dof);
        col_tree_.push_back(t);
      }
    }
  }
  tn.ncol = ncols_ - tn.col0;
  tn.nchild = (int) children.size();
  for (int c : children) tree_[c].parent = t;
  tree_.push_back(tn);
  return t;
}

/* ----------------------------------------------------------------------
   row sets R_t, block offsets, depth, the scratch sizes of factorise
------------------------------------------------------------------------- */

void LatticeSparseCholesky::symbolic()
{
  const int ntree = (int) tree_.size();
  child_off_.assign(ntree + 1, 0);
  child_.assign(ntree, 0);
  for (int t = 0; t < ntree; ++t)
    if (tree_[t].parent >= 0) ++child_off_[tree_[t].parent + 1];
  for (int t = 0; t < ntree; ++t) child_off_[t + 1] += child_off_[t];
  {
    std::vector<int> fill(child_off_.begin(), child_off_.end() - 1);
    for (int t = 0; t < ntree; ++t)
      if (tree_[t].parent >= 0) child_[fill[tree_[t].parent]++] = t;
  }
  first_desc_.resize(ntree);
  for (int t = 0; t < ntree; ++t)
    first_desc_[t] = (child_off_[t + 1] > child_off_[t]) ? first_desc_[child_[child_off_[t]]] : t;
  const std::vector<int> &child_off = child_off_, &child = child_;
  std::vector<int> mark(ncols_, -1), r;
  std::size_t block = 0;
  max_front_ = 0;
  max_rows_ = 0;
  for (int t = 0; t < ntree; ++t) {
    TreeNode &tn = tree_[t];
    const int c0 = tn.col0, c1 = tn.col0 + tn.ncol;
    r.clear();
    for (int q = child_off[t]; q < child_off[t + 1]; ++q) {
      const TreeNode &ch = tree_[child[q]];
      const int *rc = rows_.data() + ch.rows_off;
      for (int p = 0; p < ch.nrow; ++p) {
        const int col = rc[p];
        if (col < c0)
          throw std::logic_error("LatticeSparseCholesky: row set of a child below its parent");
        if (col >= c1 && mark[col] != t) {
          mark[col] = t;
          r.push_back(col);
        }
      }
    }
    int last = -1;
    for (int col = c0; col < c1; ++col) {
      const int u = col_dof_[col] / dim_;
      if (u == last) continue;
      last = u;
      for (int q = adj_off_[u]; q < adj_off_[u + 1]; ++q) {
        const int v = adj_[q];
        for (int c = 0; c < dim_; ++c) {
          const int cv = dof_col_[dim_ * v + c];
          if (cv >= c1 && mark[cv] != t) {
            mark[cv] = t;
            r.push_back(cv);
          }
        }
      }
    }
    std::sort(r.begin(), r.end());
    tn.rows_off = rows_.size();
    tn.nrow = (int) r.size();
    rows_.insert(rows_.end(), r.begin(), r.end());
    tn.block_off = block;
    const std::size_t m = (std::size_t) tn.ncol + tn.nrow;
    block += m * tn.ncol;
    max_front_ = std::max(max_front_, m * m);
    max_rows_ = std::max(max_rows_, m);
  }
  rows_.shrink_to_fit();
  factor_size_ = block;

  // depth, and the peak of the update-matrix stack in post-order
  std::vector<int> d(ntree, 1);
  depth_ = 0;
  for (int t = ntree - 1; t >= 0; --t) {
    if (tree_[t].parent >= 0) d[t] = d[tree_[t].parent] + 1;
    depth_ = std::max(depth_, d[t]);
  }
  std::vector<std::size_t> sizes;
  std::size_t total = 0;
  max_stack_ = 0;
  for (int t = 0; t < ntree; ++t) {
    for (int q = 0; q < tree_[t].nchild; ++q) {
      total -= sizes.back();
      sizes.pop_back();
    }
    const std::size_t r2 = (std::size_t) tree_[t].nrow * (tree_[t].nrow + 1) / 2;
    sizes.push_back(r2);
    total += r2;
    max_stack_ = std::max(max_stack_, total);
  }
}

/* ----------------------------------------------------------------------
   the plans of solve() and factorise() for threads_ threads (after symbolic)
------------------------------------------------------------------------- */

void LatticeSparseCholesky::make_plans()
{
  solve_plan_ = Plan();
  factor_plan_ = Plan();
  const int ntree = (int) tree_.size();
  if (threads_ < 2 || ntree < 2) return;
  std::vector<double> entries(ntree), flops(ntree);
  for (int t = 0; t < ntree; ++t) {
    const double n = tree_[t].ncol, r = tree_[t].nrow, m = n + r;
    entries[t] = m * n;
    flops[t] = n * n * n / 3.0 + r * n * n + r * r * n + m * m;
  }
  solve_plan_ = make_plan(entries, 1.0, MIN_PARALLEL_SOLVE);
  // factorise's top: its rank-k updates run on all the threads, the rest (panels, assembly) on one
  factor_plan_ = make_plan(flops, 0.25 + 0.75 / threads_, MIN_PARALLEL_FACTOR);

  // solve: the products a task's node keeps for the top's rows (R_t beyond the task's columns)
  Plan &sp = solve_plan_;
  if (!sp.roots.empty()) {
    sp.defer_off.assign(ntree + 1, 0);
    for (int t = 0; t < ntree; ++t) {
      std::size_t nkept = 0;
      if (sp.task_of[t] >= 0) {
        const int end = col_end(sp.roots[sp.task_of[t]]);
        const int *R = rows(t);
        nkept = (R + tree_[t].nrow) - std::lower_bound(R, R + tree_[t].nrow, end);
      }
      sp.defer_off[t + 1] = sp.defer_off[t] + nkept;
    }
  }
  // factorise: the largest frontal matrix and update stack of a task (symbolic()'s
  // post-order stack over the task's subtree)
  Plan &fp = factor_plan_;
  for (int root : fp.roots) {
    std::vector<std::size_t> sizes;
    std::size_t total = 0;
    for (int t = first_desc_[root]; t <= root; ++t) {
      for (int q = 0; q < tree_[t].nchild; ++q) {
        total -= sizes.back();
        sizes.pop_back();
      }
      const std::size_t r = tree_[t].nrow, m = (std::size_t) tree_[t].ncol + r;
      sizes.push_back(r * (r + 1) / 2);
      total += sizes.back();
      fp.stack = std::max(fp.stack, total);
      fp.front = std::max(fp.front, m * m);
    }
  }
}

/* ----------------------------------------------------------------------
   the task roots for the cost of each tree node: from the roots of the
   forest, the costliest subtree that has children is split (its root goes
   to the top) up to MAX_TASKS tasks; the split with the least estimated time
   (top_weight x the top's cost + the largest load of the threads when the
   tasks are dealt out by decreasing cost to the least loaded) is kept.  No
   tasks if the total is below min_cost or the best has one task
------------------------------------------------------------------------- */

LatticeSparseCholesky::Plan LatticeSparseCholesky::make_plan(const std::vector<double> &cost,
                                                             double top_weight,
                                                             double min_cost) const
{
  Plan plan;
  const int ntree = (int) tree_.size();
  std::vector<double> sub(cost);    // the subtrees' costs (children come before parents)
  double total = 0.0;
  for (int t = 0; t < ntree; ++t) {
    total += cost[t];
    if (tree_[t].parent >= 0) sub[tree_[t].parent] += sub[t];
  }
  if (threads_ < 2 || total < min_cost) return plan;
  std::vector<int> tasks, best;
  for (int t = 0; t < ntree; ++t)
    if (tree_[t].parent < 0) tasks.push_back(t);
  double top = 0.0, best_time = total;
  std::vector<double> load(threads_), c;
  for (;;) {
    if (tasks.size() >= 2) {
      c.clear();
      for (int t : tasks) c.push_back(sub[t]);
      std::sort(c.begin(), c.end(), [](double a, double b) { return a > b; });
      std::fill(load.begin(), load.end(), 0.0);
      for (double x : c) *std::min_element(load.begin(), load.end()) += x;
      const double time = top_weight * top + *std::max_element(load.begin(), load.end());
      if (time < best_time) {
        best_time = time;
        best = tasks;
      }
    }
    int pick = -1;
    for (int q = 0; q < (int) tasks.size(); ++q)
      if (tree_[tasks[q]].nchild > 0 && (pick < 0 || sub[tasks[q]] > sub[tasks[pick]])) pick = q;
    if (pick < 0 || (int) tasks.size() - 1 + tree_[tasks[pick]].nchild > MAX_TASKS) break;
    const int t = tasks[pick];
    top += cost[t];
    tasks.erase(tasks.begin() + pick);
    for (int q = 0; q < nchildren(t); ++q) tasks.push_back(child(t, q));
  }
  if (best.size() < 2) return plan;
  std::sort(best.begin(), best.end());
  const int ntask = (int) best.size();
  plan.roots = best;
  plan.task_of.assign(ntree, -1);
  for (int k = 0; k < ntask; ++k)
    for (int t = first_desc_[best[k]]; t <= best[k]; ++t) plan.task_of[t] = k;
  plan.order.resize(ntask);
  for (int k = 0; k < ntask; ++k) plan.order[k] = k;
  std::stable_sort(plan.order.begin(), plan.order.end(),
                   [&](int a, int b) { return sub[best[a]] > sub[best[b]]; });
  return plan;
}

/* ---------------------------------------------------------------------- */

bool LatticeSparseCholesky::in_pattern(int a, int b) const
{
  return std::binary_search(adj_.begin() + adj_off_[a], adj_.begin() + adj_off_[a + 1], b);
}

void LatticeSparseCholesky::check_spring(const LatticeSpring &s, const char *what) const
{
  const std::string who = std::string("LatticeSparseCholesky::") + what + ": spring (" +
      std::to_string(s.a) + ", " + std::to_string(s.b) + ")";
  if (s.a < 0 || s.a >= nnodes_ || s.b < 0 || s.b >= nnodes_ || s.a == s.b)
    throw std::runtime_error(who + " does not join two different nodes in [0, " +
                             std::to_string(nnodes_) + ")");
  if (!std::isfinite(s.k) || s.k < 0.0)
    throw std::runtime_error(who + " has stiffness " + std::to_string(s.k) +
                             " (valid: finite, >= 0)");
  for (int c = 0; c < dim_; ++c)
    if (!std::isfinite(s.n[c]))
      throw std::runtime_error(who + " has a direction that is not finite");
  if (!in_pattern(s.a, s.b))
    throw std::runtime_error(who + " is not in the pattern given to analyse()");
}

int LatticeSparseCholesky::spring_vector(const LatticeSpring &s, int *cols, double *vals) const
{
  int nv = 0;
  for (int c = 0; c < dim_; ++c) {
    const int col = dof_col_[dim_ * s.a + c];
    if (col >= 0) {
      cols[nv] = col;
      vals[nv++] = -s.n[c];
    }
  }
  for (int c = 0; c < dim_; ++c) {
    const int col = dof_col_[dim_ * s.b + c];
    if (col >= 0) {
      cols[nv] = col;
      vals[nv++] = s.n[c];
    }
  }
  return nv;
}

void LatticeSparseCholesky::pivot_error(int col, double pivot, const char *what) const
{
  const int dof = col_dof_[col];
  throw std::runtime_error(std::string("LatticeSparseCholesky::") + what + ": pivot " +
                           std::to_string(pivot) + " of node " + std::to_string(dof / dim_) +
                           " component " + std::to_string(dof % dim_) +
                           " is not positive (the stiffness matrix is not positive definite: "
                           "a part of the network held by no spring, with shift 0?)");
}

/* ---------------------------------------------------------------------- */

void LatticeSparseCholesky::factorise(const std::vector<LatticeSpring> &springs, double shift)
{
  if (!std::isfinite(shift) || shift < 0.0)
    throw std::runtime_error("LatticeSparseCholesky::factorise: shift " + std::to_string(shift) +
                             " is out of range (finite, >= 0)");
  factorised_ = false;
  const int ntree = (int) tree_.size();

  // springs by the tree nodes of their two nodes (each entry of k g g^T
  // belongs to the tree node of its column, the lower of its two)
  std::vector<int> off(ntree + 1, 0);
  auto tree_of_node = [&](int u) {
    for (int c = 0; c < dim_; ++c)
      if (dof_col_[dim_ * u + c] >= 0) return col_tree_[dof_col_[dim_ * u + c]];
    return -1;
  };
  std::vector<int> ta(springs.size()), tb(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    check_spring(springs[s], "factorise");
    ta[s] = tree_of_node(springs[s].a);
    tb[s] = tree_of_node(springs[s].b);
    if (ta[s] >= 0) ++off[ta[s] + 1];
    if (tb[s] >= 0 && tb[s] != ta[s]) ++off[tb[s] + 1];
  }
  for (int t = 0; t < ntree; ++t) off[t + 1] += off[t];
  std::vector<int> bucket(off[ntree]);
  {
    std::vector<int> fill(off.begin(), off.end() - 1);
    for (std::size_t s = 0; s < springs.size(); ++s) {
      if (ta[s] >= 0) bucket[fill[ta[s]]++] = (int) s;
      if (tb[s] >= 0 && tb[s] != ta[s]) bucket[fill[tb[s]]++] = (int) s;
    }
  }

  factor_.resize(factor_size_);    // every entry is written below (the blocks tile it)
  Front top;
  top.F.resize(max_front_);
  top.stack.resize(max_stack_);
  top.loc.assign(ncols_, -1);
  double pivot = 0.0;
  const Plan &pl = factor_plan_;
  if (!pool_ || pl.roots.empty()) {
    for (int t = 0; t < ntree; ++t) {
      const int bad = factor_node(t, top, springs, off.data(), bucket.data(), shift, nullptr, pivot);
      if (bad >= 0) pivot_error(bad, pivot, "factorise");
    }
    factorised_ = true;
    return;
  }

  // the tasks: each subtree's sweep on one thread, its root's update matrix kept
  const int ntask = (int) pl.roots.size();
  std::vector<Front> fronts(pool_->size());
  std::vector<std::vector<double>> update(ntask);
  std::vector<int> bad_col(ntask, -1);
  std::vector<double> bad_pivot(ntask, 0.0);
  pool_->run(ntask, [&](int q, int thread) {
    const int k = pl.order[q], root = pl.roots[k];
    Front &fr = fronts[thread];
    if (fr.loc.empty()) {
      fr.F.resize(pl.front);
      fr.stack.resize(pl.stack);
      fr.loc.assign(ncols_, -1);
    }
    fr.entries.clear();
    fr.top = 0;
    for (int t = first_desc_[root]; t <= root; ++t) {
      double pv = 0.0;
      const int bad = factor_node(t, fr, springs, off.data(), bucket.data(), shift, nullptr, pv);
      if (bad >= 0) {
        bad_col[k] = bad;
        bad_pivot[k] = pv;
        return;
      }
    }
    const std::size_t r = tree_[root].nrow;
    update[k].assign(fr.entries.back().U, fr.entries.back().U + r * (r + 1) / 2);
  });
  fronts.clear();

  // the top in post-order; a task's failure or update matrix where its root comes
  for (int t = 0; t < ntree; ++t) {
    const int k = pl.task_of[t];
    if (k >= 0) {
      if (t != pl.roots[k]) continue;
      if (bad_col[k] >= 0) pivot_error(bad_col[k], bad_pivot[k], "factorise");
      top.entries.push_back({update[k].data(), t, top.top});
      continue;
    }
    const int bad = factor_node(t, top, springs, off.data(), bucket.data(), shift, pool_.get(), pivot);
    if (bad >= 0) pivot_error(bad, pivot, "factorise");
  }
  factorised_ = true;
}

/* ----------------------------------------------------------------------
   the front of tree node t on fr: the springs' entries and the shift, the
   extend-add of the children's update matrices (the last entries of fr's
   stack, in order), the partial Cholesky (its rank-k updates on pool's
   threads if given), L_t into the factor, the update matrix pushed.
   Returns -1, or the column whose pivot failed (its value in pivot)
------------------------------------------------------------------------- */

int LatticeSparseCholesky::factor_node(int t, Front &fr, const std::vector<LatticeSpring> &springs,
                                       const int *off, const int *bucket, double shift,
                                       LatticeThreadPool *pool, double &pivot)
{
  const TreeNode &tn = tree_[t];
  const int n = tn.ncol, r = tn.nrow, m = n + r;
  const int c0 = tn.col0, c1 = tn.col0 + n;
  const int *R = rows_.data() + tn.rows_off;
  if (fr.F.size() < (std::size_t) m * m) fr.F.resize((std::size_t) m * m);
  double *F = fr.F.data();
  int *loc = fr.loc.data();
  for (int j = 0; j < m; ++j) std::fill(F + (std::size_t) j * m + j, F + (std::size_t) (j + 1) * m, 0.0);
  for (int i = 0; i < n; ++i) loc[c0 + i] = i;
  for (int p = 0; p < r; ++p) loc[R[p]] = n + p;

  // the springs' entries in the columns of t, and the shift
  int cols[6];
  double vals[6];
  for (int q = off[t]; q < off[t + 1]; ++q) {
    const LatticeSpring &s = springs[bucket[q]];
    const int nv = spring_vector(s, cols, vals);
    for (int a = 0; a < nv; ++a) {
      if (cols[a] < c0 || cols[a] >= c1) continue;
      const int lj = cols[a] - c0;
      for (int b = 0; b < nv; ++b)
        if (cols[b] >= cols[a]) F[(std::size_t) lj * m + loc[cols[b]]] += s.k * vals[a] * vals[b];
    }
  }
  for (int i = 0; i < n; ++i) F[(std::size_t) i * m + i] += shift;

  // extend-add of the children's update matrices (the top of the stack)
  const int nchild = tn.nchild;
  const std::size_t ne = fr.entries.size();
  for (std::size_t q = ne - nchild; q < ne; ++q) {
    const TreeNode &ch = tree_[fr.entries[q].tree];
    const int rc = ch.nrow;
    const int *Rc = rows_.data() + ch.rows_off;
    const double *U = fr.entries[q].U;
    for (int b = 0; b < rc; ++b) {
      double *col = F + (std::size_t) loc[Rc[b]] * m;
      for (int a = b; a < rc; ++a) col[loc[Rc[a]]] += *U++;
    }
  }
  if (nchild > 0) {
    fr.top = fr.entries[ne - nchild].top_before;
    fr.entries.resize(ne - nchild);
  }

  const int bad = partial_cholesky(F, m, n, fr.pack, pool, pivot);
  if (bad >= 0) return c0 + bad;
  std::memcpy(factor_.data() + tn.block_off, F, sizeof(double) * (std::size_t) m * n);
  for (int j = 0; j < n; ++j)    // the strict upper triangle of the diagonal block: zeros
    std::fill(factor_.begin() + tn.block_off + (std::size_t) j * m,
              factor_.begin() + tn.block_off + (std::size_t) j * m + j, 0.0);

  // the Schur complement on R_t, packed lower, onto the stack
  fr.entries.push_back({fr.stack.data() + fr.top, t, fr.top});
  for (int b = n; b < m; ++b) {
    const double *col = F + (std::size_t) b * m;
    std::copy(col + b, col + m, fr.stack.data() + fr.top);
    fr.top += m - b;
  }
  return -1;
}

/* ---------------------------------------------------------------------- */

void LatticeSparseCholesky::solve(double *x) const
{
  if (!factorised_)
    throw std::logic_error("LatticeSparseCholesky::solve: no factor (factorise() first)");
  const int ntree = (int) tree_.size();
  const Plan &pl = solve_plan_;
  if (!pool_ || pl.roots.empty()) {
    std::vector<double> w(ncols_), v(max_rows_);
    for (int col = 0; col < ncols_; ++col) w[col] = x[col_dof_[col]];
    for (int t = 0; t < ntree; ++t) forward_block(t, w.data(), v.data());
    for (int t = ntree - 1; t >= 0; --t) back_block(t, w.data(), v.data());
    for (int col = 0; col < ncols_; ++col) x[col_dof_[col]] = w[col];
    return;
  }

  const int ntask = (int) pl.roots.size();
  std::unique_ptr<double[]> wbuf(new double[ncols_]);    // every entry gathered below
  double *w = wbuf.get();
  std::vector<double> kept(pl.defer_off[ntree]);
  std::vector<std::vector<double>> scratch(pool_->size(), std::vector<double>(max_rows_));
  // the q-th task run (by decreasing cost): its subtree [first, root], its columns [c0, c1)
  struct Range {
    int first, root, c0, c1;
  };
  auto range = [&](int q) {
    const int root = pl.roots[pl.order[q]], first = first_desc_[root];
    return Range{first, root, tree_[first].col0, col_end(root)};
  };

  // forward, the tasks: w gathered on their columns; the products for the
  // top's rows kept
  pool_->run(ntask, [&](int q, int thread) {
    const Range r = range(q);
    for (int col = r.c0; col < r.c1; ++col) w[col] = x[col_dof_[col]];
    for (int t = r.first; t <= r.root; ++t) {
      const int nkept = (int) (pl.defer_off[t + 1] - pl.defer_off[t]);
      forward_rows(t, w, scratch[thread].data(), tree_[t].nrow - nkept, kept.data() + pl.defer_off[t]);
    }
  });
  // forward, the top: gathered, then the post-order walk (the serial order of the additions)
  double *v = scratch[0].data();
  for (int t = 0; t < ntree; ++t)
    if (pl.task_of[t] < 0)
      for (int col = tree_[t].col0; col < col_end(t); ++col) w[col] = x[col_dof_[col]];
  for (int t = 0; t < ntree; ++t) {
    if (pl.task_of[t] < 0) {
      forward_rows(t, w, v, tree_[t].nrow, nullptr);
      continue;
    }
    const std::size_t o = pl.defer_off[t], nkept = pl.defer_off[t + 1] - o;
    const int *R = rows(t) + (tree_[t].nrow - nkept);
    for (std::size_t p = 0; p < nkept; ++p) w[R[p]] += kept[o + p];
  }
  // back: the top, then the tasks
  for (int t = ntree - 1; t >= 0; --t)
    if (pl.task_of[t] < 0) {
      back_block(t, w, v);
      for (int col = tree_[t].col0; col < col_end(t); ++col) x[col_dof_[col]] = w[col];
    }
  pool_->run(ntask, [&](int q, int thread) {
    const Range r = range(q);
    for (int t = r.root; t >= r.first; --t) back_block(t, w, scratch[thread].data());
    for (int col = r.c0; col < r.c1; ++col) x[col_dof_[col]] = w[col];
  });
}

/* ---------------------------------------------------------------------- */

// y := w on the columns of t, then w on R_t (rows_too) or zeros; returns L_t
const double *LatticeSparseCholesky::load_block(int t, const double *w, double *y, bool rows_too,
                                                int &n, int &m) const
{
  const TreeNode &tn = tree_[t];
  n = tn.ncol;
  m = n + tn.nrow;
  std::copy(w + tn.col0, w + tn.col0 + n, y);
  const int *R = rows_.data() + tn.rows_off;
  for (int p = 0; p < tn.nrow; ++p) y[n + p] = rows_too ? w[R[p]] : 0.0;
  return factor_.data() + tn.block_off;
}

void LatticeSparseCholesky::forward_block(int t, double *w, double *scratch) const
{
  forward_rows(t, w, scratch, tree_[t].nrow, nullptr);
}

// forward_block, its products for the rows R_t[nrow_w..) stored in kept instead of
// added into w
void LatticeSparseCholesky::forward_rows(int t, double *w, double *scratch, int nrow_w,
                                         double *kept) const
{
  int n, m;
  const double *L = load_block(t, w, scratch, false, n, m);
  double *y = scratch;
  for (int j = 0; j < n; ++j) {    // column by column through the block
    const double *col = L + (std::size_t) j * m;
    const double yj = y[j] / col[j];
    y[j] = yj;
    for (int i = j + 1; i < m; ++i) y[i] -= col[i] * yj;
  }
  std::copy(y, y + n, w + tree_[t].col0);
  const int *R = rows(t);
  for (int p = 0; p < nrow_w; ++p) w[R[p]] += y[n + p];
  for (int p = nrow_w; p < m - n; ++p) kept[p - nrow_w] = y[n + p];
}
void LatticeSparseCholesky::back_block(int t, double *w, double *scratch) const
{
  int n, m;
  const double *L = load_block(t, w, scratch, true, n, m);
  double *y = scratch;
  for (int j = n - 1; j >= 0; --j) {
    const double *col = L + (std::size_t) j * m;
    // four partial sums (a fixed order: deterministic)
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    int i = j + 1;
    for (; i + 4 <= m; i += 4) {
      s0 += col[i] * y[i];
      s1 += col[i + 1] * y[i + 1];
      s2 += col[i + 2] * y[i + 2];
      s3 += col[i + 3] * y[i + 3];
    }
    for (; i < m; ++i) s0 += col[i] * y[i];
    y[j] = (y[j] - ((s0 + s1) + (s2 + s3))) / col[j];
  }
  std::copy(y, y + n, w + tree_[t].col0);
}

/* ---------------------------------------------------------------------- */

std::vector<int> LatticeSparseCholesky::path(int a, int b) const
{
  std::vector<int> p;
  for (int u : {a, b}) {
    if (u < 0 || u >= nnodes_) continue;
    int t = -1;
    for (int c = 0; c < dim_ && t < 0; ++c)
      if (dof_col_[dim_ * u + c] >= 0) t = col_tree_[dof_col_[dim_ * u + c]];
    for (; t >= 0; t = tree_[t].parent) p.push_back(t);
  }
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

void LatticeSparseCholesky::modify(const LatticeSpring &s, int sign)
{
  if (!factorised_)
    throw std::logic_error("LatticeSparseCholesky::modify: no factor (factorise() first)");
  if (sign != 1 && sign != -1)
    throw std::invalid_argument("LatticeSparseCholesky::modify: sign " + std::to_string(sign) +
                                " is out of range (+1 or -1)");
  check_spring(s, "modify");
  int cols[6];
  double vals[6];
  const int nv = spring_vector(s, cols, vals);
  if (nv == 0 || s.k == 0.0) return;
  const std::vector<int> p = path(s.a, s.b);

  xwork_.resize(ncols_, 0.0);
  const double sq = std::sqrt(s.k);
  for (int q = 0; q < nv; ++q) xwork_[cols[q]] += sq * vals[q];
  std::size_t most = 0;
  for (int t : p) most += ((std::size_t) tree_[t].ncol + tree_[t].nrow) * tree_[t].ncol;
  std::vector<double> v(max_rows_);
  // a downdate can fail part way: it keeps the old values of the column parts it
  // changes (col[j..m) of each column it rotates) in backup_, at these factor offsets
  std::vector<std::pair<std::size_t, std::size_t>> saved;    // (offset in factor_, length)
  std::size_t used = 0;
  if (sign < 0 && backup_.size() < most) backup_.resize(most);

  for (int t : p) {
    const TreeNode &tn = tree_[t];
    const int n = tn.ncol, m = n + tn.nrow;
    const int *R = rows_.data() + tn.rows_off;
    double *L = factor_.data() + tn.block_off;
    int j0 = 0;
    while (j0 < n && xwork_[tn.col0 + j0] == 0.0) ++j0;
    if (j0 == n) continue;    // nothing reaches this block's columns: it stays as it is
    std::copy(xwork_.begin() + tn.col0, xwork_.begin() + tn.col0 + n, v.begin());
    for (int q = 0; q < tn.nrow; ++q) v[n + q] = xwork_[R[q]];
    for (int j = j0; j < n; ++j) {
      const double xj = v[j];
      if (xj == 0.0) continue;
      double *col = L + (std::size_t) j * m;
      const double ljj = col[j];
      const double r2 = ljj * ljj + (sign > 0 ? xj * xj : -(xj * xj));
      if (!(r2 > 0.0) || !std::isfinite(r2)) {
        std::fill(xwork_.begin(), xwork_.end(), 0.0);
        std::size_t o = 0;
        for (const auto &sv : saved) {
          std::copy(backup_.begin() + o, backup_.begin() + o + sv.second,
                    factor_.begin() + sv.first);
          o += sv.second;
        }
        if (sign > 0) factorised_ = false;    // only an overflow: the columns before are changed
        pivot_error(tn.col0 + j, r2, sign > 0 ? "modify (update)" : "modify (downdate)");
      }
      const double rr = std::sqrt(r2);
      const double c = rr / ljj, sn = xj / ljj, ic = 1.0 / c;
      col[j] = rr;
      if (sign > 0) {
        for (int i = j + 1; i < m; ++i) {
          const double l = (col[i] + sn * v[i]) * ic;
          col[i] = l;
          v[i] = c * v[i] - sn * l;
        }
      } else {
        double *bk = backup_.data() + used;
        bk[0] = ljj;
        for (int i = j + 1; i < m; ++i) {
          const double old = col[i];
          bk[i - j] = old;
          const double l = (old - sn * v[i]) * ic;
          col[i] = l;
          v[i] = c * v[i] - sn * l;
        }
        saved.push_back({tn.block_off + (std::size_t) j * m + j, (std::size_t) (m - j)});
        used += m - j;
      }
    }
    std::fill(xwork_.begin() + tn.col0, xwork_.begin() + tn.col0 + n, 0.0);
    for (int q = 0; q < tn.nrow; ++q) xwork_[R[q]] = v[n + q];
  }
}

/* ---------------------------------------------------------------------- */

double LatticeSparseCholesky::factor_entries() const
{
  double e = 0.0;
  for (const auto &tn : tree_)
    e += 0.5 * (double) tn.ncol * (tn.ncol + 1) + (double) tn.nrow * tn.ncol;
  return e;
}

std::size_t LatticeSparseCholesky::bytes() const
{
  return sizeof(double) * factor_.capacity() +
      sizeof(int) * (rows_.capacity() + dof_col_.capacity() + col_dof_.capacity() +
                     col_tree_.capacity() + adj_.capacity() + adj_off_.capacity() +
                     child_off_.capacity() + child_.capacity() + first_desc_.capacity()) +
      sizeof(TreeNode) * tree_.capacity();
}

std::size_t LatticeSparseCholesky::work_bytes() const
{
  return sizeof(double) * (max_front_ + max_stack_);
}
