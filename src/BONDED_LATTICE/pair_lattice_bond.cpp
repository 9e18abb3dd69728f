/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Design (see docs/design.md):
   - Every bond or contact is one record (spring, partner tag, state) stored
     on the particle with the lower tag, kept by the companion fix LATTICE/BOND/STORE that
     migrates it with the atom.  The owner's rank computes the force, applies
     it to both particles and relies on reverse communication (newton on).
   - Bonds are created once, at the first run, from the full neighbour list.
   - Per step the force loop visits records only; the neighbour list is used
     at reneighbouring to find the partners' local indices and to collect
     unbonded pairs close enough to touch before the next reneighbouring
     (LatticeBondRecords).
   This file: the settings, coefficients, init, compute (the step's order of
   work), the communication the parts share, and restart and data files.
------------------------------------------------------------------------- */

#include "pair_lattice_bond.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "group.h"
#include "lammps_api_compat.h"
#include "lattice_bond_records.h"
#include "lattice_heterogeneity.h"
#include "lattice_rotation_fit.h"
#include "lattice_time_step.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

static constexpr double DEFAULT_TOLERANCE = 0.01;
static constexpr int DEFAULT_MAXSLOT = 16;
static constexpr double BIG = 1.0e300;
// 2D: |z| beyond this fraction of the smallest radius is off the plane, not round-off
static constexpr double PLANE_TOLERANCE = 1.0e-9;

/* ---------------------------------------------------------------------- */

PairLatticeBond::PairLatticeBond(LAMMPS *lmp) :
    Pair(lmp), params(nullptr), bondable(nullptr), coeff_set(nullptr),
    tolerance(DEFAULT_TOLERANCE), maxslot(DEFAULT_MAXSLOT), cut_user(0.0), diameter(0.0),
    cut_global(0.0),
    fix_store(nullptr), hetero(new LatticeHeterogeneity(lmp)),
    time_step(new LatticeTimeStep(lmp)), records(new LatticeBondRecords(lmp, *hetero, *time_step)),
    rotation_fit(new LatticeRotationFit(lmp)), forward_part(nullptr), reverse_part(nullptr),
    min_radius(0.0), equal_radius(0.0), shear_pairs(SHEAR_PAIRS_SOME), any_friction(1),
    uniform_params(0), tally_flag(0), breaking_enabled(true)
{
  shear_frame = SHEAR_FRAME_FIXED;
  heat[0] = heat[1] = heat[2] = 0.0;
  single_enable = 0;
  restartinfo = 1;
  writedata = 1;
  finitecutflag = 1;
  centroidstressflag = CENTROID_SAME;
  comm_forward = 3;    // the particles' displacements (or rotations, or heterogeneity
                       // properties) this step, to the ghosts
  comm_reverse = 1;    // bond stiffness summed per particle (critical time step); more for
                       // the sums of the rotation fit with shear_frame corotational
  store_id = "LATTICE_BOND_STORE";
}

/* ---------------------------------------------------------------------- */

PairLatticeBond::~PairLatticeBond()
{
  if (copymode) return;
  // the records belong to this pair style: switching to another pair style drops them
  if (modify && modify->nfix && modify->get_fix_by_id(store_id)) modify->delete_fix(store_id);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(params);
    memory->destroy(bondable);
    memory->destroy(coeff_set);
  }
  delete records;
  delete rotation_fit;
  delete time_step;
  delete hetero;
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(params, n, n, "pair:params");
  memory->create(bondable, n, n, "pair:bondable");
  memory->create(coeff_set, n, n, "pair:coeff_set");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      // setflag is always 1 so that init_style, not Pair::init(), reports a
      // missing pair_coeff with the offending type pair
      setflag[i][j] = 1;
      coeff_set[i][j] = 0;
      bondable[i][j] = 1;
      params[i][j] = {0.0, 0.0, 0.0, 0.0, 0.0};
    }
}

/* ----------------------------------------------------------------------
   pair_style lattice/bond [tolerance t] [maxslot n] [cutoff rc] [diameter D]
                           [shear_frame fixed|corotational]
                           [stiffness d_name] [grain i_name]
                           [strength min max] [strength_factor d_name]
                           [seed n] [boundary_strength f]
------------------------------------------------------------------------- */

