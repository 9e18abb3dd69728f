/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   The force loop of pair_style lattice/bond: the table that picks the
   variant of the loop for a step (scene_features, loop_variant) and the
   serial loop.  The loop itself, eval<F, Tally>, is in
   pair_lattice_bond_eval.h (shared with pair_style lattice/bond/omp); the
   physics of a record is in lattice_bond_physics.h, the corotational
   frame's per-record operations in lattice_rotation_fit.h, the bond factors
   of heterogeneous rock in lattice_heterogeneity.h; the partner index the
   loop reads is made by LatticeBondRecords after every reneighbouring.
------------------------------------------------------------------------- */

#include "pair_lattice_bond_eval.h"

#include "domain.h"
#include "error.h"

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   compile-time features of the force loop for this step.  The specialised
   loops skip work, never change arithmetic: every variant gives the same
   forces to the last bit, so thermo output (which needs the energy/virial
   variant) or an energy compute never perturbs a trajectory.  Steps that
   tally energy or virial take the general loop.
------------------------------------------------------------------------- */

int PairLatticeBond::scene_features() const
{
  // 2D records hold signed scalar springs: every 2D loop is planar
  const int planar = (domain->dimension == 2) ? LB_PLANAR : 0;
  const int corotate = corotational() ? LB_COROTATE : 0;
  const int hetero_bit = hetero->enabled() ? LB_HETERO : 0;
  // with the keyword diameter there is no per-atom radius to read: equal particles always
  const int equal = (diameter > 0.0) ? LB_EQUAL : 0;
  if (evflag)
    return LB_EV | LB_SHEAR_SOME | LB_FRICTION | planar | (tally_flag ? LB_TALLY : 0) | corotate |
        hetero_bit | equal;
  int features = planar | (tally_flag ? LB_TALLY : 0) | corotate | hetero_bit;
  if (uniform_params) features |= LB_UNIFORM;
  if (shear_pairs == SHEAR_PAIRS_ALL) features |= LB_SHEAR_ALL;
  else if (shear_pairs == SHEAR_PAIRS_SOME) features |= LB_SHEAR_SOME;
  if (any_friction) features |= LB_FRICTION;
  if (equal_radius > 0.0) features |= LB_EQUAL;
  return features;
}

/* the loop a feature combination runs (loop_variant): steps with energy/virial tallies
   (thermo output), and the combination that never occurs (both shear bits),
   use the general loop (for equal particles with the keyword diameter, which
   leaves no per-atom radius to read); heat tallies are specialised like plain
   steps.  Without shear springs contact friction changes nothing in the loop
   (FRICTION only selects the sliding of a spring), so those entries share the
   frictionless loop.  Every bit, made a runtime branch, cost the loop over 1%
   in 2D or 3D (docs/design.md, "What each template parameter is worth") */

template <int F> constexpr PairLatticeBond::EvalFn PairLatticeBond::eval_entry()
{
  return &PairLatticeBond::eval_all<loop_variant(F)>;
}

template <std::size_t... I>
constexpr std::array<PairLatticeBond::EvalFn, sizeof...(I)>
PairLatticeBond::make_eval_table(std::index_sequence<I...>)
{
  return {eval_entry<static_cast<int>(I)>()...};
}

const std::array<PairLatticeBond::EvalFn, PairLatticeBond::LB_NFEATURES>
    PairLatticeBond::EVAL_TABLE =
        PairLatticeBond::make_eval_table(std::make_index_sequence<LB_NFEATURES>{});

/* ----------------------------------------------------------------------
   the force loop compiled for the physics of this step
------------------------------------------------------------------------- */

void PairLatticeBond::run_force_loop()
{
  check_spring_components();
  (this->*EVAL_TABLE[scene_features()])();
}

/* ----------------------------------------------------------------------
   the springs are a signed length in 2D (compute() converts loaded vectors
   first) and a vector in 3D: what the loops compiled for 2D and 3D expect
------------------------------------------------------------------------- */

void PairLatticeBond::check_spring_components() const
{
  const int nc = (domain->dimension == 2) ? 1 : 3;
  if (fix_store->spring_components() != nc)
    error->one(FLERR, "pair_style lattice/bond: internal error: {} spring components, the loop "
               "expects {}", fix_store->spring_components(), nc);
}

/* ----------------------------------------------------------------------
   the serial loop: every local particle's records, forces into atom->f,
   energy/virial through Pair::ev_tally_xyz, heat into this style's tallies
------------------------------------------------------------------------- */

template <int F> void PairLatticeBond::eval_all()
{
  SerialTally tally{this};
  eval<F>(0, atom->nlocal, reinterpret_cast<double(*)[3]>(atom->f[0]), tally);
}

