/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Local relaxation of a network of central springs (lattice/quasistatic
   relax local): multicolour successive over-relaxation on a work queue.

   Only particles whose largest free force component exceeds the tolerance
   are moved, each by omega times the Newton step of its own springs
   (x += omega D^-1 f, D = sum of Kn n n^T over its records plus Kn Xn / r
   (I - n n^T) over its intact bonds in tension), no further than the pass's
   displacement budget; a move puts
   the particle's neighbours on the queue.  A broken spring therefore costs
   work in the region whose forces it changes by more than the tolerance,
   not in the whole box.  The particles are coloured (Jones-Plassmann, by a
   hash of their IDs) so that no two of one colour share a spring: the
   particles of one colour move together, which is Gauss-Seidel in colour
   order on any number of ranks.

   The energy of central springs is a function of the positions, and each
   move lowers it for 0 < omega < 2 (D bounds each particle's stiffness), so
   the relaxation ends at the equilibrium of the network to the tolerance,
   as the minimiser does.  Fixes that hold force components at zero (fix
   setforce 0.0, fix enforce2d) hold those components; other fixes that act
   in a minimisation are refused.  docs/lattice_quasistatic.rst.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_LOCAL_RELAX_H
#define LMP_LATTICE_LOCAL_RELAX_H

#include "lattice_comm.h"
#include "pointers.h"

#include <vector>

namespace LAMMPS_NS {

class PairLatticeBond;
enum class BreakMode : unsigned char;    // fix_lattice_bond_store.h

class LatticeLocalRelax : protected Pointers, public LatticeForwardPart, public LatticeReversePart {
 public:
  LatticeLocalRelax(class LAMMPS *, PairLatticeBond *pair, double ftol, double omega);

  // refuses what the method cannot treat (an error naming it); before set_up
  void check_model();
  // before each force evaluation that precedes set_up: which components the
  // fixes hold (an error for a fix that does anything else); collective
  void probe_fixes();
  // after a force evaluation (run 0: ghosts, records and partner indices
  // current): the springs, their stiffness blocks, the colours, the held
  // components and the forces; collective
  void set_up();

  enum class Outcome { RELAXED, MOVED_FAR, SWEEPS };
  // sweeps until no free force component exceeds ftol (RELAXED), or some
  // particle moved more than the displacement budget since set_up (MOVED_FAR:
  // a force evaluation must refresh ghosts and records first), or after
  // maxsweeps sweeps; counts sweeps and particle moves (all ranks); collective
  Outcome relax(bigint maxsweeps, bigint &sweeps, bigint &moves);

  // the intact spring with the largest ratio to its threshold (ties: lowest
  // IDs), over all ranks; collective
  double worst(tagint &owner, tagint &partner, BreakMode &mode);
  // break the spring owner-partner (found by worst) in the given mode; the
  // forces it no longer carries are applied by the next relax; collective
  void break_spring(tagint owner, tagint partner, BreakMode mode);
  // break every intact spring whose ratio exceeds 1 (break all); counts by
  // mode over all ranks; collective
  bigint break_beyond_threshold(int &tension, int &shear);
  // largest free force component (as the minimiser's norm max); collective
  double largest_force();

  // the most a particle may move between force evaluations (set_up)
  double displacement_budget() const { return budget; }

  int pack_forward(int n, const int *list, double *buf) override;
  void unpack_forward(int n, int first, const double *buf) override;
  int pack_reverse(int n, int first, double *buf) override;
  void unpack_reverse(int n, const int *list, const double *buf) override;

 private:
  PairLatticeBond *pair;
  double ftol, omega, budget;

  // one record of a local owner whose partner is present (local or ghost)
  struct Spring {
    int i, j, slot;       // owner (local), partner (local or ghost), record slot of the owner
    double kn, touch, xb, fs0, mu_p;
    double f[3];          // its force on the owner now
    bool intact;
  };
  std::vector<Spring> springs;
  std::vector<int> adj_start, adj;    // springs of each atom (local and ghost), CSR
  std::vector<double> stiff;          // per local atom: D as xx, yy, zz, xy, xz, yz
  std::vector<double> fnet;           // per local atom: 3 components (all springs)
  std::vector<double> ghost_force;    // per ghost: forces of local springs, to send
  std::vector<double> disp;           // per atom: displacement since set_up (ghosts: received)
  std::vector<unsigned char> held;    // per local atom: bit k = component k held at zero
  std::vector<tagint> held_ids;       // probe_fixes: ID, bits of every particle holding some
  std::vector<int> colour;            // per atom (ghosts: received)
  int ncolours;
  std::vector<std::vector<int>> queue;    // per colour: local atoms to look at
  std::vector<unsigned char> queued;      // per local atom
  std::vector<int> moved;                 // atoms (local and ghost) moved in this phase
  std::vector<unsigned> stamp;            // per spring: last phase that recomputed it
  unsigned phase_stamp;
  // the ratio tournament: tree[1] is the spring with the largest ratio
  std::vector<double> ratio;
  std::vector<int> tree;
  int leaves;
  std::vector<int> dirty;                 // springs whose ratio changed since the tree was
  std::vector<unsigned char> is_dirty;    // brought up to date (worst)
  double max_move;                        // largest displacement of a local atom since set_up
  int communicate = 1;                    // 0: one rank without ghosts, nothing to send

  enum class Comm { DISP, FORCE, COLOUR, STIFF } comm_mode;
  int stiff_part;                         // STIFF: which 3 of the 6 components

  void build_springs();
  void build_colours();
  // force on the owner and ratio to the threshold (-1 if not intact) at the
  // current positions
  double spring_force(const Spring &s, double *f, BreakMode &mode) const;
  double force_only(const Spring &s, double *f) const;    // returns the stretch Xn
  void recompute(int k);
  void add_force(int a, const double *df);
  void enqueue(int a);
  bool free_force_above(int a) const;
  void move(int a);
  void displace(int a, const double *dx, int n);
  void exchange_forces();
  bool better(int a, int b) const;
  void tree_update(int k);
};

}    // namespace LAMMPS_NS

#endif