void PairLatticeBond::settings(int narg, char **arg)
{
  // a repeated pair_style command changes only the keywords it gives (also
  // after read_restart), like the other settings
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style lattice/bond keyword {} needs a value", key);
    if (const int words = hetero->parse_keyword(narg, arg, iarg)) {
      iarg += words;
      continue;
    }
    if (key == "tolerance") {
      tolerance = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (tolerance < 0.0 || tolerance >= 0.4)
        error->all(FLERR, "pair_style lattice/bond tolerance {} is out of range: need 0 <= tolerance < 0.4",
                   tolerance);
    } else if (key == "maxslot") {
      const int n = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (n < 1 || n > MAX_RECORDS)
        error->all(FLERR, "pair_style lattice/bond maxslot {} is out of range: need 1 <= maxslot <= {}",
                   n, MAX_RECORDS);
      maxslot = n;
    } else if (key == "cutoff") {
      cut_user = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (cut_user <= 0.0)
        error->all(FLERR, "pair_style lattice/bond cutoff {} must be > 0", cut_user);
    } else if (key == "diameter") {
      const double d = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(d > 0.0) || !std::isfinite(d))
        error->all(FLERR, "pair_style lattice/bond diameter {} is out of range: need a finite "
                   "diameter > 0 (distance units; the diameter of every particle)", d);
      diameter = d;
    } else if (key == "shear_frame") {
      const std::string value = arg[iarg + 1];
      if (value == "fixed") shear_frame = SHEAR_FRAME_FIXED;
      else if (value == "corotational") shear_frame = SHEAR_FRAME_COROTATIONAL;
      else
        error->all(FLERR, "pair_style lattice/bond shear_frame {} is not valid: use fixed or "
                   "corotational", value);
    } else {
      error->all(FLERR, "Unknown pair_style lattice/bond keyword {}: valid are tolerance, maxslot, "
                 "cutoff, diameter, shear_frame, stiffness, grain, strength, strength_factor, seed, "
                 "boundary_strength", key);
    }
    iarg += 2;
  }
  hetero->check_keywords();
  if (!allocated && domain->box_exist) allocate();
}

/* ----------------------------------------------------------------------
   pair_coeff I J Kn Ks Xb Fs0 mu_p [bond yes|no]
------------------------------------------------------------------------- */

