/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Direct relaxation of a network of central springs (lattice/quasistatic
   relax direct): the seed's loop with each equilibrium solved exactly.

   Between breaks a network of central springs at small strain is linear:
   about the current positions the forces are f(u) = f0 - K u, with
   K = sum of Kn g g^T over the springs that carry force (intact bonds and
   closed contacts; g the spring's stretch gradient, -n on its owner and +n
   on its partner).  One pass gathers the network to rank 0, solves K u = f0
   with a sparse Cholesky factor (LatticeSparseCholesky, nested dissection),
   then breaks the intact spring with the largest ratio to its threshold
   (ties: the lowest owner and partner IDs), which is a rank-one downdate of
   the factor and one solve for the force the spring released, and so on
   until no spring exceeds its threshold.  A broken spring whose linear
   stretch closes becomes a contact (a rank-one update) and opens again the
   same way.  The particles then move by u, every rank breaks the records it
   owns, and a force evaluation checks the end state with the pair style's
   own forces and ratios: what the linear model left (second order in the
   displacements) is the next pass's right-hand side, so the passes are
   Newton steps with the linear stiffness and end when no force component
   exceeds ftol and no bond its threshold.

   The factor is kept between passes and calls (in the pair style) while
   the atoms and the records are the same; breaks made elsewhere (a dynamic
   run between calls) are applied as downdates.  docs/lattice_quasistatic.rst.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_DIRECT_RELAX_H
#define LMP_LATTICE_DIRECT_RELAX_H

#include "lattice_sparse_cholesky.h"
#include "pointers.h"

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class PairLatticeBond;
enum class BreakMode : unsigned char;    // fix_lattice_bond_store.h

// what rank 0 keeps between passes and calls: the network the factor is of
struct LatticeDirectState {
  std::vector<tagint> tags;                           // the nodes, by ID
  std::vector<std::pair<tagint, tagint>> keys;        // the springs (owner, partner IDs)
  std::vector<double> kn;                             // their stiffness in the factor
  std::vector<double> n;                              // their directions in it (3 each)
  std::vector<unsigned char> in_factor;               // 1 if the factor holds the spring
  std::vector<unsigned char> free;                    // free components (dim per node)
  int dim = 0;
  double shift = 0.0;
  LatticeSparseCholesky factor;
  bigint factorisations = 0;
};

class LatticeDirectRelax : protected Pointers {
 public:
  LatticeDirectRelax(class LAMMPS *, PairLatticeBond *pair);

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
    bigint solves = 0;
    bool factorised = false;
    double largest_move = 0.0;    // largest displacement component of the pass
  };
  // after a force evaluation (run 0): one pass as described above, breaking
  // at most maxbreak bonds (-1: no limit), all past their threshold at once
  // with break_all; moves the particles and breaks the records; collective
  Outcome pass(bigint maxbreak, bool break_all);

 private:
  PairLatticeBond *pair;
  std::vector<tagint> held_ids;    // probe_fixes: ID, bits of every particle holding some

  // the network on rank 0, in ID order
  struct Spring {
    int a, b;                 // nodes of owner and partner
    double n[3];              // unit vector from owner to partner
    double e0;                // stretch Xn at the pass's start
    double kn, xb, fs0, mu_p;
    bool intact;
    bool active;              // carries force in the linear model (intact or closed)
    double e;                 // stretch at the current solution
  };
  struct Network {
    int dim = 0;
    std::vector<tagint> tags;
    std::vector<double> coords;             // dim per node
    std::vector<double> force;              // dim per node (held components 0)
    std::vector<unsigned char> free;        // dim per node
    std::vector<Spring> springs;
    std::vector<std::pair<tagint, tagint>> keys;
  };

  void gather(Network &net);    // collective; the network on rank 0
  // rank 0: the factor of the network's active springs (kept or made anew)
  bool prepare_factor(Network &net, LatticeDirectState &state, bigint &solves);
  // rank 0: the seed's loop in the linear model
  void break_loop(Network &net, LatticeDirectState &state, std::vector<double> &u,
                  bigint maxbreak, bool break_all, Outcome &out);
  void stretches(Network &net, const std::vector<double> &u) const;
  // rank 0: contacts that closed or opened join or leave the factor, with the
  // solve of the force they change; false if nothing changed
  bool settle_contacts(Network &net, LatticeDirectState &state, std::vector<double> &u,
                       bigint &solves);
  void solve_released(Network &net, LatticeDirectState &state, std::vector<double> &u,
                      const std::vector<int> &changed, bigint &solves);
  double ratio(const Spring &s, BreakMode &mode) const;
  LatticeSpring term(const Spring &s) const;
};

}    // namespace LAMMPS_NS

#endif
