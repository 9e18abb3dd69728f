/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Direct relaxation of a network of central springs (lattice/quasistatic
   relax direct): the seed's loop with each equilibrium solved exactly.

   The network of central springs is gathered to rank 0, which finds its
   equilibrium by Newton steps with a sparse Cholesky factor of the
   stiffness K = sum of Kn n n^T over the springs that carry force (intact
   bonds and closed contacts; LatticeSparseCholesky, nested dissection),
   plus, for the springs in tension of a particle whose step came out too
   long, the stiffness T / r (I - n n^T) their tension gives across them:
   u += K^-1 f(u), with f the force loop's forces for Ks = 0 at the
   displacements u, until no free force component exceeds ftol.  Between
   breaks at small strain the network is nearly linear, so one or two steps
   do.  It then breaks the intact spring with the largest ratio to its
   threshold (ties: the lowest owner and partner IDs) and finds the new
   equilibrium the same way: a spring that breaks, or a broken one that
   closes or opens as a contact, is a rank-one change of the factor, and the
   steps cost a solve each, not a factorisation.  When no spring exceeds its
   threshold the particles move by u and every rank breaks the records it
   owns; a force evaluation (run 0) then checks the end state with the pair
   style's own records (new contacts included), and another pass follows if
   a force still exceeds ftol or a bond its threshold.

   The factor is kept between passes and calls (in the pair style) while
   the atoms, the records and their stiffness are the same and no spring has
   turned far; breaks made elsewhere (a dynamic run between calls) become
   rank-one changes.  docs/lattice_quasistatic.rst.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_DIRECT_RELAX_H
#define LMP_LATTICE_DIRECT_RELAX_H

#include "lattice_sparse_cholesky.h"
#include "pointers.h"

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class PairLatticeBond;
enum class BreakMode : unsigned char;    // fix_lattice_bond_store.h

// what rank 0 keeps between passes and calls: the network the factor is of
struct LatticeDirectState {
  int dim = 0;
  std::vector<tagint> tags;                           // the nodes, by ID
  std::vector<std::pair<tagint, tagint>> keys;        // the springs (owner, partner IDs)
  std::vector<std::pair<int, int>> ends;              // their nodes
  std::vector<unsigned char> free;                    // free components (dim per node)
  std::vector<double> kn;                             // the springs' stiffness in the factor
  std::vector<double> n;                              // their directions in it (3 each)
  std::vector<unsigned char> in_factor;               // 1 if the factor holds the spring
  double shift = 0.0;
  LatticeSparseCholesky factor;
  bigint factorisations = 0;
  // the cost of a factorisation in solves (from the operation counts of the
  // ordering), and the Newton steps beyond the first of each equilibrium
  // since the factor was made: a new factor when they have cost as much
  double factor_in_solves = 0.0;
  double excess_steps = 0.0;
  // per spring, the stiffness across it that its tension gives, T / r, in the
  // factor as T / r (I - n n^T) with the spring's direction n there (0: none;
  // newton_step sets it, a factorisation clears it)
  std::vector<double> across;
};

class LatticeDirectRelax : protected Pointers {
 public:
  LatticeDirectRelax(class LAMMPS *, PairLatticeBond *pair, double ftol, int threads);

  // refuses what the method cannot treat (an error naming it)
  void check_model();
  // before the force evaluation that precedes pass(); collective
  void probe_fixes();

  struct Break {
    tagint owner, partner;
    BreakMode mode;
    double ratio;
  };
  struct Outcome {
    std::vector<Break> breaks;    // in the order they broke
    bigint solves = 0;            // Newton steps (one solve each)
    bigint changes = 0;           // springs that joined or left the factor
    bigint factorised = 0;        // numeric factorisations
    bool analysed = false;        // a new ordering (atoms or records changed)
    bool relinearise = false;     // an equilibrium took NEWTON_MAX steps: the pass ended
  };
  // after a force evaluation (run 0): one pass as described above, breaking
  // at most maxbreak bonds (-1: no limit), all past their threshold at once
  // with break_all; moves the particles and breaks the records; collective.
  // Rank 0 calls on_break for each break as it happens (a log that shows the
  // progress of a long avalanche)
  Outcome pass(bigint maxbreak, bool break_all,
               const std::function<void(const Break &)> &on_break);