void PairLatticeBond::coeff(int narg, char **arg)
{
  if (narg != 7 && narg != 9)
    error->all(FLERR, "pair_coeff for lattice/bond needs: I J Kn Ks Xb Fs0 mu_p [bond yes|no] "
               "(got {} arguments)", narg);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  BondParams p;
  p.kn = utils::numeric(FLERR, arg[2], false, lmp);
  p.ks = utils::numeric(FLERR, arg[3], false, lmp);
  p.xb = utils::numeric(FLERR, arg[4], false, lmp);
  p.fs0 = utils::numeric(FLERR, arg[5], false, lmp);
  p.mu_p = utils::numeric(FLERR, arg[6], false, lmp);

  const std::string which = fmt::format("pair_coeff {} {} (lattice/bond)", arg[0], arg[1]);
  if (!(p.kn > 0.0)) error->all(FLERR, "{}: Kn = {} is out of range: need Kn > 0 (force/distance)", which, p.kn);
  if (!(p.ks >= 0.0)) error->all(FLERR, "{}: Ks = {} is out of range: need Ks >= 0 (force/distance)", which, p.ks);
  if (!(p.xb > 0.0)) error->all(FLERR, "{}: Xb = {} is out of range: need Xb > 0 (distance)", which, p.xb);
  if (!(p.fs0 >= 0.0)) error->all(FLERR, "{}: Fs0 = {} is out of range: need Fs0 >= 0 (force)", which, p.fs0);
  if (!(p.mu_p >= 0.0)) error->all(FLERR, "{}: mu_p = {} is out of range: need mu_p >= 0", which, p.mu_p);

  int bond = 1;
  if (narg == 9) {
    if (strcmp(arg[7], "bond") != 0)
      error->all(FLERR, "{}: unknown keyword {}: the only keyword is bond yes|no", which, arg[7]);
    bond = utils::logical(FLERR, arg[8], false, lmp);
  }

  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      params[i][j] = params[j][i] = p;
      bondable[i][j] = bondable[j][i] = bond;
      coeff_set[i][j] = coeff_set[j][i] = 1;
    }
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::init_style()
{
  // diameters: per atom (atom_style sphere) or one for all (keyword diameter), never both
  if (!atom->radius_flag && !(diameter > 0.0))
    error->all(FLERR, "pair_style lattice/bond: atom_style {} has no per-atom diameter: give the "
               "particles' diameter with the keyword diameter (pair_style lattice/bond diameter "
               "D ...), or use atom_style sphere", atom->get_style());
  if (atom->radius_flag && diameter > 0.0)
    error->all(FLERR, "pair_style lattice/bond: keyword diameter {} is only for atom styles without "
               "per-atom diameters (e.g. atom_style atomic). atom_style {} has them: the "
               "diameters come from the atoms (set ... diameter, or the data file); remove the "
               "keyword diameter", diameter, atom->get_style());
  // masses: per atom (atom_style sphere) or per type (mass command)
  if (!atom->rmass_flag) {
    if (!atom->mass)
      error->all(FLERR, "pair_style lattice/bond needs particle masses: atom_style {} has neither "
                 "per-atom nor per-type masses", atom->get_style());
    for (int t = 1; t <= atom->ntypes; t++)
      if (!atom->mass_setflag[t])
        error->all(FLERR, "pair_style lattice/bond needs particle masses: type {} has no mass; set "
                   "it with the mass command (mass {} value)", t, t);
  }
  if (force->newton_pair == 0)
    error->all(FLERR, "pair_style lattice/bond requires newton on (or newton on off): each bond is "
               "computed once and its force reaches the partner by reverse communication");
  if (!allocated) error->all(FLERR, "pair_style lattice/bond has no pair_coeff: give one for every type pair");

  ensure_atom_map();
  hetero->find();

  // which physics the type pairs use: the force loop is compiled for it
  const int nt = atom->ntypes;
  int n_shear = 0, n_pairs = 0;
  any_friction = 0;
  uniform_params = 1;
  const BondParams &p11 = params[1][1];
  for (int i = 1; i <= nt; i++)
    for (int j = i; j <= nt; j++) {
      if (!coeff_set[i][j])
        error->all(FLERR, "pair_style lattice/bond: pair_coeff {} {} is missing; every type pair "
                   "needs Kn Ks Xb Fs0 mu_p", i, j);
      const BondParams &p = params[i][j];
      n_pairs++;
      if (p.ks > 0.0) n_shear++;
      if (p.mu_p > 0.0) any_friction = 1;
      if (p.kn != p11.kn || p.ks != p11.ks || p.xb != p11.xb || p.fs0 != p11.fs0 ||
          p.mu_p != p11.mu_p)
        uniform_params = 0;
    }
  shear_pairs = (n_shear == 0) ? SHEAR_PAIRS_NONE
      : (n_shear == n_pairs)   ? SHEAR_PAIRS_ALL
                               : SHEAR_PAIRS_SOME;

  // cutoff: the longest bond that can exist (2 * largest radius, plus tolerance)
  const double maxrad = measure_radii();
  if (atom->natoms > 0 && maxrad <= 0.0)
    error->all(FLERR, "pair_style lattice/bond: all particles have zero diameter; set diameters "
               "(the bond rest length is r_i + r_j)");
  if (domain->dimension == 2) check_plane();
  const double cut_auto = 2.0 * maxrad * (1.0 + tolerance);
  if (cut_user > 0.0) {
    if (cut_user < cut_auto)
      error->all(FLERR, "pair_style lattice/bond cutoff {} is too small: bonds reach {} "
                 "(2 * largest radius * (1 + tolerance)); use cutoff >= {}", cut_user, cut_auto, cut_auto);
    cut_global = cut_user;
  } else {
    cut_global = cut_auto > 0.0 ? cut_auto : 1.0;
  }

  // ghosts' sums of the rotation fit travel back to their owners
  comm_reverse = (shear_frame == SHEAR_FRAME_COROTATIONAL)
      ? LatticeRotationFit::reverse_values(domain->dimension) : 1;

  acquire_store();

  // a half list that holds each local-ghost pair on both ranks: the rank of
  // the lower tag finds every pair it must own (half the memory of a full list)
  neighbor->add_request(this, NeighConst::REQ_NEWTON_OFF);
}

