/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   pair_style lattice/bond: bonds between touching particles with a normal
   spring Kn that breaks in tension past Xb and an incremental shear spring
   Ks capped by the Coulomb limit Fs0 - mu_p*Fn; broken bonds and new
   contacts are repulsive-only frictional contacts.  Liu, Pollard & Shi
   (2013), Liu et al. (2017), Li et al. (2018).
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(lattice/bond,PairLatticeBond);
// clang-format on
#else

#ifndef LMP_PAIR_LATTICE_BOND_H
#define LMP_PAIR_LATTICE_BOND_H

#include "lattice_bond_geometry.h"
#include "lattice_bond_physics.h"
#include "lattice_comm.h"
#include "lattice_energy_source.h"
#include "pair.h"

#include <array>
#include <memory>
#include <string>
#include <utility>

// The force loop is compiled twice on x86-64 Linux, for the baseline instruction set
// (SSE2) and for AVX2, and the processor picks one when the plugin or LAMMPS is loaded
// (function multiversioning: GCC's and Clang's target_clones, an ifunc).  With AVX2 the
// batched square roots and divisions of the record geometry run four at a time.  Both
// do the same IEEE operations in the same order (no fused multiply-add: the sources are
// compiled with -ffp-contract=off, and the avx2 target does not enable FMA), so they
// give the same bits (bench/compare_bits.py; docs/performance.md, "The force loop for
// AVX2").  -DBONDED_LATTICE_NO_TARGET_CLONES builds the baseline loop only.
#if defined(__x86_64__) && defined(__linux__) && defined(__has_attribute) && \
    !defined(BONDED_LATTICE_NO_TARGET_CLONES)
#if __has_attribute(target_clones)
#define LB_LOOP_CLONES __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef LB_LOOP_CLONES
#define LB_LOOP_CLONES
#endif

namespace LAMMPS_NS {

class FixLatticeBondStore;
enum class BreakMode : unsigned char;    // fix_lattice_bond_store.h
class LatticeBondRecords;
class LatticeHeterogeneity;
class LatticeRotationFit;
class LatticeTimeStep;
struct LatticeDirectState;

// The pair style keeps the settings, the coefficients, init, compute and
// restart; its parts (each with its own file) are the records' lifecycle
// (LatticeBondRecords), heterogeneous rock (LatticeHeterogeneity), the
// corotational rotation fit (LatticeRotationFit) and the time-step check
// (LatticeTimeStep); the force loop is pair_lattice_bond_kernel.cpp, the
// query API for other styles pair_lattice_bond_query.cpp
class PairLatticeBond : public Pair, public LatticeCommCarrier, public LatticeEnergySource {
 public:
  PairLatticeBond(class LAMMPS *);
  // the pair style lattice/bond (or lattice/bond/omp) in use, nullptr if none
  static PairLatticeBond *find(class Force *force);
  ~PairLatticeBond() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void write_data(FILE *) override;
  void write_data_all(FILE *) override;
  double memory_usage() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  void carry_forward(LatticeForwardPart *part) override;
  void carry_reverse(LatticeReversePart *part, int values = 0) override;

  // ---- query API for other styles (pair_lattice_bond_query.cpp) ----

  // bond parameters of one type pair (SI: N/m, N/m, m, N, -)
  using BondParams = LatticeBondParams;
  // the parameters of the bond (or contact) between local or ghost atoms i
  // and j: their type pair's, scaled by the heterogeneity keywords if given
  BondParams bond_params(int i, int j) const;

  FixLatticeBondStore *store() const { return fix_store; }
  FixLatticeBondStore *acquire_store();    // find or create the record store
  void ensure_atom_map();                  // a tag -> index map, created if absent
  // local/ghost index of each record's partner, -1 if absent: record s of
  // atom i at partner_index()[i * partner_index_stride() + s]
  const int *partner_index() const;
  int partner_index_stride() const;
  // shear spring of record s of local atom i as a vector (2D stores a signed
  // length); false if a loaded 2D spring's partner is not on this rank
  bool shear_vector(int i, int s, double *out) const;

  // energy accounting (LatticeEnergySource): heat released on this rank since
  // the pair style was created, by breaking (normal springs: BREAK_NORMAL,
  // shear springs: BREAK_SHEAR) and friction (FRICTION), tallied only while
  // enabled; the records' elastic energy (local_elastic_energy on this rank)
  void enable_energy_tallies(bool on) override { tally_flag = on ? 1 : 0; }
  void add_energy_tallies(double *tally) const override
  {
    tally[BREAK_NORMAL] += heat[0];
    tally[BREAK_SHEAR] += heat[1];
    tally[FRICTION] += heat[2];
  }
  double elastic_energy() override
  {
    double local = local_elastic_energy(), all = 0.0;
    MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_SUM, world);
    return all;
  }
  double local_elastic_energy() const;

  // quasi-static loading (command lattice/quasistatic): breaking is switched
  // off while it relaxes; it breaks the most over-stressed bonds itself
  void enable_breaking(bool flag) { breaking_enabled = flag; }
  double break_ratio(int i, int s, BreakMode &mode) const { return bond_load(i, s, mode).ratio; }
  // record s of local atom i at the current positions: its parameters, length,
  // normal force (tension positive; 0 while an unbonded or broken pair is apart),
  // shear force and ratio to its breaking threshold (see break_ratio)
  struct BondLoad {
    BondParams p;
    double dist, fn, fs, ratio;
  };
  BondLoad bond_load(int i, int s, BreakMode &mode) const;
  // an intact record breaks in the given mode (nothing for BreakMode::None)
  void break_record(int i, int s, BreakMode mode);
  bool has_shear_springs() const;    // some type pair has Ks > 0
  double smallest_radius() const { return min_radius; }

