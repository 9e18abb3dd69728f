/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Sparse Cholesky factorisation of the stiffness matrix of a network of
   central springs, K = sum_s k_s g_s g_s^T + shift I on the free
   components, with rank-one updates and downdates (a spring added or
   removed) along the elimination tree.  Standalone: only the C++17
   standard library (no LAMMPS, no BLAS), so that it compiles by itself
   (tests/cpp/sparse_cholesky_check.cpp) as well as in the plugin.

   Ordering (analyse): geometric nested dissection of the nodes that have a
   free component.  A set of nodes is split at the median of its longest
   extent; the nodes of one side that have a pattern neighbour on the other
   side (the smaller of the two such sets) are the vertex separator, ordered
   after both halves, which are dissected in turn down to leaves of at most
   leaf_size() nodes.  This gives the separator tree: tree node t (numbered
   in post-order, children before parents) owns the contiguous columns
   [col_begin(t), col_end(t)) (the free components of its graph nodes, node
   by node, components in order), has parent(t) (-1 for a root) and the row
   set R_t = rows(t): the sorted columns of its ancestors that are coupled to
   its subtree, i.e. the off-diagonal rows of L in its columns.  The
   columns of L owned by t are a dense block L_t (block(t)) of m_t x n_t,
   m_t = n_t + |R_t|, n_t = col_end(t) - col_begin(t), column-major with
   leading dimension m_t: rows 0..n_t-1 are the columns of t (lower
   triangle used, the strict upper triangle holds zeros), rows n_t..m_t-1
   are R_t in order.

   Factorisation (factorise): multifrontal.  In post-order, the frontal
   matrix of t (lower triangle, over t's columns followed by R_t) receives
   the springs' entries in t's columns and the update matrices of t's
   children (extend-add); its first n_t columns are factorised (blocked
   right-looking dense Cholesky: panel factorisation, then a packed 4 x 4
   register-blocked symmetric rank-k update of the trailing matrix), they
   are L_t, and the trailing |R_t| x |R_t| Schur complement goes on a stack
   to t's parent.

   Solve: forward substitution over the blocks in post-order (triangular
   solve with the diagonal block, then the rectangle's product scattered
   into R_t), back substitution in reverse order.

   Rank-one change (modify): K + sign k g g^T with g nonzero on the columns
   of the spring's two nodes only.  The classic column-by-column
   update/downdate (for each column j: r = sqrt(L_jj^2 + sign x_j^2),
   c = r / L_jj, s = x_j / L_jj, L_jj = r, L_ij = (L_ij + sign s x_i) / c,
   x_i = c x_i - s L_ij; x = sqrt(k) g) changes only the columns where x
   is nonzero, which lie in the tree nodes on the union of the two paths
   from the nodes' blocks to the root: the cost is the size of the blocks
   on that path, not of the factor.

   Threads (set_threads, default 1): factorise() and solve() run disjoint
   subtrees of the separator tree at the same time; modify() is one path and
   stays serial.  The plan (made by analyse() and set_threads()) picks task
   roots by splitting the costliest subtree greedily, from the roots of the
   forest down to at most 64 tasks, and keeps the split of least estimated
   time (the tree nodes above the tasks, "the top", on one thread; the tasks
   dealt to the threads by decreasing cost); solve() and factorise() have
   their own plans (costs: the block entries m_t n_t; the flops).  Each task
   is a range [first_descendant(r), r] of the post-order.  The threads are a
   small pool kept by the object (set_threads() starts them; they wait on a
   condition variable between calls, so a call costs no thread start-up).
     Results are bit-identical for any number of threads (and to the serial
   code): every floating-point operation, and for every variable the order of
   the operations on it, is that of the serial post-order sweep.
   - forward: a task's blocks add their products into the rows of R_t inside
     the task's subtree (only that task writes them, in post-order); the rows
     of R_t above the task (the suffix of R_t beyond col_end(r), the top's
     columns) are kept in a buffer per tree node.  Then one thread walks the
     post-order: a top node's forward_block, a task node's kept products added
     into the top's rows.  Each entry of w therefore receives its additions in
     the serial order.
   - back: the top in reverse post-order on one thread, then the tasks: a
     block reads w on R_t (final) and writes its own columns only.
   - factorise: a task runs the multifrontal sweep of its subtree with its own
     frontal matrix and update stack, and leaves its root's update matrix in a
     buffer.  The top is then factorised in post-order on the calling thread,
     the children's update matrices extend-added in the serial order; the
     symmetric rank-k update of a large front is split into disjoint row
     blocks over the threads (every 4 x 4 block of C is formed by one kernel
     call over the whole k range and subtracted once, whoever computes it).
     A pivot that fails in a task is reported when the walk reaches the task:
     the error is the serial one (the first bad pivot in post-order).
   Small problems (a plan with one task, or below a minimum of work) run on
   the calling thread alone.  solve() may still be called from several
   threads at once (the pool takes one call's tasks at a time);
   set_threads() not while another call runs.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_SPARSE_CHOLESKY_H
#define LMP_LATTICE_SPARSE_CHOLESKY_H

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

// one central spring: K += k g g^T, g = -n on node a's components, +n on
// node b's (held components dropped)
struct LatticeSpring {
  int a, b;
  double k;
  double n[3];
};

class LatticeThreadPool;    // lattice_sparse_cholesky.cpp

class LatticeSparseCholesky {
 public:
  LatticeSparseCholesky();
  ~LatticeSparseCholesky();
  LatticeSparseCholesky(const LatticeSparseCholesky &) = delete;
  LatticeSparseCholesky &operator=(const LatticeSparseCholesky &) = delete;

  // threads of factorise() and solve() (default 1; results bit-identical for
  // any number); std::invalid_argument below 1.  Any time (the plan is remade)
  void set_threads(int n);
  int threads() const { return threads_; }
  // the pool of those threads (nullptr for one thread): its user may run other loops on it
  // between the factor's calls (lattice_thread_pool.h)
  LatticeThreadPool *pool() const { return pool_.get(); }
  // tasks (subtrees run in parallel) of the current plans; 0: the call runs serially
  int solve_tasks() const { return (int) solve_plan_.roots.size(); }
  int factorise_tasks() const { return (int) factor_plan_.roots.size(); }

  // largest number of graph nodes in a leaf of the dissection (default 8);
  // before analyse(); std::invalid_argument below 1
  void set_leaf_size(int nodes);
  int leaf_size() const { return leaf_size_; }

  // ordering + symbolic analysis.  coords: dim per node (dim = 2 or 3);
  // free[dim*node + c] != 0 if component c of node is an unknown (else held:
  // not in the matrix); pairs: every (a,b) that may ever carry a spring (the
  // pattern: later factorise()/modify() springs must be among them).
  // std::invalid_argument for a bad dim, size, or node index.
  void analyse(int dim, int nnodes, const double *coords, const std::vector<unsigned char> &free,
               const std::vector<std::pair<int, int>> &pairs);

  // numeric factorisation of K = sum_s k_s g_s g_s^T + shift * I (on the
  // free components).  shift > 0 keeps K definite when part of the network
  // comes loose.  std::runtime_error (naming the node and component) if a
  // pivot is not positive, or naming a spring whose pair is not in the
  // pattern or whose k or n is not finite; the factor is then unusable
  // (factorised() false) until a successful factorise().
  void factorise(const std::vector<LatticeSpring> &springs, double shift);

  // x := K^-1 x in place; x has dim*nnodes entries indexed dim*node + c;
  // held entries untouched.  std::logic_error before a factorise().
  void solve(double *x) const;

  // the steps of solve() one block at a time, on a vector w in column order (ncols()
  // entries, w[col_of_dof(dof)]); scratch: max_rows() doubles.  forward_block(t):
  // w[cols of t] := L11^-1 w[cols of t], then w[R_t] -= L21 w[cols of t]; back_block(t):
  // w[cols of t] := L11^-T (w[cols of t] - L21^T w[R_t]).  Forward over t = 0, 1, ...
  // then back over t = ntree()-1, ..., 0 is solve(); after the forward sweep, the back
  // steps of the path from t to its root give w on the columns of t and its ancestors only
  // (back_block needs w final on R_t).  After a factorise(); no checks.
  void forward_block(int t, double *w, double *scratch) const;
  void back_block(int t, double *w, double *scratch) const;
  int max_rows() const { return (int) max_rows_; }    // the largest m_t

  // K := K + sign k g g^T (sign +1 adds a spring, -1 removes one): rank-one
  // update/downdate of the factor along the elimination-tree path only.
  // std::runtime_error if the pair is not in the pattern, k or n is not
  // finite (the factor is then unchanged), or a downdate makes K indefinite (a
  // pivot not positive: the downdate restores the columns it changed, the factor
  // is unchanged), or an update overflows (then factorised() is false).
  // std::invalid_argument for sign not +-1.
  void modify(const LatticeSpring &s, int sign);

  double factor_entries() const;    // stored entries of L (lower triangles + rectangles)
  std::size_t bytes() const;        // memory of the factor and its indices
  std::size_t work_bytes() const;   // peak scratch of factorise (frontal + update stack)
  bool factorised() const { return factorised_; }

  // ---- read-only view of the structure (valid after analyse) ----
  int dim() const { return dim_; }
  int nnodes() const { return nnodes_; }
  int ncols() const { return ncols_; }    // free components = order of the matrix
  // column of component c of node (dof = dim*node + c), -1 if held
  int col_of_dof(int dof) const { return dof_col_[dof]; }
  int dof_of_col(int col) const { return col_dof_[col]; }
  int tree_of_col(int col) const { return col_tree_[col]; }
  int ntree() const { return (int) tree_.size(); }    // tree nodes, post-order
  int parent(int t) const { return tree_[t].parent; }
  int col_begin(int t) const { return tree_[t].col0; }
  int col_end(int t) const { return tree_[t].col0 + tree_[t].ncol; }
  int nrows(int t) const { return tree_[t].nrow; }    // |R_t|
  const int *rows(int t) const { return rows_.data() + tree_[t].rows_off; }
  // L_t: (n_t + |R_t|) x n_t, column-major, leading dimension n_t + |R_t|
  const double *block(int t) const { return factor_.data() + tree_[t].block_off; }
  int nchildren(int t) const { return child_off_[t + 1] - child_off_[t]; }
  int child(int t, int q) const { return child_[child_off_[t] + q]; }    // ascending in q
  // post-order: the subtree of t is the tree nodes [first_descendant(t), t], and its
  // columns are [col_begin(first_descendant(t)), col_end(t))
  int first_descendant(int t) const { return first_desc_[t]; }
  int depth() const { return depth_; }    // tree nodes on the longest leaf-to-root path
  // the tree nodes whose blocks a modify() of a spring between nodes a and b
  // changes: the union of the two paths to the root, ascending
  std::vector<int> path(int a, int b) const;

 private:
  struct TreeNode {
    int col0 = 0, ncol = 0, nrow = 0, parent = -1, nchild = 0;
    std::size_t rows_off = 0, block_off = 0;
  };

  // subtrees run in parallel: roots ascending, task_of[t] (-1: the top), the order
  // of execution (by decreasing cost); solve: defer_off[t], the offset of t's kept
  // products for the top's rows (a prefix sum over the tree nodes)
  struct Plan {
    std::vector<int> roots, task_of, order;
    std::vector<std::size_t> defer_off;
    std::size_t stack = 0, front = 0;    // factorise: the largest update stack, front of a task
  };
  struct Front;    // factorise's frontal matrix, update stack and scratch (one per thread)

  int leaf_size_ = 8;
  int threads_ = 1;
  std::unique_ptr<LatticeThreadPool> pool_;
  Plan solve_plan_, factor_plan_;
  int dim_ = 0, nnodes_ = 0, ncols_ = 0, depth_ = 0;
  bool factorised_ = false;
  std::vector<int> dof_col_, col_dof_, col_tree_;
  std::vector<int> adj_off_, adj_;    // pattern, per node, sorted
  std::vector<TreeNode> tree_;
  std::vector<int> rows_;
  std::vector<int> child_off_, child_, first_desc_;
  std::vector<double> factor_;
  std::size_t factor_size_ = 0, max_front_ = 0, max_stack_ = 0, max_rows_ = 0;
  std::vector<double> xwork_;    // modify(): the changing vector, zero between calls
  std::vector<double> backup_;   // modify(): the columns a downdate changes, until it succeeds

  void dissect(std::vector<int> &nodes, const double *coords, std::vector<int> &mark,
               int &stamp, std::vector<int> &roots, std::vector<int> &node_tree);
  int add_tree_node(const std::vector<int> &nodes, const std::vector<int> &children,
                    std::vector<int> &node_tree);
  void symbolic();
  void make_plans();
  Plan make_plan(const std::vector<double> &cost, double top_weight, double min_cost) const;
  int factor_node(int t, Front &fr, const std::vector<LatticeSpring> &springs, const int *off,
                  const int *bucket, double shift, LatticeThreadPool *pool, double &pivot);
  void forward_rows(int t, double *w, double *scratch, int nrow_w, double *kept) const;
  bool in_pattern(int a, int b) const;
  const double *load_block(int t, const double *w, double *y, bool rows_too, int &n, int &m) const;
  int spring_vector(const LatticeSpring &s, int *cols, double *vals) const;
  void check_spring(const LatticeSpring &s, const char *what) const;
  [[noreturn]] void pivot_error(int col, double pivot, const char *what) const;
};

}    // namespace LAMMPS_NS

#endif