/* ----------------------------------------------------------------------
   the particles' radii over all ranks, in one reduction: returns the
   largest; sets min_radius (smallest positive radius, instability test) and
   equal_radius.  Equal particles (the lattice model's own case) take a force
   loop without the per-partner radius: equal_radius is their radius, or 0 if
   radii differ or a fix adapt may change them during a run.  With the
   keyword diameter every particle has radius D/2 (no per-atom radius)
------------------------------------------------------------------------- */

double PairLatticeBond::measure_radii()
{
  if (diameter > 0.0) {
    min_radius = equal_radius = 0.5 * diameter;
    return equal_radius;
  }
  // max radius, -(smallest positive radius), -(smallest radius), -(lowest ID
  // of an atom without a valid radius: zero, negative or not finite)
  double range[4] = {0.0, -BIG, -BIG, -BIG}, range_all[4];
  for (int i = 0; i < atom->nlocal; i++) {
    const double r = atom->radius[i];
    range[0] = MAX(range[0], r);
    if (r > 0.0) range[1] = MAX(range[1], -r);
    range[2] = MAX(range[2], -r);
    if (!(r > 0.0 && std::isfinite(r))) range[3] = MAX(range[3], -(double) atom->tag[i]);
  }
  MPI_Allreduce(range, range_all, 4, MPI_DOUBLE, MPI_MAX, world);
  if (range_all[3] > -BIG) {
    // the owner tells the others the radius (an error is certain)
    const tagint bad = (tagint) -range_all[3];
    double r = 0.0, r_all = 0.0;
    for (int i = 0; i < atom->nlocal; i++)
      if (atom->tag[i] == bad) r = atom->radius[i];
    MPI_Allreduce(&r, &r_all, 1, MPI_DOUBLE, MPI_SUM, world);
    error->all(FLERR, "pair_style lattice/bond: atom {} has diameter {}; every particle needs a "
               "finite diameter > 0 (the rest length of a bond is r_i + r_j). Set it with set "
               "atom {} diameter D, set type ... diameter D or in the data file's Atoms section",
               bad, 2.0 * r_all, bad);
  }
  min_radius = (range_all[1] > -BIG) ? -range_all[1] : 0.0;
  const bool adapt = !modify->get_fix_by_style("^adapt").empty();
  equal_radius = (range_all[0] > 0.0 && range_all[0] == -range_all[2] && !adapt) ? range_all[0] : 0.0;
  return range_all[0];
}

/* ----------------------------------------------------------------------
   2D: every particle in the plane z = 0.  LAMMPS checks this only where atoms
   are made (create_atoms, read_data); set ... z, fix move and others can
   move an atom off the plane.  The neighbour search and the bonding use 3D
   distances, so such an atom silently loses its bonds and contacts.
   Round-off is allowed: |z| up to PLANE_TOLERANCE of the smallest radius
   (it changes a distance by less than 1e-18 relative).  Called in init_style
   after measure_radii(); collective
------------------------------------------------------------------------- */

void PairLatticeBond::check_plane()
{
  const double zmax = PLANE_TOLERANCE * min_radius;
  double worst = -BIG, worst_all = -BIG;    // -(lowest ID off the plane)
  for (int i = 0; i < atom->nlocal; i++)
    if (!(std::fabs(atom->x[i][2]) <= zmax)) worst = MAX(worst, -(double) atom->tag[i]);
  MPI_Allreduce(&worst, &worst_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (worst_all <= -BIG) return;
  const tagint bad = (tagint) -worst_all;
  double z = 0.0, z_all = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->tag[i] == bad) z = atom->x[i][2];
  MPI_Allreduce(&z, &z_all, 1, MPI_DOUBLE, MPI_SUM, world);
  error->all(FLERR, "pair_style lattice/bond: atom {} is at z = {}, off the plane of this 2d "
             "simulation: 2d particles must have z = 0 (within {:.3g}, round-off). LAMMPS checks "
             "z only when atoms are made (create_atoms, read_data), not after set ... z, fix move "
             "or similar commands; an atom off the plane loses its bonds and contacts. Put it back "
             "with set atom {} z 0.0", bad, z_all, zmax, bad);
}

/* ---------------------------------------------------------------------- */