  // the particles' radii (see LatticeRadii): per atom, or D/2 for all with the
  // keyword diameter D
  using Radii = LatticeRadii;
  Radii radii() const;
  double uniform_diameter() const { return diameter; }    // keyword diameter, 0 if not given
  // lattice/quasistatic relax direct: the network and its factor, kept (on
  // rank 0) from one call to the next (lattice_direct_relax.h)
  std::shared_ptr<LatticeDirectState> &direct_state() { return direct_cache; }

 protected:
  BondParams **params;
  int **bondable;      // 1 if touching particles of this type pair are bonded at the first run
  int **coeff_set;     // 1 if pair_coeff was given for this type pair
  double tolerance;    // bond if r < (ri + rj)(1 + tolerance) at the first run
  int maxslot;         // records per atom
  double cut_user;     // cutoff keyword, 0 = automatic
  double diameter;     // diameter keyword: every particle's diameter, 0 = per-atom radii
  double cut_global;
  // shear_frame keyword: increments of the shear springs measured in the fixed
  // frame (the papers) or relative to each particle's local rigid rotation
  enum { SHEAR_FRAME_FIXED = 0, SHEAR_FRAME_COROTATIONAL = 1 };
  int shear_frame;

  std::string store_id;
  FixLatticeBondStore *fix_store;

  // the parts
  LatticeHeterogeneity *hetero;       // keywords stiffness, grain, strength, seed
  LatticeTimeStep *time_step;         // critical time step, instability stop
  LatticeBondRecords *records;        // record lifecycle and the partner index
  LatticeRotationFit *rotation_fit;   // shear_frame corotational
  // the part whose values LAMMPS communicates now; null: the step's displacements
  LatticeForwardPart *forward_part;
  LatticeReversePart *reverse_part;

  double min_radius;                  // smallest particle radius (instability test)
  std::shared_ptr<LatticeDirectState> direct_cache;    // see direct_state()
  double equal_radius;                // the radius if all particles have it, else 0
  double measure_radii();    // largest radius; sets min_radius, equal_radius
  // physics used by the type pairs (init_style): selects the compiled force loop
  enum { SHEAR_PAIRS_NONE, SHEAR_PAIRS_SOME, SHEAR_PAIRS_ALL };
  int shear_pairs;                    // how many type pairs have Ks > 0
  int any_friction;                   // 1 if some type pair has mu_p > 0
  int uniform_params;                 // 1 if all type pairs have the same parameters
  int tally_flag;                     // 1: accumulate heat (compute lattice/energy)
  double heat[3];                     // see add_energy_tallies()
  bool breaking_enabled;              // see enable_breaking()
  // true in pair_style lattice/bond/omp, whose threads sum the f . r virial themselves
  bool virial_in_threads = false;

  void allocate();
  void warn_data_file_has_no_bonds();
  void check_plane();
  void refresh_partners();
  bool skin_advised = false;          // see advise_on_skin()
  void advise_on_skin();
  bool fixes_advised = false;        // see advise_on_fixes()
  void advise_on_fixes();
  bool corotational() const;          // the shear_frame corotational pre-pass runs this step

  // the force loop (pair_lattice_bond_kernel.cpp): compile-time features
  // (bits of its template argument)
  enum EvalFeature {
    LB_EV = 1,            // energy / virial tallies (thermo steps)
    LB_TALLY = 2,         // heat tallies of compute lattice/energy
    LB_PLANAR = 4,        // 2D: no z components
    LB_UNIFORM = 8,       // one parameter set for every type pair
    LB_SHEAR_ALL = 16,    // every type pair has a shear spring
    LB_SHEAR_SOME = 32,   // some type pairs have one (tested per record)
    LB_FRICTION = 64,     // some type pair has contact friction
    LB_EQUAL = 128,       // all particles have the same radius
    LB_COROTATE = 256,    // shear_frame corotational: remove the local rigid rotation
    LB_HETERO = 512,      // per-bond stiffness and strength factors (heterogeneous rock)
    LB_NFEATURES = 1024
  };
  // the largest maxslot: the force loop keeps per-record scratch of this size
  static constexpr int MAX_RECORDS = 64;
  using EvalFn = void (PairLatticeBond::*)();
  int scene_features() const;
  // the loop variant that runs feature set F (fewer variants than feature sets)
  static constexpr int loop_variant(int F);
  // the loop compiled for scene_features(); pair_style lattice/bond/omp runs it on threads
  virtual void run_force_loop();
  void check_spring_components() const;
  // the loop over the records of particles ifrom..ito-1 (pair_lattice_bond_eval.h)
  template <int F, class Sink> LB_LOOP_CLONES void eval(int ifrom, int ito, double (*f)[3], Sink &tally);
  // what the serial loop tallies: energy/virial into Pair's accumulators, heat into heat[]
  struct SerialTally {
    PairLatticeBond *style;
    void pair(int i, int j, int nlocal, double e, double fx, double fy, double fz, double dx,
              double dy, double dz)
    {
      style->ev_tally_xyz(i, j, nlocal, 1, e, 0.0, fx, fy, fz, dx, dy, dz);
    }
    void heat(double break_normal, double break_shear, double friction)
    {
      style->heat[0] += break_normal;
      style->heat[1] += break_shear;
      style->heat[2] += friction;
    }
  };
  template <int F> void eval_all();    // the serial loop: every local particle
  template <int F> static constexpr EvalFn eval_entry();
  template <std::size_t... I>
  static constexpr std::array<EvalFn, sizeof...(I)> make_eval_table(std::index_sequence<I...>);
  static const std::array<EvalFn, LB_NFEATURES> EVAL_TABLE;
};

}    // namespace LAMMPS_NS

#endif
#endif