 private:
  PairLatticeBond *pair;
  double ftol;
  int threads;    // of the factor's factorisations and solves, and of the loops over the network
  class LatticeThreadPool *pool = nullptr;    // the factor's (nullptr: one thread)
  mutable std::vector<double> scratch;        // a value per spring (energy_change)
  double max_step;    // the longest move of a particle in one Newton step
  double max_travel;  // the longest move of a particle in one pass (half the skin)
  std::vector<tagint> held_ids;    // probe_fixes: ID, bits of every particle holding some

  // the network on rank 0, in ID order: what a spring is, and apart from it (compact
  // arrays the loops stream) what changes during the pass
  struct Spring {
    int a, b;                 // nodes of owner and partner
    double d[3];              // owner-to-partner vector at the pass's start
    double touch;             // rest length
    double kn, xb, fs0, mu_p;
  };
  struct Network {
    int dim = 0;
    std::vector<tagint> tags;
    std::vector<double> coords;             // dim per node
    std::vector<unsigned char> free;        // dim per node
    std::vector<Spring> springs;
    std::vector<std::pair<tagint, tagint>> keys;
    std::vector<int> node_start, node_springs;    // the springs of each node (CSR)
    std::vector<unsigned char> node_owns;         // per entry: 1 if the node is the owner
    std::vector<unsigned char> intact;      // per spring
    std::vector<double> e;                  // per spring: stretch Xn at the displacements u
    std::vector<double> f;                  // 3 per spring: its force on the owner there
    bool current = false;                   // e and f are those at the current u
    // energy_change: stretches and forces at its displacements, which a Newton step
    // that ends there takes over (e and f then need no new evaluation)
    std::vector<double> e_trial, f_trial;
  };

  void gather(Network &net);    // collective; the network on rank 0
  // rank 0: the factor kept or made anew for the pass
  void prepare_factor(Network &net, LatticeDirectState &state, const std::vector<double> &u,
                      Outcome &out);
  void factorise(Network &net, LatticeDirectState &state, const std::vector<double> &u);
  // rank 0: stretches and free forces at u; returns the largest force component.
  // After break_loop has made the springs of each node (net.node_start, node_springs)
  double forces(Network &net, const std::vector<double> &u, std::vector<double> &f) const;
  // rank 0: the longest displacement of a node in v (dim per node); the nodes beyond
  // `beyond` in far, ascending, if far is given
  double longest_move(const Network &net, const std::vector<double> &v, double beyond,
                      std::vector<int> *far) const;
  // a spring's owner-to-partner vector d at the displacements u
  static void offset(const Spring &s, int dim, const std::vector<double> &u, double d[3]);
  // a spring's stretch and force on its owner (3 values) at u, for the intact flag given
  static void spring_state(const Spring &s, bool intact, int dim, const std::vector<double> &u,
                           double &e, double *f);
  // spring k's e and f brought to the current u
  static void update_spring(Network &net, size_t k, const std::vector<double> &u);
  // rank 0: the springs' energy at `to` minus at the last force evaluation (their e),
  // leaving the stretches and forces at `to` in e_trial, f_trial; the fraction of a
  // Newton step from u to take (at_trial: e_trial, f_trial are those at u + the
  // fraction x step)
  double energy_change(Network &net, const std::vector<double> &to) const;
  double step_length(Network &net, const std::vector<double> &u, const std::vector<double> &f,
                     const std::vector<double> &step, bool &at_trial) const;
  // rank 0: Gauss-Seidel moves of the particles whose force exceeds ftol, at most budget
  bool smooth(Network &net, std::vector<double> &u, std::vector<double> &f,
              bigint budget) const;
  // rank 0: u += K^-1 f, no particle moving more than max_step
  void newton_step(Network &net, LatticeDirectState &state, std::vector<double> &u,
                   const std::vector<double> &f, Outcome &out);
  // rank 0: Newton steps to ftol; false if they did not get there
  bool equilibrate(Network &net, LatticeDirectState &state, std::vector<double> &u, Outcome &out);
  // rank 0: the seed's loop
  void break_loop(Network &net, LatticeDirectState &state, std::vector<double> &u,
                  bigint maxbreak, bool break_all, Outcome &out,
                  const std::function<void(const Break &)> &on_break);
  double ratio(const Spring &s, double e, BreakMode &mode) const;
  LatticeSpring term(const LatticeDirectState &state, int k) const;
  // adds (sign 1) or removes (-1) the term across of stiffness kx for a spring of
  // direction n between nodes a and b; returns the rank-one changes made
  static int modify_across(LatticeDirectState &state, int a, int b, double kx, const double *n,
                           int sign);
};

}    // namespace LAMMPS_NS

#endif