PairLatticeBond::Radii PairLatticeBond::radii() const
{
  if (diameter > 0.0) return {nullptr, 0.5 * diameter};
  return {atom->radius, 0.0};
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::ensure_atom_map()
{
  records->ensure_atom_map();
}

/* ----------------------------------------------------------------------
   the companion fix that keeps the records; created at the first run (or by
   read_lattice_bonds) so that a fix restored by read_restart picks up its
   per-atom data
------------------------------------------------------------------------- */

FixLatticeBondStore *PairLatticeBond::acquire_store()
{
  fix_store = dynamic_cast<FixLatticeBondStore *>(modify->get_fix_by_id(store_id));
  if (!fix_store)
    fix_store = dynamic_cast<FixLatticeBondStore *>(
        modify->add_fix(fmt::format("{} all LATTICE/BOND/STORE {}", store_id, maxslot)));
  if (!fix_store) error->all(FLERR, "pair_style lattice/bond could not create its record store");
  if (fix_store->maxslot() != maxslot) fix_store->set_maxslot(maxslot);
  records->attach(fix_store);
  return fix_store;
}

/* ---------------------------------------------------------------------- */

double PairLatticeBond::init_one(int i, int j)
{
  params[j][i] = params[i][j];
  bondable[j][i] = bondable[i][j];
  return cut_global;
}

/* ----------------------------------------------------------------------
   the pair style of this package in use: lattice/bond, or lattice/bond/omp
   (`-sf omp`, `package omp`), alone or as a sub-style of pair hybrid
------------------------------------------------------------------------- */

PairLatticeBond *PairLatticeBond::find(Force *force)
{
  for (const char *name : {"lattice/bond", "lattice/bond/omp"})
    if (auto *pair = dynamic_cast<PairLatticeBond *>(force->pair_match(name, 1))) return pair;
  return nullptr;
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  bool rebuilt = (neighbor->ago == 0);
  if (!fix_store->bonds_created()) {
    records->create_bonds(list, radii(), {bondable, params, tolerance});
    rebuilt = true;
  }
  // 2D records read from a bond file or an older restart file hold vectors
  const bool convert = domain->dimension == 2 &&
      fix_store->shear_layout() == FixLatticeBondStore::SHEAR_VECTOR;
  hetero->fetch();
  if (rebuilt && hetero->enabled()) hetero->share_ghosts(*this);
  if (rebuilt || convert) refresh_partners();
  if (rebuilt && update->setupflag && !skin_advised) advise_on_skin();
  if (update->setupflag && !fixes_advised) advise_on_fixes();
  if (convert) records->planar_springs_from_vectors();

  // each particle's displacement over this step, ghosts included; outside
  // setup (where a user may have moved atoms between runs) a step longer than
  // a tenth of a radius stops an unstable run before it writes NaN
  const bool setup = update->setupflag;
  // (a minimiser's line search may try long steps: no test there)
  const bool minimizing = (update->whichflag == 2);
  // (fix lattice/nve may have measured the steps already, testing them against step_limit)
  fix_store->publish_step_limit(LatticeTimeStep::step_limit(min_radius));
  const int runaway = fix_store->update_displacements(
      (setup || minimizing) ? 0.0 : fix_store->step_limit());
  // (only the owner knows, and no collective is added to every step for it:
  // report_instability makes sure its message reaches the user, lattice_errors.h)
  if (runaway >= 0) time_step->report_instability(fix_store, runaway, min_radius);
  comm->forward_comm(this);
  // unbonded pairs that came into contact in this step (after the displacements
  // are known on the ghosts too: they bound which pairs can touch)
  if (records->has_candidates())
    records->detect_new_contacts(radii(), fix_store->displacements(), atom->nlocal + atom->nghost);
  if (setup) time_step->check(*this, *this);
  if (corotational())
    rotation_fit->fit(fix_store, records->partner_index(), records->stride(), *this);

  // each scene runs a force loop compiled for the physics it uses
  run_force_loop();

  // the displacements the store formed give way to the positions again
  fix_store->end_evaluation();
  if (vflag_fdotr && !virial_in_threads) virial_fdotr_compute();
}

/* ----------------------------------------------------------------------
   once per simulation, at the first setup with candidates collected: a skin
   much longer than this model needs gives every particle tens of unbonded
   candidate pairs (the second and third neighbour shells) and long
   neighbour lists.  The candidates cost nothing while the block deforms
   elastically (detect_new_contacts), but every step once particles have
   moved far, so the user gets the line that avoids it.  Collective
------------------------------------------------------------------------- */

void PairLatticeBond::advise_on_skin()
{
  skin_advised = true;
  bigint local = records->candidate_count();    // not const: the MPI stubs take void *
  bigint total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  const double d = 2.0 * min_radius;
  const double per_particle = atom->natoms > 0 ? (double) total / (double) atom->natoms : 0.0;
  // a skin of d/10 leaves an intact lattice with no candidates at all; warn when
  // the skin is several times that and the particles have candidates to show for it
  if (comm->me == 0 && d > 0.0 && neighbor->skin > 0.3 * d && per_particle >= 1.0)
    error->warning(FLERR,
                   "pair_style lattice/bond: the neighbor skin {:.6g} is {:.2g} particle diameters, "
                   "so each particle has {:.1f} unbonded pairs to watch for new contacts (none "
                   "with a skin of a tenth of a diameter in an intact lattice). They cost little "
                   "while the particles stay close to their places, but every step once they "
                   "have moved far, and the neighbor lists are long. For this model add: "
                   "neighbor {:.3g} bin",
                   neighbor->skin, neighbor->skin / d, per_particle, 0.1 * d);
}

/* ----------------------------------------------------------------------
   once per simulation, at the first setup: LAMMPS' general fixes nve (with
   fix enforce2d in 2D) and viscous do what the package's fix lattice/nve and
   fix lattice/viscous do with the same arithmetic, in more passes over the
   atoms (fix nve integrates z too, enforce2d then zeroes it, and the record
   store forms each step's displacements in a pass of its own, which fix
   lattice/nve measures while it moves the atoms): the user gets the lines
   that replace them (docs/performance.md, "Decks users write")
------------------------------------------------------------------------- */

void PairLatticeBond::advise_on_fixes()
{
  fixes_advised = true;
  if (comm->me != 0) return;
  // 2D: the fix enforce2d that fix nve needs and fix lattice/nve does not
  std::string plane;
  if (domain->dimension == 2)
    for (const Fix *fix : modify->get_fix_list())
      if (utils::strmatch(fix->style, "^enforce2d")) plane = fix->id;
  std::string use;
  for (const Fix *fix : modify->get_fix_list()) {
    const std::string style = fix->style, group_name = group->names[fix->igroup];
    std::string line;
    if (style == "nve")
      line = fmt::format("'fix {} {} lattice/nve' (the same integration arithmetic{})", fix->id,
                         group_name, plane.empty() ? "" : fmt::format("; it integrates x and y "
                         "only, so fix {} has nothing left to do for its atoms", plane));
    else if (style == "viscous")
      line = fmt::format("'fix {} {} lattice/viscous' with the same gamma (one value for every "
                         "type)", fix->id, group_name);
    if (!line.empty()) use += (use.empty() ? "" : ", ") + line;
  }
  if (use.empty()) return;
  error->warning(FLERR,
                 "pair_style lattice/bond: fix nve and fix viscous move and damp these particles "
                 "as fix lattice/nve and fix lattice/viscous do, with the same arithmetic but "
                 "more passes over the atoms each step; fix lattice/nve also keeps the "
                 "displacements the force loop needs as it moves the atoms (docs/performance.md, "
                 "\"Decks users write\"). For this "
                 "model use: {}", use);
}

/* ----------------------------------------------------------------------
   after reneighbouring: each record's partner (collective), the radii of
   atoms created since (fix deposit, ...), then the unbonded pairs that may
   touch before the next rebuild
------------------------------------------------------------------------- */

void PairLatticeBond::refresh_partners()
{
  const Radii radius = radii();
  records->refresh_partners(radius, min_radius);
  measure_radii();
  records->collect_candidates(list, radius);
}

/* ----------------------------------------------------------------------
   shear_frame corotational (docs/pair_lattice_bond.rst, "Rigid rotation"):
   the pre-pass runs only when some type pair has a shear spring
------------------------------------------------------------------------- */

bool PairLatticeBond::corotational() const
{
  return shear_frame == SHEAR_FRAME_COROTATIONAL && shear_pairs != SHEAR_PAIRS_NONE;
}

/* ----------------------------------------------------------------------
   communication for a part (heterogeneity, rotation fit, time-step check):
   LAMMPS calls the pack and unpack methods below, which route to it
------------------------------------------------------------------------- */

void PairLatticeBond::carry_forward(LatticeForwardPart *part)
{
  forward_part = part;
  comm->forward_comm(this);
  forward_part = nullptr;
}

void PairLatticeBond::carry_reverse(LatticeReversePart *part, int values)
{
  if (values > 3 && values > comm_reverse)
    error->all(FLERR, "Internal error: a part of pair_style lattice/bond sends {} values per atom "
               "in reverse communication, more than 3 or comm_reverse {}", values, comm_reverse);
  reverse_part = part;
  comm->reverse_comm(this, MAX(values, comm_reverse));
  reverse_part = nullptr;
}

/* ----------------------------------------------------------------------
   forward communication: a part's values, or the pair's own: the step's
   displacements of the ghosts' owners, plus, for a ghost across a periodic
   boundary of a box that changed since the last force evaluation, the
   change of its periodic shift (a ghost is its owner plus a lattice vector
   of the box, which strains with the box: see FixLatticeBondStore::BoxStep)
------------------------------------------------------------------------- */

int PairLatticeBond::pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  if (forward_part) return forward_part->pack_forward(n, list, buf);
  const double *disp = fix_store->displacements();
  const int dim = domain->dimension;    // 2D: the force loop reads x and y only
  int m = 0;
  const FixLatticeBondStore::BoxStep &box = fix_store->box_step();
  if (pbc_flag && box.moved) {
    double shift[3];
    box.shift(pbc, shift);
    for (int k = 0; k < n; k++)
      for (int c = 0; c < dim; c++) buf[m++] = disp[3 * list[k] + c] + shift[c];
    return m;
  }
  for (int k = 0; k < n; k++)
    for (int c = 0; c < dim; c++) buf[m++] = disp[3 * list[k] + c];
  return m;
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::unpack_forward_comm(int n, int first, double *buf)
{
  if (forward_part) {
    forward_part->unpack_forward(n, first, buf);
    return;
  }
  double *disp = fix_store->displacements();
  const int dim = domain->dimension;
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int c = 0; c < dim; c++) disp[3 * i + c] = buf[m++];
}

/* ----------------------------------------------------------------------
   reverse communication: only parts sum values into the owners
------------------------------------------------------------------------- */

int PairLatticeBond::pack_reverse_comm(int n, int first, double *buf)
{
  if (!reverse_part) error->one(FLERR, "pair_style lattice/bond: internal error: reverse "
                                "communication without a part to carry");
  return reverse_part->pack_reverse(n, first, buf);
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::unpack_reverse_comm(int n, int *list, double *buf)
{
  if (!reverse_part) error->one(FLERR, "pair_style lattice/bond: internal error: reverse "
                                "communication without a part to carry");
  reverse_part->unpack_reverse(n, list, buf);
}

/* ----------------------------------------------------------------------
   settings: tolerance, then a negative settings format (files before the
   shear_frame keyword have maxslot >= 1 there), maxslot, cutoff, shear_frame;
   format 3 adds the heterogeneity keywords, format 4 the keyword diameter,
   format 5 the keyword strength_factor
------------------------------------------------------------------------- */

static constexpr int SETTINGS_FORMAT = 5;

void PairLatticeBond::write_restart_settings(FILE *fp)
{
  const int format = -SETTINGS_FORMAT;
  fwrite(&tolerance, sizeof(double), 1, fp);
  fwrite(&format, sizeof(int), 1, fp);
  fwrite(&maxslot, sizeof(int), 1, fp);
  fwrite(&cut_user, sizeof(double), 1, fp);
  fwrite(&shear_frame, sizeof(int), 1, fp);
  hetero->write_restart(fp);
  fwrite(&diameter, sizeof(double), 1, fp);
  hetero->write_restart_strength_factor(fp);
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::read_restart_settings(FILE *fp)
{
  // the second word: maxslot (format 1) or minus the format (2 and later)
  const auto known_format = [](int word) { return word <= -2 && word >= -SETTINGS_FORMAT; };
  int word = 0;
  if (comm->me == 0) {
    utils::sfread(FLERR, &tolerance, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &word, sizeof(int), 1, fp, nullptr, error);
    if (word > 0) {    // format 1: maxslot, cutoff; the papers' shear frame
      maxslot = word;
      shear_frame = SHEAR_FRAME_FIXED;
    } else if (known_format(word)) {
      utils::sfread(FLERR, &maxslot, sizeof(int), 1, fp, nullptr, error);
    }
    if (word > 0 || known_format(word))
      utils::sfread(FLERR, &cut_user, sizeof(double), 1, fp, nullptr, error);
    if (known_format(word))
      utils::sfread(FLERR, &shear_frame, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&word, 1, MPI_INT, 0, world);
  if (word <= 0 && !known_format(word))
    error->all(FLERR, "This restart file holds pair_style lattice/bond settings in format {} "
               "(a newer BONDED_LATTICE version); this version reads formats 1 to {}", -word,
               SETTINGS_FORMAT);
  // format 3: the heterogeneity keywords; older files have none
  hetero->read_restart(fp, word <= -3);
  // format 4: the keyword diameter; older files come from atom_style sphere
  diameter = 0.0;
  if (word <= -4) {
    if (comm->me == 0) utils::sfread(FLERR, &diameter, sizeof(double), 1, fp, nullptr, error);
    MPI_Bcast(&diameter, 1, MPI_DOUBLE, 0, world);
  }
  // format 5: the keyword strength_factor
  hetero->read_restart_strength_factor(fp, word <= -5);
  MPI_Bcast(&tolerance, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&maxslot, 1, MPI_INT, 0, world);
  MPI_Bcast(&cut_user, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&shear_frame, 1, MPI_INT, 0, world);
  if (shear_frame != SHEAR_FRAME_FIXED && shear_frame != SHEAR_FRAME_COROTATIONAL)
    error->all(FLERR, "This restart file holds an unknown pair_style lattice/bond shear_frame ({})",
               shear_frame);
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&coeff_set[i][j], sizeof(int), 1, fp);
      if (coeff_set[i][j]) {
        fwrite(&params[i][j], sizeof(BondParams), 1, fp);
        fwrite(&bondable[i][j], sizeof(int), 1, fp);
      }
    }
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int me = comm->me;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) utils::sfread(FLERR, &coeff_set[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&coeff_set[i][j], 1, MPI_INT, 0, world);
      if (coeff_set[i][j]) {
        if (me == 0) {
          utils::sfread(FLERR, &params[i][j], sizeof(BondParams), 1, fp, nullptr, error);
          utils::sfread(FLERR, &bondable[i][j], sizeof(int), 1, fp, nullptr, error);
        }
        MPI_Bcast(&params[i][j], 5, MPI_DOUBLE, 0, world);
        MPI_Bcast(&bondable[i][j], 1, MPI_INT, 0, world);
      }
    }
}

/* ----------------------------------------------------------------------
   write_data: coefficients only; the bond network lives in restart files
------------------------------------------------------------------------- */

void PairLatticeBond::warn_data_file_has_no_bonds()
{
  error->warning(FLERR, "write_data stores the pair_style lattice/bond coefficients but not the bond "
                 "network (intact and broken bonds, contacts, shear springs): a run from this data "
                 "file bonds all touching particles anew. Use write_restart to keep the network");
}

/* ----------------------------------------------------------------------
   "Pair Coeffs" section (write_data default): only I I pairs fit in it
------------------------------------------------------------------------- */

void PairLatticeBond::write_data(FILE *fp)
{
  warn_data_file_has_no_bonds();
  if (atom->ntypes > 1)
    error->warning(FLERR, "write_data writes only I I lattice/bond coefficients; use "
                   "'write_data file pair ij' to keep the I J ones");
  for (int i = 1; i <= atom->ntypes; i++) {
    const BondParams &p = params[i][i];
    lattice_print(fp, "{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}{}\n", i, p.kn, p.ks, p.xb, p.fs0,
                  p.mu_p, bondable[i][i] ? "" : " bond no");
  }
}

/* ----------------------------------------------------------------------
   "PairIJ Coeffs" section (write_data ... pair ij)
------------------------------------------------------------------------- */

void PairLatticeBond::write_data_all(FILE *fp)
{
  warn_data_file_has_no_bonds();
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      const BondParams &p = params[i][j];
      lattice_print(fp, "{} {} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}{}\n", i, j, p.kn, p.ks, p.xb,
                    p.fs0, p.mu_p, bondable[i][j] ? "" : " bond no");
    }
}

/* ---------------------------------------------------------------------- */

double PairLatticeBond::memory_usage()
{
  double bytes = Pair::memory_usage();
  bytes += records->memory_usage();
  bytes += hetero->memory_usage();
  bytes += rotation_fit->memory_usage();
  return bytes;
}
