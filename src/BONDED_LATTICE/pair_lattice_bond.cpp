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
     unbonded pairs close enough to touch before the next reneighbouring.
------------------------------------------------------------------------- */

#include "pair_lattice_bond.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "lammps_api_compat.h"
#include "lattice_bond_physics.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace LAMMPS_NS::LatticeBondPhysics;

static constexpr double DEFAULT_TOLERANCE = 0.01;
static constexpr int DEFAULT_MAXSLOT = 16;
// a warning above this fraction of the critical time step (see check_time_step)
static constexpr double DT_SAFETY_FRACTION = 0.5;
// a particle moving more than this fraction of the smallest radius in one step
// means the integration has become unstable
static constexpr double STEP_LIMIT_FRACTION = 0.1;
static constexpr double BIG = 1.0e300;
// 2D: |z| beyond this fraction of the smallest radius is off the plane, not round-off
static constexpr double PLANE_TOLERANCE = 1.0e-9;
// at bonding (and for unbonded pairs at each reneighbouring) two atoms closer
// than this fraction of r_i + r_j are at the same position: coincident atoms
static constexpr double COINCIDENT_FRACTION = 1.0e-6;
// the deepest overlap a bondable pair may have at bonding, relative to r_i + r_j,
// when the bonding tolerance is smaller (tolerance 0: round-off only)
static constexpr double OVERLAP_FLOOR = 1.0e-6;
// branches of the force loop taken by few records (breaking, contacts, fast
// rotation): laid out off the straight path of an intact bond
#define RARE(cond) __builtin_expect(static_cast<bool>(cond), 0)
// the largest maxslot: the force loop keeps per-record scratch of this size
static constexpr int MAX_RECORDS = 64;
// records whose geometry the force loop forms in one pass (or one particle's, if more)
static constexpr int BATCH_RECORDS = 24;
// how many particles ahead the 3D force loop requests the records (4 to 16 measured
// alike), and from which size of the spring array on (below, the requests cost more
// than they save: 3D blocks of 11k particles (1.6 MB) lost 2-4%, 49k (7 MB) were
// unchanged, 203k (29 MB) gained 25-35%; docs/performance.md)
static constexpr int PREFETCH_AHEAD = 8;
static constexpr double PREFETCH_MIN_BYTES = 10.0e6;

// request the cache lines of bytes at p (for writing if write)
static inline void prefetch_bytes(const void *p, size_t bytes, bool write)
{
  const char *c = static_cast<const char *>(p);
  for (size_t b = 0; b < bytes; b += 64) {
    if (write) __builtin_prefetch(c + b, 1, 3);
    else __builtin_prefetch(c + b, 0, 3);
  }
}

// shear_frame corotational: a particle's fit of its rotation is used only when
// tr(S) tr(S^-1) <= this bound, S the sum of m m^T over its intact bonds (4 for
// an isotropic 2D and 9 for an isotropic 3D neighbourhood, 5.3 and 13.5 for the
// corner particles of hexagonal and fcc blocks; two bonds 11.5 degrees from
// collinear reach it in 2D); otherwise its rotation is taken as zero
static constexpr double ROTATION_FIT_CONDITION = 100.0;
static constexpr double ROTATION_FIT_DET_FLOOR = 1.0e-6;    // det S / (tr S)^3, 3D
static constexpr int FIT_VALUES_2D = 7;     // S: xx xy yy; B: xx xy yx yy
static constexpr int FIT_VALUES_3D = 15;    // S: xx xy xz yy yz zz; B: 9 values
// bonds between grains: this fraction of the intragranular strength (the
// Mike/Elle seed: "on average half")
static constexpr double DEFAULT_BOUNDARY_STRENGTH = 0.5;

/* ----------------------------------------------------------------------
   a uniform number in [0, 1) for the bond between the particles with tags a
   and b, the same for (a, b) and (b, a) and on every rank: splitmix64's
   finaliser over the seed and the two tags (a bijective mix per word, so no
   two bonds of a model share the input)
------------------------------------------------------------------------- */

static inline uint64_t mix64(uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

static inline double bond_uniform(bigint seed, tagint a, tagint b)
{
  const uint64_t lo = (uint64_t) (a < b ? a : b), hi = (uint64_t) (a < b ? b : a);
  const uint64_t golden = 0x9e3779b97f4a7c15ULL;
  const uint64_t z = mix64((mix64(mix64((uint64_t) seed + golden) ^ lo) + golden) ^ hi);
  return (double) (z >> 11) * 0x1.0p-53;    // the top 53 bits: every double in [0, 1) equally likely
}

/* ---------------------------------------------------------------------- */

PairLatticeBond::PairLatticeBond(LAMMPS *lmp) :
    Pair(lmp), params(nullptr), bondable(nullptr), coeff_set(nullptr),
    tolerance(DEFAULT_TOLERANCE), maxslot(DEFAULT_MAXSLOT), cut_user(0.0), diameter(0.0),
    cut_global(0.0),
    fix_store(nullptr), partner_idx(nullptr), partner_nmax(0), partner_stride(0), own_map(0), min_radius(0.0), equal_radius(0.0),
    dt_critical(0.0), shear_pairs(SHEAR_PAIRS_SOME),
    any_friction(1), uniform_params(0), tally_flag(0), spin(nullptr), spin_nmax(0),
    fit_values(0), comm_what(COMM_DISPLACEMENT), hetero_flag(0), strength_min(1.0),
    strength_max(1.0), boundary_strength(DEFAULT_BOUNDARY_STRENGTH), strength_seed(0),
    stiffness_index(-1), grain_index(-1), stiffness_factor(nullptr), grain_id(nullptr),
    breaking_enabled(true)
{
  shear_frame = SHEAR_FRAME_FIXED;
  heat[0] = heat[1] = heat[2] = 0.0;
  single_enable = 0;
  restartinfo = 1;
  writedata = 1;
  finitecutflag = 1;
  centroidstressflag = CENTROID_SAME;
  comm_forward = 3;    // the particles' displacements (or rotations) this step, to the ghosts
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
  memory->destroy(partner_idx);
  memory->destroy(spin);
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
                           [strength min max] [seed n] [boundary_strength f]
------------------------------------------------------------------------- */

void PairLatticeBond::settings(int narg, char **arg)
{
  // a repeated pair_style command changes only the keywords it gives (also
  // after read_restart), like the other settings
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style lattice/bond keyword {} needs a value", key);
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
    } else if (key == "stiffness" || key == "grain") {
      const std::string name = arg[iarg + 1];
      const char *prefix = (key == "stiffness") ? "d_" : "i_";
      if (name.size() < 3 || name.compare(0, 2, prefix) != 0)
        error->all(FLERR, "pair_style lattice/bond {} {}: give a per-atom property of fix "
                   "property/atom as {}name ({} per particle)", key, name, prefix,
                   key == "stiffness" ? "a floating-point stiffness factor" : "an integer grain ID");
      (key == "stiffness" ? stiffness_name : grain_name) = name.substr(2);
      hetero_flag = 1;
    } else if (key == "strength") {
      if (iarg + 2 >= narg)
        error->all(FLERR, "pair_style lattice/bond strength needs two values: min max");
      strength_min = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      strength_max = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (!(strength_min > 0.0) || !(strength_max >= strength_min))
        error->all(FLERR, "pair_style lattice/bond strength {} {} is out of range: need 0 < min "
                   "<= max (factors of the breaking force Kn*Xb and of Fs0)", strength_min,
                   strength_max);
      hetero_flag = 1;
      iarg += 1;
    } else if (key == "seed") {
      strength_seed = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (strength_seed <= 0)
        error->all(FLERR, "pair_style lattice/bond seed {} is out of range: need a positive integer",
                   strength_seed);
    } else if (key == "boundary_strength") {
      boundary_strength = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(boundary_strength > 0.0))
        error->all(FLERR, "pair_style lattice/bond boundary_strength {} is out of range: need > 0 "
                   "(a factor of the strength of bonds between different grains)", boundary_strength);
    } else {
      error->all(FLERR, "Unknown pair_style lattice/bond keyword {}: valid are tolerance, maxslot, "
                 "cutoff, diameter, shear_frame, stiffness, grain, strength, seed, boundary_strength", key);
    }
    iarg += 2;
  }
  if (strength_max > strength_min && strength_seed <= 0)
    error->all(FLERR, "pair_style lattice/bond strength {} {} draws a random strength per bond: "
               "give its seed (keyword seed, a positive integer)", strength_min, strength_max);
  if (boundary_strength != DEFAULT_BOUNDARY_STRENGTH && grain_name.empty())
    error->all(FLERR, "pair_style lattice/bond boundary_strength needs the keyword grain (which "
               "particles belong to which grain)");
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
  find_heterogeneity();

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
      ? (domain->dimension == 2 ? FIT_VALUES_2D : FIT_VALUES_3D) : 1;

  acquire_store();

  // a half list that holds each local-ghost pair on both ranks: the rank of
  // the lower tag finds every pair it must own (half the memory of a full list)
  neighbor->add_request(this, NeighConst::REQ_NEWTON_OFF);
}

/* ----------------------------------------------------------------------
   heterogeneity: the per-atom properties named by the keywords stiffness and
   grain (fix property/atom), checked on every run.  Their ghost values are
   sent by this style at every reneighbouring (refresh_partners), so the fix
   does not need "ghost yes"
------------------------------------------------------------------------- */

void PairLatticeBond::find_heterogeneity()
{
  stiffness_index = grain_index = -1;
  stiffness_factor = nullptr;
  grain_id = nullptr;
  if (!hetero_flag) return;
  auto lookup = [&](const std::string &name, int want_double) -> int {
    int flag = -1, cols = -1;
    const int index = atom->find_custom(name.c_str(), flag, cols);
    const char *what = want_double ? "d_" : "i_";
    if (index < 0)
      error->all(FLERR, "pair_style lattice/bond: per-atom property {}{} does not exist; define it "
                 "with fix property/atom {}{} before the run (and give its values, e.g. read_data "
                 "... fix ID NULL Section, or set)", what, name, what, name);
    if (flag != want_double || cols != 0)
      error->all(FLERR, "pair_style lattice/bond: per-atom property {} must be a single {} value "
                 "per atom ({}{})", name, want_double ? "floating-point" : "integer", what, name);
    return index;
  };
  if (!stiffness_name.empty()) {
    stiffness_index = lookup(stiffness_name, 1);
    stiffness_factor = atom->dvector[stiffness_index];
    for (int i = 0; i < atom->nlocal; i++)
      if (!(stiffness_factor[i] > 0.0) || !std::isfinite(stiffness_factor[i]))
        error->one(FLERR, "pair_style lattice/bond: atom {} has stiffness factor d_{} = {}; need a "
                   "finite value > 0 (it multiplies Kn and Ks)", atom->tag[i], stiffness_name,
                   stiffness_factor[i]);
  }
  if (!grain_name.empty()) {
    grain_index = lookup(grain_name, 0);
    grain_id = atom->ivector[grain_index];
    for (int i = 0; i < atom->nlocal; i++)
      if (grain_id[i] < 0)
        error->one(FLERR, "pair_style lattice/bond: atom {} has grain ID i_{} = {}; need >= 0",
                   atom->tag[i], grain_name, grain_id[i]);
  }
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::fetch_heterogeneity()
{
  stiffness_factor = (stiffness_index >= 0) ? atom->dvector[stiffness_index] : nullptr;
  grain_id = (grain_index >= 0) ? atom->ivector[grain_index] : nullptr;
}

/* ----------------------------------------------------------------------
   the bond's stiffness factor: the mean of its particles' factors (the
   average stiffness of two grains across their boundary)
------------------------------------------------------------------------- */

double PairLatticeBond::bond_stiffness_factor(int i, int j) const
{
  return stiffness_factor ? 0.5 * (stiffness_factor[i] + stiffness_factor[j]) : 1.0;
}

/* ----------------------------------------------------------------------
   the bond's strength factor: uniform in [strength_min, strength_max] per
   bond, times boundary_strength if the particles belong to different grains
------------------------------------------------------------------------- */

double PairLatticeBond::bond_strength_factor(int i, int j) const
{
  double g = strength_min;
  if (strength_max > strength_min)
    g += (strength_max - strength_min) * bond_uniform(strength_seed, atom->tag[i], atom->tag[j]);
  if (grain_id && grain_id[i] != grain_id[j]) g *= boundary_strength;
  return g;
}

/* ----------------------------------------------------------------------
   a bond's parameters: the type pair's; with heterogeneity the stiffnesses
   scale with the stiffness factor s, the breaking force Kn*Xb and the shear
   strength Fs0 with the strength factor g (so Xb becomes Xb g / s)
------------------------------------------------------------------------- */

static inline PairLatticeBond::BondParams scaled_params(const PairLatticeBond::BondParams &p,
                                                        double s, double g)
{
  return {p.kn * s, p.ks * s, p.xb * (g / s), p.fs0 * g, p.mu_p};
}

PairLatticeBond::BondParams PairLatticeBond::bond_params(int i, int j) const
{
  const BondParams &p = params[atom->type[i]][atom->type[j]];
  if (!hetero_flag) return p;
  return scaled_params(p, bond_stiffness_factor(i, j), bond_strength_factor(i, j));
}

/* ----------------------------------------------------------------------
   how close intact record s of local atom i is to breaking at the current
   positions and springs (as the last force evaluation left them): the larger
   of the tensile ratio Fn / (Kn Xb) = Xn / Xb and the shear ratio
   (Fs + mu_p Fn) / Fs0 (the Coulomb limit Fs <= Fs0 - mu_p Fn as a ratio;
   tensile_ratio and shear_ratio in lattice_bond_physics.h).  A bond breaks
   when it exceeds 1.  mode: LB_BROKEN_TENSION or LB_BROKEN_SHEAR, the larger
   one; 0 and LB_INTACT for other records
------------------------------------------------------------------------- */

PairLatticeBond::BondLoad PairLatticeBond::bond_load(int i, int s, int &mode) const
{
  mode = LB_INTACT;
  const int j = partner_idx ? partner_idx[(bigint) i * partner_stride + s] : -1;
  BondLoad load{bond_params(i, j >= 0 ? j : i), 0.0, 0.0, 0.0, 0.0};
  if (j < 0) return load;    // a broken bond whose particles are far apart
  double **x = atom->x;
  const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
  load.dist = sqrt(dx * dx + dy * dy + dz * dz);
  const Radii radius = radii();
  const double xn = normal_stretch(load.dist, radius[i] + radius[j]);
  const bool intact = (fix_store->states(i)[s] == LB_INTACT);
  if (!intact && contact_open(xn)) return load;    // an open contact carries no force
  const BondParams &p = load.p;
  load.fn = normal_force(p.kn, xn);
  load.fs = shear_force(p.ks, fix_store->spring_squared(i, s));
  if (!intact) return load;
  const double tension = tensile_ratio(xn, p.xb);
  const double shear = shear_ratio(load.fs, p.mu_p, load.fn, p.fs0);
  mode = (tension >= shear) ? LB_BROKEN_TENSION : LB_BROKEN_SHEAR;
  load.ratio = MAX(tension, shear);
  return load;
}

/* ---------------------------------------------------------------------- */

bool PairLatticeBond::has_shear_springs() const
{
  if (!allocated) return false;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (coeff_set[i][j] && params[i][j].ks > 0.0) return true;
  return false;
}

/* ----------------------------------------------------------------------
   break intact record s of local atom i in the given mode (lattice/quasistatic);
   the next force evaluation lets its springs go as the force loop does
------------------------------------------------------------------------- */

void PairLatticeBond::break_record(int i, int s, int mode)
{
  LatticeBondState &st = fix_store->states(i)[s];
  if (st == LB_INTACT) st = (LatticeBondState) mode;
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

/* ----------------------------------------------------------------------
   partners are found by tag: create the global-to-local map if the input
   did not ask for one (atom_modify map)
------------------------------------------------------------------------- */

void PairLatticeBond::ensure_atom_map()
{
  if (atom->map_style != Atom::MAP_NONE) return;
  if (atom->map_user == Atom::MAP_NONE) atom->map_user = Atom::MAP_YES;
  atom->map_init();
  atom->map_set();
  own_map = 1;
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
  if (fix_store->maxslot != maxslot) fix_store->set_maxslot(maxslot);
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
   a neighbour-list pair (a local, b local or ghost) seen from its owner:
   i = the particle with the lower tag, j = its partner.  False if the owner
   is a ghost: its own rank holds the pair as well and records it
------------------------------------------------------------------------- */

bool PairLatticeBond::owned_pair(int a, int b, int nlocal, const tagint *tag, int &i, int &j)
{
  if (tag[a] < tag[b]) {
    i = a;
    j = b;
    return true;
  }
  if (b < nlocal && tag[b] < tag[a]) {
    i = b;
    j = a;
    return true;
  }
  return false;
}

/* ----------------------------------------------------------------------
   visit(i, j) for every pair of the neighbour list seen from its owner
------------------------------------------------------------------------- */

template <typename Visit> void PairLatticeBond::for_each_owned_pair(Visit &&visit)
{
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  for (int ii = 0; ii < list->inum; ii++) {
    const int a = list->ilist[ii];
    if (a >= nlocal) continue;
    const int *jlist = list->firstneigh[a];
    for (int jj = 0; jj < list->numneigh[a]; jj++) {
      int i, j;
      if (owned_pair(a, jlist[jj] & NEIGHMASK, nlocal, tag, i, j)) visit(i, j);
    }
  }
}

/* ---------------------------------------------------------------------- */

bool PairLatticeBond::has_record_with(int i, tagint partner) const
{
  const tagint *pt = fix_store->partners(i);
  for (int s = 0; s < fix_store->nrec[i]; s++)
    if (pt[s] == partner) return true;
  return false;
}

/* ----------------------------------------------------------------------
   first run: every pair closer than (ri + rj)(1 + tolerance) becomes an
   intact bond, stored on the lower tag
------------------------------------------------------------------------- */

void PairLatticeBond::create_bonds()
{
  double **x = atom->x;
  const Radii radius = radii();
  int *type = atom->type;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;

  // two passes over the pairs: count each owner's bonds (an upper bound: images
  // of one partner in a small periodic box count twice), size the store for
  // the most any atom has (no growth while bonding), then create them
  std::vector<int> count(nlocal, 0);
  // bonds at either end, counted where both particles are local (interior
  // particles: exact): half the largest is the room a balanced numbering needs
  std::vector<int> coordination(nlocal, 0);
  bigint nbond_local = 0;
  // 2D springs are signed lengths: the store holds one component from the start
  if (domain->dimension == 2) fix_store->set_shear_layout(FixLatticeBondStore::SHEAR_PLANAR);
  for (int pass = 0; pass < 2; pass++) {
    for_each_owned_pair([&](int i, int j) {
      const double delx = x[i][0] - x[j][0], dely = x[i][1] - x[j][1], delz = x[i][2] - x[j][2];
      const double rsq = delx * delx + dely * dely + delz * delz;
      const bool bond_pair = bondable[type[i]][type[j]];
      if (pass == 0) check_overlap(i, j, rsq, bond_pair);
      if (!bond_pair) return;
      const double reach = (radius[i] + radius[j]) * (1.0 + tolerance);
      if (rsq >= reach * reach) return;
      if (pass == 0) {
        count[i]++;
        coordination[i]++;
        if (j < nlocal) coordination[j]++;
        return;
      }
      // in a small periodic box two images of one partner may be in range
      if (has_record_with(i, tag[j])) return;
      fix_store->add_record(i, tag[j], LB_INTACT);
      nbond_local++;
    });
    if (pass == 0) {
      int most = 0, most_all = 0;
      for (int i = 0; i < nlocal; i++) {
        if (count[i] + fix_store->nrec[i] > fix_store->maxslot)
          error->one(FLERR, "Atom {} has more than maxslot = {} bonds and contacts ({}); increase "
                     "the pair_style lattice/bond keyword maxslot", tag[i], fix_store->maxslot,
                     count[i] + fix_store->nrec[i]);
        most = MAX(most, count[i] + fix_store->nrec[i]);
      }
      MPI_Allreduce(&most, &most_all, 1, MPI_INT, MPI_MAX, world);
      fix_store->fit_capacity(most_all);
    }
  }
  bigint nbond = 0;
  MPI_Allreduce(&nbond_local, &nbond, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  fix_store->bonds_created = 1;
  // the exact room: contacts add more when they need it
  fix_store->fit_capacity(fix_store->global_max_records());
  int most_coord = 0, most_coord_all = 0;
  for (int i = 0; i < nlocal; i++) most_coord = MAX(most_coord, coordination[i]);
  MPI_Allreduce(&most_coord, &most_coord_all, 1, MPI_INT, MPI_MAX, world);
  if (comm->me == 0) {
    const double mean = atom->natoms ? 2.0 * nbond / atom->natoms : 0.0;
    utils::logmesg(lmp, "pair_style lattice/bond: created {} bonds between {} particles (mean "
                   "coordination {:.3f}); room for {} records per particle, {:.2f} used on "
                   "average\n", nbond, atom->natoms, mean, fix_store->capacity, 0.5 * mean);
    // each bond is stored on the lower ID: a numbering that is not row by row
    // (create_atoms with a multi-atom unit cell) gives some particles more
    // than half their bonds, and every particle that room
    const int balanced = (most_coord_all + 1) / 2;
    if (fix_store->capacity > balanced)
      utils::logmesg(lmp, "pair_style lattice/bond: the particle numbering gives some particles "
                     "{} records where {} would do; numbering them row by row (bonded-lattice "
                     "generate, or create_atoms with a one-atom primitive cell, 'lattice custom') "
                     "saves memory and time (docs/performance.md)\n", fix_store->capacity,
                     balanced);
  }
}

/* ----------------------------------------------------------------------
   pair i-j at bonding (rsq: squared distance): coincident atoms (no bond
   direction: NaN) are an error for any pair; a bondable pair must not
   overlap by more than the bonding tolerance (a bond starts at rest at
   r_i + r_j, where the lattice model's particles touch: a pair much closer
   than that has a wrong diameter or position and would start compressed)
------------------------------------------------------------------------- */

void PairLatticeBond::check_overlap(int i, int j, double rsq, bool bondable_pair)
{
  const Radii radius = radii();
  const double touch = radius[i] + radius[j];
  const double dist = sqrt(rsq);
  double **x = atom->x;
  const tagint *tag = atom->tag;
  if (dist < COINCIDENT_FRACTION * touch)
    error->one(FLERR, "pair_style lattice/bond: atoms {} and {} are at the same position ({} {} {}, "
               "distance {}): coincident atoms, made twice (two create_atoms commands or regions "
               "that overlap, a repeated line of a data file). Remove the copies, e.g. with "
               "delete_atoms overlap {} all all", tag[i], tag[j], x[i][0], x[i][1], x[i][2], dist,
               0.5 * touch);
  if (!bondable_pair) return;
  const double limit = MAX(tolerance, OVERLAP_FLOOR);
  if (dist >= touch * (1.0 - limit)) return;
  const double xb = params[atom->type[i]][atom->type[j]].xb;
  error->one(FLERR, "pair_style lattice/bond: atoms {} and {} overlap at bonding: their distance "
             "{:.6g} is {:.3g}% below r_i + r_j = {:.6g} (radii {:.6g} and {:.6g}), where bonded "
             "particles touch; the bond would start compressed by {:.3g} (Xb = {:.3g} of the type pair). Bonds are "
             "made between (r_i + r_j)(1 - t) and (r_i + r_j)(1 + t) = {:.6g} to {:.6g} (t = "
             "tolerance {}). Check the diameters (a particle too large for its lattice spacing) "
             "and the positions, or raise the pair_style keyword tolerance (< 0.4)",
             tag[i], tag[j], dist, 100.0 * (1.0 - dist / touch), touch, radius[i], radius[j],
             touch - dist, xb, touch * (1.0 - limit), touch * (1.0 + tolerance), tolerance);
}

/* ----------------------------------------------------------------------
   after reneighbouring: find each record's partner, drop contacts that have
   separated, collect unbonded pairs that may touch before the next rebuild
------------------------------------------------------------------------- */

void PairLatticeBond::refresh_partners()
{
  double **x = atom->x;
  const Radii radius = radii();
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;

  // the ghost shell every rank is guaranteed to hold: bonds must fit in it
  const double cutghost = comm->get_comm_cutoff();
  const double cutghost_sq = cutghost * cutghost;

  if (atom->nmax > partner_nmax || partner_stride != fix_store->capacity) {
    partner_nmax = atom->nmax;
    partner_stride = fix_store->capacity;
    memory->destroy(partner_idx);
    memory->create(partner_idx, (bigint) partner_nmax * partner_stride, "pair:partner_idx");
  }

  // a map made here, after the input's fixes: classes that cached the map style
  // when they were created (Irregular of fix balance) move atoms without
  // updating it, so it is rebuilt from the current local and ghost atoms
  if (own_map) {
    atom->map_clear();
    atom->map_set();
  }

  // records that cannot be used as they are: judged after the loop, over all
  // ranks, so that the message names the real cause (atoms lost from the box,
  // a runaway atom, renumbering) rather than the first symptom found
  RecordTrouble trouble;
  for (int i = 0; i < nlocal; i++) {
    const tagint *pt = fix_store->partners(i);
    const LatticeBondState *st = fix_store->states(i);
    int *idx = partner_idx + (bigint) i * partner_stride;
    // walk downwards so that swap-with-last removal only moves visited records
    for (int s = fix_store->nrec[i] - 1; s >= 0; s--) {
      // records live on the lower ID: a partner ID at or below the owner's
      // means the IDs changed after the record was made
      if (pt[s] <= tag[i]) {
        trouble.note(RecordTrouble::RENUMBERED, tag[i], pt[s], 0.0);
        idx[s] = -1;
        continue;
      }
      int j = atom->map(pt[s]);
      if (j >= 0) j = domain->closest_image(i, j);
      // a stale map entry (deleted atom) must not pass for the partner
      if (j >= 0 && tag[j] != pt[s]) j = -1;
      bool drop = false;
      if (j < 0) {
        if (st[s] == LB_INTACT) trouble.missing.push_back({i, pt[s]});
        drop = (st[s] == LB_CONTACT);
      } else {
        const double delx = x[i][0] - x[j][0], dely = x[i][1] - x[j][1], delz = x[i][2] - x[j][2];
        const double rsq = delx * delx + dely * dely + delz * delz;
        const double touch = radius[i] + radius[j];
        if (st[s] == LB_INTACT && rsq > cutghost_sq)
          trouble.note(RecordTrouble::TOO_LONG, tag[i], pt[s], sqrt(rsq));
        drop = (st[s] == LB_CONTACT && rsq >= touch * touch);
      }
      if (drop) {
        const int last = fix_store->nrec[i] - 1;
        fix_store->remove_record(i, s);
        if (s != last) idx[s] = idx[last];
      } else {
        idx[s] = j;
      }
    }
    if (hetero_flag) cache_bond_factors(i);
  }
  // one reduction per reneighbouring: the atom count (atoms lost from the box)
  // and the troubles of every rank
  bigint counts[4] = {nlocal, (bigint) trouble.missing.size(), trouble.count[RecordTrouble::RENUMBERED],
                      trouble.count[RecordTrouble::TOO_LONG]};
  bigint counts_all[4];
  MPI_Allreduce(counts, counts_all, 4, MPI_LMP_BIGINT, MPI_SUM, world);
  if (counts_all[1] + counts_all[2] + counts_all[3] > 0)
    settle_record_trouble(trouble, counts_all, cutghost);

  // atoms created since (fix deposit, ...) may differ in size
  measure_radii();

  // unbonded pairs within touching distance + skin: the only ones that can
  // come into contact before the next reneighbouring
  cand_i.clear();
  cand_j.clear();
  const double skin = neighbor->skin;
  for_each_owned_pair([&](int i, int j) {
    const double delx = x[i][0] - x[j][0], dely = x[i][1] - x[j][1], delz = x[i][2] - x[j][2];
    const double reach = radius[i] + radius[j] + skin;
    const double rsq = delx * delx + dely * dely + delz * delz;
    if (rsq >= reach * reach) return;
    if (has_record_with(i, tag[j])) return;
    // two atoms on top of each other would have no contact normal
    const double near = COINCIDENT_FRACTION * (radius[i] + radius[j]);
    if (rsq < near * near) check_overlap(i, j, rsq, false);
    cand_i.push_back(i);
    cand_j.push_back(j);
  });
}

/* ----------------------------------------------------------------------
   records refresh_partners() could not use, on any rank (counts_all: the
   atoms, the intact records whose partner is not here, the renumbered and
   the too long records, summed over the ranks).  Collective; runs only when
   one of those counts is nonzero.  In order:
   1. a partner ID at or below its owner's: the atoms were renumbered;
   2. a partner that is not here and exists nowhere while atoms were lost
      (fewer atoms than atom->natoms: LAMMPS deleted particles that left a
      non-periodic box): the bond went with the atom, the record is dropped
      and a warning says so; LAMMPS itself stops at the next thermo output
      with "Lost atoms" unless thermo_modify lost ignore or warn;
   3. stretched or missing partners during a run: an atom that moved more
      than the instability limit in this step is the cause (report_instability);
   4. the record's own message
------------------------------------------------------------------------- */

void PairLatticeBond::settle_record_trouble(RecordTrouble &trouble, const bigint *counts_all,
                                            double cutghost)
{
  using RT = RecordTrouble;
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;

  if (counts_all[2] > 0)
    error_from_any_rank(
        trouble.count[RT::RENUMBERED] > 0,
        fmt::format("pair_style lattice/bond: the atom IDs changed after the bonds were made: atom "
                    "{} holds the record of its bond to atom {}, but each record is kept on the "
                    "lower ID of its pair, by the IDs the particles had when the bond was made. "
                    "The particles were renumbered (reset_atoms id, or delete_atoms with its "
                    "default compress yes). Bond records name their partners by atom ID: "
                    "renumber before the first run or minimize, which makes the bonds, or not at "
                    "all (delete_atoms ... compress no keeps the IDs)",
                    trouble.owner[RT::RENUMBERED], trouble.partner[RT::RENUMBERED]));

  // partners that are neither local nor ghosts: do they exist on any rank?
  const bigint natoms_before = atom->natoms;
  const bigint natoms_now = counts_all[0];
  bigint dropped = 0;
  if (counts_all[1] > 0) {
    const int nprocs = comm->nprocs;
    const int nmine = (int) trouble.missing.size();
    std::vector<int> nper(nprocs), offset(nprocs, 0);
    MPI_Allgather(&nmine, 1, MPI_INT, nper.data(), 1, MPI_INT, world);
    for (int p = 1; p < nprocs; p++) offset[p] = offset[p - 1] + nper[p - 1];
    const int ntotal = offset[nprocs - 1] + nper[nprocs - 1];
    std::vector<tagint> mine(nmine), wanted(ntotal);
    for (int k = 0; k < nmine; k++) mine[k] = trouble.missing[k].second;
    MPI_Allgatherv(mine.data(), nmine, MPI_LMP_TAGINT, wanted.data(), nper.data(), offset.data(),
                   MPI_LMP_TAGINT, world);
    std::vector<int> here(ntotal), exists(ntotal);
    for (int k = 0; k < ntotal; k++) {
      const int m = atom->map(wanted[k]);
      here[k] = (m >= 0 && m < nlocal && tag[m] == wanted[k]) ? 1 : 0;
    }
    MPI_Allreduce(here.data(), exists.data(), ntotal, MPI_INT, MPI_MAX, world);
    const bool atoms_lost = natoms_now < natoms_before;
    for (int k = 0; k < nmine; k++) {
      const int i = trouble.missing[k].first;
      const tagint p = trouble.missing[k].second;
      if (exists[offset[comm->me] + k]) {
        trouble.note(RT::BEYOND, tag[i], p, 0.0);
      } else if (atoms_lost) {
        drop_record(i, p);
        dropped++;
      } else {
        trouble.note(RT::GONE, tag[i], p, 0.0);
      }
    }
    bigint dropped_all = 0;
    MPI_Allreduce(&dropped, &dropped_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    if (dropped_all > 0 && comm->me == 0)
      error->warning(FLERR, "pair_style lattice/bond: {} particles left the non-periodic box "
                     "and LAMMPS deleted them (Lost atoms: original {} current {}); their {} "
                     "intact bonds are removed. LAMMPS stops at the next thermo output unless "
                     "thermo_modify lost ignore or warn lets them go; to keep the particles, "
                     "make the box larger than the block of particles (LAMMPS deletes atoms that "
                     "cross a fixed boundary, boundary f) or use boundary s or m (shrink-wrapped)",
                     natoms_before - natoms_now, natoms_before, natoms_now, dropped_all);
  }

  bigint rest[3] = {trouble.count[RT::TOO_LONG], trouble.count[RT::BEYOND],
                    trouble.count[RT::GONE]};
  bigint rest_all[3];
  MPI_Allreduce(rest, rest_all, 3, MPI_LMP_BIGINT, MPI_SUM, world);
  if (rest_all[0] + rest_all[1] + rest_all[2] == 0) return;

  // an error is certain: during a run, a particle that moved too far in this
  // step (an unstable integration) is the cause, not the neighbour skin
  const bool setup = update->setupflag;
  if (!setup && update->whichflag != 2) {
    const int runaway = fix_store->update_displacements(STEP_LIMIT_FRACTION * min_radius);
    int any = (runaway >= 0) ? 1 : 0, any_all = 0;
    MPI_Allreduce(&any, &any_all, 1, MPI_INT, MPI_MAX, world);
    if (any) report_instability(runaway);
    // the rank(s) above stop the run
    if (any_all) MPI_Barrier(world);
  }

  std::string message;
  const char *when = setup
      ? "At the start of a run: atoms were moved by hand (displace_atoms, set, change_box "
        "without remap) or renumbered (reset_atoms id, delete_atoms ... compress yes) after the "
        "bonds were made, or the bond stretched that far in the previous run"
      : "The intact bond stretched that far in this run (raise neighbor skin or comm_modify "
        "cutoff)";
  if (trouble.count[RT::GONE])
    message = fmt::format("pair_style lattice/bond: bond {}-{} lost its partner: atom {} no longer "
                          "exists. It was deleted (delete_atoms, fix evaporate) or the atoms were "
                          "renumbered (reset_atoms id, delete_atoms ... compress yes) after the "
                          "bonds were made; deleting or renumbering bonded particles is not "
                          "supported",
                          trouble.owner[RT::GONE], trouble.partner[RT::GONE],
                          trouble.partner[RT::GONE]);
  else if (trouble.count[RT::TOO_LONG])
    message = fmt::format("pair_style lattice/bond: bond {}-{} is {} long, beyond the "
                          "communication cutoff {}. {}",
                          trouble.owner[RT::TOO_LONG], trouble.partner[RT::TOO_LONG],
                          trouble.length[RT::TOO_LONG], cutghost, when);
  else if (trouble.count[RT::BEYOND])
    message = fmt::format("pair_style lattice/bond: bond {}-{} is beyond the communication cutoff "
                          "{}: atom {} exists but is neither on this rank nor a ghost. {}",
                          trouble.owner[RT::BEYOND], trouble.partner[RT::BEYOND], cutghost,
                          trouble.partner[RT::BEYOND], when);
  error_from_any_rank(!message.empty(), message);
}

/* ----------------------------------------------------------------------
   remove the record of local atom i with the given partner
------------------------------------------------------------------------- */

void PairLatticeBond::drop_record(int i, tagint partner)
{
  const tagint *pt = fix_store->partners(i);
  int *idx = partner_idx + (bigint) i * partner_stride;
  for (int s = 0; s < fix_store->nrec[i]; s++)
    if (pt[s] == partner) {
      const int last = fix_store->nrec[i] - 1;
      fix_store->remove_record(i, s);
      if (s != last) idx[s] = idx[last];
      if (hetero_flag) cache_bond_factors(i);
      return;
    }
}

/* ----------------------------------------------------------------------
   collective: if some rank has a message (mine), every rank stops with the
   message of the lowest such rank (error->all: printed once, by rank 0);
   returns if none has one
------------------------------------------------------------------------- */

void PairLatticeBond::error_from_any_rank(bool mine, const std::string &message)
{
  const int nprocs = comm->nprocs;
  int rank = mine ? comm->me : nprocs, first = nprocs;
  MPI_Allreduce(&rank, &first, 1, MPI_INT, MPI_MIN, world);
  if (first >= nprocs) return;
  int len = (comm->me == first) ? (int) message.size() : 0;
  MPI_Bcast(&len, 1, MPI_INT, first, world);
  std::string text = (comm->me == first) ? message : std::string(len, ' ');
  MPI_Bcast(&text[0], len, MPI_CHAR, first, world);
  error->all(FLERR, text);
}

/* ----------------------------------------------------------------------
   the stiffness and strength factors of local atom i's records (see
   bond_factor); records without a partner here get 1, 1 (unused)
------------------------------------------------------------------------- */

void PairLatticeBond::cache_bond_factors(int i)
{
  const size_t need = (size_t) partner_nmax * partner_stride * 2;
  if (bond_factor.size() != need) bond_factor.assign(need, 1.0);
  const int *idx = partner_idx + (bigint) i * partner_stride;
  double *bf = bond_factor.data() + (size_t) i * partner_stride * 2;
  for (int s = 0; s < fix_store->nrec[i]; s++) {
    const int j = idx[s];
    bf[2 * s] = (j >= 0) ? bond_stiffness_factor(i, j) : 1.0;
    bf[2 * s + 1] = (j >= 0) ? bond_strength_factor(i, j) : 1.0;
  }
}

/* ----------------------------------------------------------------------
   2D: shear springs stored as vectors in the tangent plane (bond files,
   restart files of format 2) become signed lengths along t = z x n, with
   the sign of their projection on t and their length kept
------------------------------------------------------------------------- */

void PairLatticeBond::planar_springs_from_vectors()
{
  double **x = atom->x;
  // the signed length goes to component 0; set_shear_layout keeps only it
  const int nc = fix_store->ncomp;
  for (int i = 0; i < atom->nlocal; i++) {
    double *sp = fix_store->springs(i);
    const int *idx = partner_idx + (bigint) i * partner_stride;
    for (int s = 0; s < fix_store->nrec[i]; s++) {
      double *sh = sp + s * nc;
      const double len = sqrt(sh[0] * sh[0] + sh[1] * sh[1] + sh[2] * sh[2]);
      const int j = idx[s];
      double sig = 0.0;
      if (j >= 0 && len > 0.0) {
        const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1];
        // sign of s . t with t = (-dy, dx) / r: the length r does not matter
        sig = (dx * sh[1] - dy * sh[0] >= 0.0) ? len : -len;
      }
      sh[0] = sig;
    }
  }
  fix_store->set_shear_layout(FixLatticeBondStore::SHEAR_PLANAR);
}

/* ----------------------------------------------------------------------
   the shear spring of record s of local atom i as a vector (force on the
   owner -Ks times it): 2D springs are stored as signed lengths along
   t = z x n.  False if the partner of a loaded 2D spring is not on this
   rank (its direction is then unknown)
------------------------------------------------------------------------- */

bool PairLatticeBond::shear_vector(int i, int s, double *out) const
{
  const int nc = fix_store->ncomp;
  const double *sh = fix_store->springs(i) + s * nc;
  for (int k = 0; k < 3; k++) out[k] = (k < nc) ? sh[k] : 0.0;
  if (fix_store->shear_layout != FixLatticeBondStore::SHEAR_PLANAR || sh[0] == 0.0) return true;
  const tagint partner = fix_store->partners(i)[s];
  int j = atom->map(partner);
  if (j >= 0) j = domain->closest_image(i, j);
  if (j < 0 || atom->tag[j] != partner) return false;
  double **x = atom->x;
  const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1];
  const double rinv = 1.0 / sqrt(dx * dx + dy * dy);
  out[0] = -sh[0] * dy * rinv;
  out[1] = sh[0] * dx * rinv;
  out[2] = 0.0;
  return true;
}

/* ----------------------------------------------------------------------
   unbonded candidate pairs that now overlap become contact records
------------------------------------------------------------------------- */

void PairLatticeBond::detect_new_contacts()
{
  double **x = atom->x;
  const Radii radius = radii();
  tagint *tag = atom->tag;

  size_t c = 0;
  while (c < cand_i.size()) {
    const int i = cand_i[c], j = cand_j[c];
    const double delx = x[i][0] - x[j][0], dely = x[i][1] - x[j][1], delz = x[i][2] - x[j][2];
    const double touch = radius[i] + radius[j];
    if (delx * delx + dely * dely + delz * delz < touch * touch) {
      const int s = fix_store->add_record(i, tag[j], LB_CONTACT);
      if (fix_store->capacity != partner_stride) relayout_partners();
      partner_idx[(bigint) i * partner_stride + s] = j;
      if (hetero_flag) cache_bond_factors(i);
      cand_i[c] = cand_i.back();
      cand_j[c] = cand_j.back();
      cand_i.pop_back();
      cand_j.pop_back();
    } else {
      c++;
    }
  }
}

/* ----------------------------------------------------------------------
   the record store grew: the same partner indices with the new stride
------------------------------------------------------------------------- */

void PairLatticeBond::relayout_partners()
{
  const int stride = fix_store->capacity;
  int *fresh = nullptr;
  memory->create(fresh, (bigint) partner_nmax * stride, "pair:partner_idx");
  const int nlocal = atom->nlocal;
  const int keep = MIN(stride, partner_stride);
  for (int i = 0; i < nlocal; i++)
    for (int s = 0; s < keep; s++)
      fresh[(bigint) i * stride + s] = partner_idx[(bigint) i * partner_stride + s];
  memory->destroy(partner_idx);
  partner_idx = fresh;
  partner_stride = stride;
  if (hetero_flag)
    for (int i = 0; i < nlocal; i++) cache_bond_factors(i);
}

/* ----------------------------------------------------------------------
   critical time step of the bonded lattice, reported at the start of each
   run: velocity Verlet is stable for dt < 2 / omega_max, and by Gershgorin's
   theorem omega_max^2 <= max_i 2 sum_j k_ij / m_i over the particle's records
   (k = max(Kn, Ks): each bond's stiffness matrix has eigenvalues Kn and Ks),
   so dt_c = 2 / sqrt(max_i 2 sum_j k_ij / m_i).  It is a lower bound of the
   exact limit (0.6-0.9 of it for regular lattices: docs/theory.md,
   "Critical time step"; conversion.critical_time_step); walls and damping
   are not included.
   In LAMMPS units a force f on a mass m accelerates it by ftm2v f / m
   (fix nve's arithmetic), so k / m is a squared frequency only times ftm2v
   (1 in si, cgs, micro, nano, lj; 1 / 1.0364269e-4 in metal)
------------------------------------------------------------------------- */

void PairLatticeBond::check_time_step()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const double *rmass = atom->rmass;    // per-atom masses, or per-type ones (atom->mass)
  const double *mass = atom->mass;
  const int *type = atom->type;
  stiffness_sum.assign(nall, 0.0);
  for (int i = 0; i < nlocal; i++) {
    const int *idx = partner_idx + (bigint) i * partner_stride;
    for (int s = 0; s < fix_store->nrec[i]; s++) {
      const int j = idx[s];
      if (j < 0) continue;
      const BondParams p = bond_params(i, j);
      const double k = MAX(p.kn, p.ks);
      stiffness_sum[i] += k;
      stiffness_sum[j] += k;
    }
  }
  comm_what = COMM_STIFFNESS;
  comm->reverse_comm(this);
  double lambda_local = 0.0, lambda = 0.0;
  for (int i = 0; i < nlocal; i++) {
    const double m = rmass ? rmass[i] : mass[type[i]];
    if (m > 0.0) lambda_local = MAX(lambda_local, 2.0 * stiffness_sum[i] / m);
  }
  MPI_Allreduce(&lambda_local, &lambda, 1, MPI_DOUBLE, MPI_MAX, world);
  lambda *= force->ftm2v;    // omega^2 in 1/time^2 (x 1.0 in si: the same bits)
  dt_critical = (lambda > 0.0) ? 2.0 / sqrt(lambda) : 0.0;
  if (dt_critical <= 0.0) return;
  const double dt = update->dt;
  if (comm->me == 0)
    utils::logmesg(lmp, "pair_style lattice/bond: critical time step {:.6g} (stiffest particle, "
                   "walls not included); the time step {:.6g} is {:.3f} of it\n", dt_critical, dt,
                   dt / dt_critical);
  if (dt > DT_SAFETY_FRACTION * dt_critical && comm->me == 0)
    error->warning(FLERR, "Time step {:.6g} is {:.2f} of the critical time step {:.6g} of "
                   "pair_style lattice/bond (above the safety fraction {}): the run may become "
                   "unstable; use a time step of at most {:.6g}", dt, dt / dt_critical, dt_critical,
                   DT_SAFETY_FRACTION, DT_SAFETY_FRACTION * dt_critical);
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::report_instability(int i)
{
  double **x = atom->x;
  const double *d = fix_store->displacements() + 3 * i;
  const double step = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double dt = update->dt;
  error->one(FLERR,
             "pair_style lattice/bond: atom {} moved {:.6g} in one time step at step {} (more "
             "than a tenth of the smallest particle radius, {:.6g}; it is now at {:.6g} {:.6g} "
             "{:.6g}): the integration is unstable. The time step {:.6g} is {:.2f} of the "
             "critical time step {:.6g} reported at the start of the run: reduce it to at most "
             "{:.6g}, or look for a much stiffer wall or type pair",
             atom->tag[i], step, update->ntimestep, STEP_LIMIT_FRACTION * min_radius, x[i][0],
             x[i][1], x[i][2], dt, dt_critical > 0.0 ? dt / dt_critical : 0.0, dt_critical,
             DT_SAFETY_FRACTION * dt_critical);
}

/* ----------------------------------------------------------------------
   reverse communication: ghosts' stiffness sums to their owners
------------------------------------------------------------------------- */

int PairLatticeBond::pack_reverse_comm(int n, int first, double *buf)
{
  if (comm_what == COMM_FIT) {
    const int nv = fit_values;
    std::memcpy(buf, fit_sums.data() + (size_t) first * nv, sizeof(double) * n * nv);
    return n * nv;
  }
  for (int k = 0; k < n; k++) buf[k] = stiffness_sum[first + k];
  return n;
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::unpack_reverse_comm(int n, int *list, double *buf)
{
  if (comm_what == COMM_FIT) {
    const int nv = fit_values;
    for (int k = 0; k < n; k++) {
      double *sums = fit_sums.data() + (size_t) list[k] * nv;
      for (int v = 0; v < nv; v++) sums[v] += buf[k * nv + v];
    }
    return;
  }
  for (int k = 0; k < n; k++) stiffness_sum[list[k]] += buf[k];
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  bool rebuilt = (neighbor->ago == 0);
  if (!fix_store->bonds_created) {
    create_bonds();
    rebuilt = true;
  }
  // 2D records read from a bond file or an older restart file hold vectors
  const bool convert = domain->dimension == 2 &&
      fix_store->shear_layout == FixLatticeBondStore::SHEAR_VECTOR;
  fetch_heterogeneity();
  if (rebuilt && hetero_flag) {
    // the ghosts' stiffness factors and grain IDs, once per reneighbouring
    comm_what = COMM_HETERO;
    comm->forward_comm(this);
  }
  if (rebuilt || convert) refresh_partners();
  if (convert) planar_springs_from_vectors();
  if (!cand_i.empty()) detect_new_contacts();

  // each particle's displacement over this step, ghosts included; outside
  // setup (where a user may have moved atoms between runs) a step longer than
  // a tenth of a radius stops an unstable run before it writes NaN
  const bool setup = update->setupflag;
  // (a minimiser's line search may try long steps: no test there)
  const bool minimizing = (update->whichflag == 2);
  // (fix lattice/nve may have measured the steps already, testing them against step_limit)
  fix_store->step_limit = STEP_LIMIT_FRACTION * min_radius;
  const int runaway = fix_store->update_displacements(
      (setup || minimizing) ? 0.0 : fix_store->step_limit);
  if (runaway >= 0) report_instability(runaway);
  comm_what = COMM_DISPLACEMENT;
  comm->forward_comm(this);
  if (setup) check_time_step();
  if (corotational()) local_rotations();

  // each scene runs a force loop compiled for the physics it uses
  const int features = scene_features();
  (this->*EVAL_TABLE[features])();

  // the displacements the store formed give way to the positions again
  fix_store->end_evaluation();
  if (vflag_fdotr) virial_fdotr_compute();
}

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
  const int hetero = hetero_flag ? LB_HETERO : 0;
  // with the keyword diameter there is no per-atom radius to read: equal particles always
  const int equal = (diameter > 0.0) ? LB_EQUAL : 0;
  if (evflag)
    return LB_EV | LB_SHEAR_SOME | LB_FRICTION | planar | (tally_flag ? LB_TALLY : 0) | corotate |
        hetero | equal;
  int features = planar | (tally_flag ? LB_TALLY : 0) | corotate | hetero;
  if (uniform_params) features |= LB_UNIFORM;
  if (shear_pairs == SHEAR_PAIRS_ALL) features |= LB_SHEAR_ALL;
  else if (shear_pairs == SHEAR_PAIRS_SOME) features |= LB_SHEAR_SOME;
  if (any_friction) features |= LB_FRICTION;
  if (equal_radius > 0.0) features |= LB_EQUAL;
  return features;
}

/* one entry per feature combination: steps with energy/virial tallies
   (thermo output), and the combination that never occurs (both shear bits),
   use the general loop (for equal particles with the keyword diameter, which
   leaves no per-atom radius to read); heat tallies are specialised like plain
   steps.  Without shear springs contact friction changes nothing in the loop
   (FRICTION only selects the sliding of a spring), so those entries share the
   frictionless loop.  Every bit, made a runtime branch, cost the loop over 1%
   in 2D or 3D (docs/design.md, "What each template parameter is worth") */

template <int F> constexpr PairLatticeBond::EvalFn PairLatticeBond::eval_entry()
{
  // a step without energy/virial tallies: friction matters only with shear springs
  constexpr int PLAIN = (F & (LB_SHEAR_ALL | LB_SHEAR_SOME)) ? F : (F & ~LB_FRICTION);
  constexpr int GENERAL = LB_SHEAR_SOME | LB_FRICTION |
      (F & (LB_EV | LB_TALLY | LB_PLANAR | LB_COROTATE | LB_HETERO | LB_EQUAL));
  constexpr bool both_shear = (F & LB_SHEAR_ALL) && (F & LB_SHEAR_SOME);
  // without shear springs there is nothing to corotate (corotational() is false)
  constexpr bool idle_corotate = (F & LB_COROTATE) && !(F & (LB_SHEAR_ALL | LB_SHEAR_SOME | LB_EV));
  if constexpr ((F & LB_EV) || both_shear) return &PairLatticeBond::eval<GENERAL>;
  else if constexpr (idle_corotate) return &PairLatticeBond::eval<PLAIN & ~LB_COROTATE>;
  else return &PairLatticeBond::eval<PLAIN>;
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
   shear_frame corotational (docs/pair_lattice_bond.rst, "Rigid rotation"):
   the pre-pass runs only when some type pair has a shear spring
------------------------------------------------------------------------- */

bool PairLatticeBond::corotational() const
{
  return shear_frame == SHEAR_FRAME_COROTATIONAL && shear_pairs != SHEAR_PAIRS_NONE;
}

/* ----------------------------------------------------------------------
   each particle's rotation increment in this step, fitted to the motion of
   its intact bonds.  For a bond of particle i with partner j let u = the
   step's relative displacement (disp_i - disp_j) and m = r_ij - u/2 its
   mid-step separation.  The velocity gradient L of the neighbourhood is the
   least-squares fit of u = L m over the particle's intact bonds,
       L = B S^-1,   B = sum u m^T,   S = sum m m^T,
   and the rotation is its antisymmetric part, w = axial vector of (L - L^T)/2.
   A rigid rotation by the angle phi about the axis a moves every separation by
   u = 2 g x m exactly (Cayley: r_new - r_old = g x (r_new + r_old),
   g = tan(phi/2) a), so the fit returns w = 2 g to round-off, and a pure strain
   (symmetric L) returns w = 0 for any neighbourhood geometry.  A particle
   whose bonds do not span the plane (2D) or space (3D), or span it poorly
   (tr S tr S^-1 above ROTATION_FIT_CONDITION: one bond, collinear bonds, in 3D
   coplanar ones), gets w = 0, as in the papers.  Both atoms of a bond receive
   its terms (the products do not change sign with the bond's direction);
   ghosts' sums go back to their owners, and the owners' rotations out to the
   ghosts.  Nothing is kept between steps.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   the sums S and B of local_rotations over the intact bonds, on both atoms
   (the owner's in registers, the partner's in fit_sums)
------------------------------------------------------------------------- */

template <bool PLANAR> void PairLatticeBond::fit_sums_over_bonds()
{
  constexpr int NV = PLANAR ? FIT_VALUES_2D : FIT_VALUES_3D;
  const auto *const x = reinterpret_cast<const double(*)[3]>(atom->x[0]);
  const auto *const disp = reinterpret_cast<const double(*)[3]>(fix_store->displacements());
  const int *const nrec = fix_store->nrec;
  double *const sums = fit_sums.data();
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    const LatticeBondState *__restrict st = fix_store->states(i);
    const int *__restrict idx = partner_idx + (bigint) i * partner_stride;
    const double xi = x[i][0], yi = x[i][1], zi = x[i][2];
    const double dxi = disp[i][0], dyi = disp[i][1], dzi = disp[i][2];
    double acc[NV] = {};
    for (int s = 0; s < nrec[i]; s++) {
      const int j = idx[s];
      if (j < 0 || st[s] != LB_INTACT) continue;
      // the same expressions as in eval(), so that a rigid rotation cancels to round-off
      const double ux = dxi - disp[j][0], uy = dyi - disp[j][1];
      const double mx = (xi - x[j][0]) - 0.5 * ux, my = (yi - x[j][1]) - 0.5 * uy;
      double t[NV];
      if constexpr (PLANAR) {
        const double terms[NV] = {mx * mx, mx * my, my * my, ux * mx, ux * my, uy * mx, uy * my};
        for (int v = 0; v < NV; v++) t[v] = terms[v];
      } else {
        const double uz = dzi - disp[j][2];
        const double mz = (zi - x[j][2]) - 0.5 * uz;
        const double terms[NV] = {mx * mx, mx * my, mx * mz, my * my, my * mz, mz * mz,
                                  ux * mx, ux * my, ux * mz, uy * mx, uy * my, uy * mz,
                                  uz * mx, uz * my, uz * mz};
        for (int v = 0; v < NV; v++) t[v] = terms[v];
      }
      double *__restrict sj = sums + (size_t) j * NV;
      for (int v = 0; v < NV; v++) {
        acc[v] += t[v];
        sj[v] += t[v];
      }
    }
    double *si = sums + (size_t) i * NV;
    for (int v = 0; v < NV; v++) si[v] += acc[v];
  }
}

/* ---------------------------------------------------------------------- */

void PairLatticeBond::local_rotations()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const bool planar = (domain->dimension == 2);
  const int nv = planar ? FIT_VALUES_2D : FIT_VALUES_3D;
  fit_values = nv;
  fit_sums.assign((size_t) nall * nv, 0.0);
  if (atom->nmax > spin_nmax) {
    memory->destroy(spin);
    spin_nmax = atom->nmax;
    memory->create(spin, spin_nmax, 3, "pair:spin");
  }

  if (planar) fit_sums_over_bonds<true>();
  else fit_sums_over_bonds<false>();
  comm_what = COMM_FIT;
  comm->reverse_comm(this);

  const double *const sums = fit_sums.data();
  for (int i = 0; i < nlocal; i++) {
    const double *f = sums + (size_t) i * nv;
    double *wi = spin[i];
    wi[0] = wi[1] = wi[2] = 0.0;
    if (planar) {
      const double tr = f[0] + f[2];
      if (!(tr > 0.0)) continue;
      const double q = 1.0 / tr;    // scale S and B by 1/tr S: no under- or overflow
      const double a = f[0] * q, b = f[1] * q, c = f[2] * q;
      const double det = a * c - b * b;    // tr S tr S^-1 = tr^2 / det = 1 / det here
      if (!(det * ROTATION_FIT_CONDITION >= 1.0)) continue;
      const double bxx = f[3] * q, bxy = f[4] * q, byx = f[5] * q, byy = f[6] * q;
      // (L_yx - L_xy) / 2 with L = B S^-1, S^-1 = [c -b; -b a] / det
      wi[2] = 0.5 * ((c * byx - b * byy) - (a * bxy - b * bxx)) / det;
    } else {
      const double tr = f[0] + f[3] + f[5];
      if (!(tr > 0.0)) continue;
      const double q = 1.0 / tr;
      const double sxx = f[0] * q, sxy = f[1] * q, sxz = f[2] * q;
      const double syy = f[3] * q, syz = f[4] * q, szz = f[5] * q;
      // adjugate of S (symmetric) and its determinant
      const double axx = syy * szz - syz * syz, axy = sxz * syz - sxy * szz;
      const double axz = sxy * syz - sxz * syy, ayy = sxx * szz - sxz * sxz;
      const double ayz = sxy * sxz - sxx * syz, azz = sxx * syy - sxy * sxy;
      const double det = sxx * axx + sxy * axy + sxz * axz;
      // tr S tr S^-1 = (axx + ayy + azz) / det, tr S = 1 here.  Below the bound
      // every eigenvalue of S is at least 1/100, so det >= 1e-4: the floor only
      // rejects round-off, where S has rank 1 (one bond, collinear bonds) and
      // both det and the adjugate are noise of order 1e-17
      if (!(det >= ROTATION_FIT_DET_FLOOR && det * ROTATION_FIT_CONDITION >= axx + ayy + azz))
        continue;
      const double bm[3][3] = {{f[6] * q, f[7] * q, f[8] * q},
                               {f[9] * q, f[10] * q, f[11] * q},
                               {f[12] * q, f[13] * q, f[14] * q}};
      const double adj[3][3] = {{axx, axy, axz}, {axy, ayy, ayz}, {axz, ayz, azz}};
      // L det = B adj; w = axial vector of the antisymmetric part of L
      auto l = [&](int a, int b) {
        return bm[a][0] * adj[0][b] + bm[a][1] * adj[1][b] + bm[a][2] * adj[2][b];
      };
      const double h = 0.5 / det;
      wi[0] = (l(2, 1) - l(1, 2)) * h;
      wi[1] = (l(0, 2) - l(2, 0)) * h;
      wi[2] = (l(1, 0) - l(0, 1)) * h;
    }
  }
  comm_what = COMM_SPIN;
  comm->forward_comm(this);
}

/* ----------------------------------------------------------------------
   shear_frame corotational, per record (inlined into the force loop): the
   step's relative displacement u of the pair without its share of the local
   rigid rotation, u -= wbar x m, wbar = (w_i + w_j)/2, m = r_ij - u/2 (exact
   for a rigid rotation, see local_rotations; it is the relative displacement
   of the contact point if each particle turned with its neighbourhood)
------------------------------------------------------------------------- */

template <bool PLANAR>
static inline __attribute__((always_inline)) void
remove_rigid_rotation(const double *wi, const double *wj, double dx, double dy, double dz,
                      double &ux, double &uy, double &uz)
{
  const double wz = 0.5 * (wi[2] + wj[2]);
  const double mx = dx - 0.5 * ux, my = dy - 0.5 * uy;
  if constexpr (PLANAR) {
    ux += wz * my;
    uy -= wz * mx;
  } else {
    const double wx = 0.5 * (wi[0] + wj[0]), wy = 0.5 * (wi[1] + wj[1]);
    const double mz = dz - 0.5 * uz;
    ux -= wy * mz - wz * my;
    uy -= wz * mx - wx * mz;
    uz -= wx * my - wy * mx;
  }
}

/* ----------------------------------------------------------------------
   3D: the shear spring s turned by the pair's rotation, whose Gibbs vector
   is g = wbar/2 = (w_i + w_j)/4 (Rodrigues): s += 2/(1 + g.g) (g x s +
   g x (g x s)).  A 2D spring is a signed length along the pair's tangent and
   turns with the pair by itself
------------------------------------------------------------------------- */

static inline __attribute__((always_inline)) void rotate_spring(const double *wi, const double *wj,
                                                                double &sx, double &sy, double &sz)
{
  const double gx = 0.5 * (0.5 * (wi[0] + wj[0])), gy = 0.5 * (0.5 * (wi[1] + wj[1]));
  const double gz = 0.5 * (0.5 * (wi[2] + wj[2]));
  const double c = 2.0 / (1.0 + (gx * gx + gy * gy + gz * gz));
  const double ax = gy * sz - gz * sy, ay = gz * sx - gx * sz, az = gx * sy - gy * sx;
  const double bx = gy * az - gz * ay, by = gz * ax - gx * az, bz = gx * ay - gy * ax;
  sx += c * (ax + bx);
  sy += c * (ay + by);
  sz += c * (az + bz);
}

/* ----------------------------------------------------------------------
   a spring of NC components let go
------------------------------------------------------------------------- */

template <int NC> static inline void clear_spring(double *sh)
{
  for (int k = 0; k < NC; k++) sh[k] = 0.0;
}

/* ----------------------------------------------------------------------
   the force loop over records (docs/theory.md, "The model"), compiled per feature
   set F (see scene_features):
   LB_EV: tally energy/virial; LB_TALLY: accumulate breaking and frictional
   heat (compute lattice/energy); LB_PLANAR: 2D, no z components;
   LB_UNIFORM: one parameter set for all type pairs; LB_SHEAR_ALL / _SOME:
   every / some type pair has Ks > 0 (neither: no shear springs);
   LB_FRICTION: some type pair has mu_p > 0 (without it broken bonds and
   contacts are frictionless and carry no shear spring); LB_EQUAL: every
   particle has the same radius (no per-partner radius load); LB_HETERO:
   each bond scales its type pair's parameters by its stiffness and
   strength factors (scaled_params).

   The physics of a record (stretch, break tests, the 2D and 3D spring
   updates, Coulomb sliding, the heat of each event, the energy) is in
   lattice_bond_physics.h, with the formulas; this loop decides which of them
   a record needs and applies the forces.
------------------------------------------------------------------------- */

template <int F> void PairLatticeBond::eval()
{
  constexpr bool EVFLAG = F & LB_EV;
  constexpr bool TALLY = F & LB_TALLY;
  constexpr bool PLANAR = F & LB_PLANAR;
  constexpr bool UNIFORM = F & LB_UNIFORM;
  constexpr bool SHEAR = F & (LB_SHEAR_ALL | LB_SHEAR_SOME);
  constexpr bool SHEAR_ALL = F & LB_SHEAR_ALL;
  constexpr bool FRICTION = F & LB_FRICTION;
  constexpr bool EQUAL = F & LB_EQUAL;
  constexpr bool COROTATE = F & LB_COROTATE;
  constexpr bool HETERO = F & LB_HETERO;

  // LAMMPS keeps x and f contiguous: index them as arrays of triples
  const auto *const x = reinterpret_cast<const double(*)[3]>(atom->x[0]);
  auto *const f = reinterpret_cast<double(*)[3]>(atom->f[0]);
  const double *const radius = atom->radius;
  const int *const type = atom->type;
  const int nlocal = atom->nlocal;
  const int *const nrec = fix_store->nrec;
  const auto *const disp = reinterpret_cast<const double(*)[3]>(fix_store->displacements());
  const int stride = partner_stride;
  const BondParams p_uniform = params[1][1];
  const double touch_equal = 2.0 * equal_radius;    // r + r is exact: the same bits
  const auto *const w = COROTATE ? reinterpret_cast<const double(*)[3]>(spin[0]) : nullptr;
  const bool can_break = breaking_enabled;    // off while lattice/quasistatic relaxes
  // the springs: a signed length in 2D (compute() converts loaded vectors first)
  constexpr int NC = PLANAR ? 1 : 3;
  if (fix_store->ncomp != NC)
    error->one(FLERR, "pair_style lattice/bond: internal error: {} spring components, the loop "
               "expects {}", fix_store->ncomp, NC);
  double q_break_n = 0.0, q_break_s = 0.0, q_friction = 0.0;
  const bool prefetch = !PLANAR && sizeof(double) * NC * stride * (double) nlocal >= PREFETCH_MIN_BYTES;

  // geometry of a batch of particles first (about BATCH_RECORDS records), then
  // their records: the lengths and directions come from one loop without
  // indexing, which the compiler turns into paired square roots and divisions,
  // and the processor overlaps them with the batch's record updates (a record
  // otherwise waits for the divider, docs/performance.md); the positions do
  // not change in between, so the bits are those of one record at a time
  double sep[3][MAX_RECORDS], dist[MAX_RECORDS], dinv[MAX_RECORDS];
  for (int i0 = 0; i0 < nlocal;) {
    int nb = 0, i1 = i0;
    for (; i1 < nlocal && (nb == 0 || nb + nrec[i1] <= BATCH_RECORDS); i1++) {
      const int *__restrict idx = partner_idx + (bigint) i1 * stride;
      const double xi = x[i1][0], yi = x[i1][1], zi = PLANAR ? 0.0 : x[i1][2];
      for (int s = 0; s < nrec[i1]; s++, nb++) {
        const int j = idx[s];
        // a far-away partner: any finite values (unit length)
        sep[0][nb] = (j < 0) ? 1.0 : xi - x[j][0];
        sep[1][nb] = (j < 0) ? 0.0 : yi - x[j][1];
        if (!PLANAR) sep[2][nb] = (j < 0) ? 0.0 : zi - x[j][2];
      }
    }
    for (int k = 0; k < nb; k++) {
      const double sx = sep[0][k], sy = sep[1][k], sz = PLANAR ? 0.0 : sep[2][k];
      const double rr = sqrt(sx * sx + sy * sy + sz * sz);
      const double rinv = 1.0 / rr;
      dist[k] = rr;
      dinv[k] = rinv;
      sep[0][k] = sx * rinv;    // now the unit vector
      sep[1][k] = sy * rinv;
      if (!PLANAR) sep[2][k] = sz * rinv;
    }
    int base = 0;
    for (int i = i0; i < i1; base += nrec[i], i++) {
      const int nr = nrec[i];
      // the springs and partner indices of the particle PREFETCH_AHEAD places on
      // are requested now, so that they arrive while this one computes: a large
      // 3D block otherwise waits on memory for each particle's records
      if (prefetch && i + PREFETCH_AHEAD < nlocal) {
        const int ahead = i + PREFETCH_AHEAD, n = nrec[ahead];
        prefetch_bytes(fix_store->springs(ahead), sizeof(double) * NC * n, true);
        prefetch_bytes(partner_idx + (bigint) ahead * stride, sizeof(int) * n, false);
      }
      if (!nr) continue;
      double *__restrict spr = fix_store->springs(i);
      LatticeBondState *__restrict st = fix_store->states(i);
      const int *__restrict idx = partner_idx + (bigint) i * stride;
      const double *__restrict factors = HETERO ? bond_factor.data() + (size_t) i * stride * 2 : nullptr;
      const double xi = x[i][0], yi = x[i][1], zi = PLANAR ? 0.0 : x[i][2];
      const double dxi = disp[i][0], dyi = disp[i][1], dzi = PLANAR ? 0.0 : disp[i][2];
      const double radi = EQUAL ? 0.0 : radius[i];
      const BondParams *prow = params[type[i]];
      double fxi = 0.0, fyi = 0.0, fzi = 0.0;    // summed here: fewer stores in the loop
      const double *const rlen = dist + base;
      const double *const rinvs = dinv + base;
      const double *const unit[3] = {sep[0] + base, sep[1] + base, sep[2] + base};

      for (int s = 0; s < nr; s++) {
        const int j = idx[s];
        if (RARE(j < 0)) continue;    // broken bond whose partner is far away
        double *const sh = spr + s * NC;    // this record's spring
        const BondParams &p_type = UNIFORM ? p_uniform : prow[type[j]];
        // heterogeneous rock: this bond's own stiffness and strength
        BondParams p_bond;
        if (HETERO) p_bond = scaled_params(p_type, factors[2 * s], factors[2 * s + 1]);
        const BondParams &p = HETERO ? p_bond : p_type;
        const bool has_shear = SHEAR && (SHEAR_ALL || p.ks > 0.0);

        // separation (for the tallies and the corotational frame), its length and direction
        const double dx = xi - x[j][0], dy = yi - x[j][1], dz = PLANAR ? 0.0 : zi - x[j][2];
        const double rr = rlen[s];
        const double nx = unit[0][s], ny = unit[1][s], nz = PLANAR ? 0.0 : unit[2][s];
        const double touch = EQUAL ? touch_equal : radi + radius[j];    // rest length
        const double xn = normal_stretch(rr, touch);    // tension positive
        // this step's relative displacement (dx minus its value at the last step)
        const double ddx = dxi - disp[j][0], ddy = dyi - disp[j][1];
        const double ddz = PLANAR ? 0.0 : dzi - disp[j][2];
        // the increment the shear springs see: with shear_frame corotational
        // without the pair's share of the local rigid rotation
        double ux = ddx, uy = ddy, uz = ddz;
        if (COROTATE) remove_rigid_rotation<PLANAR>(w[i], w[j], dx, dy, dz, ux, uy, uz);

        // 2D: its part along the tangent t = z x n at mid-step
        const double dtan = PLANAR ? planar_increment(nx, ny, ux, uy, rinvs[s]) : 0.0;

        int state = st[s];
        if (RARE(state == LB_INTACT && breaks_in_tension(xn, p.xb) && can_break)) {
          // tensile break: both springs let go
          st[s] = LB_BROKEN_TENSION;
          state = LB_BROKEN_TENSION;
          if (TALLY) {
            q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
            q_break_s += PLANAR ? planar_release(sh, p.ks, dtan) : spring_release(sh, p.ks, ddx, ddy, ddz);
            clear_spring<NC>(sh);
          }
        }
        if (RARE(state != LB_INTACT && contact_open(xn))) {
          // open contact: no force, no memory
          if (TALLY)
            q_friction += PLANAR ? planar_release(sh, p.ks, dtan) : spring_release(sh, p.ks, ddx, ddy, ddz);
          clear_spring<NC>(sh);
          continue;
        }

        const double fn = normal_force(p.kn, xn);    // tension positive
        double fsx = 0.0, fsy = 0.0, fsz = 0.0, es = 0.0;

        if (state == LB_INTACT && !has_shear && coulomb_limit(p.fs0, p.mu_p, fn) < 0.0 &&
            can_break) {
          // no shear spring: the bond fails in shear only when its Coulomb
          // limit itself becomes negative (tension above Fs0/mu_p)
          st[s] = LB_BROKEN_SHEAR;
          state = LB_BROKEN_SHEAR;
          if (contact_open(xn)) {
            if (TALLY)
              q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
            continue;
          }
        }

        // a frictionless contact (closed, mu_p = 0 everywhere) has no shear spring
        if (PLANAR && has_shear && (FRICTION || state == LB_INTACT)) {
          // 2D: the spring is a signed length along t, which turns with the
          // pair, so it needs no projection and keeps its length exactly
          const double s1 = sh[0];
          double sig = s1 + dtan;
          const double fs2 = planar_force_squared(p.ks, sig);
          const bool broke_now =
              state == LB_INTACT && RARE(breaks_in_shear(p.fs0, p.mu_p, fn, fs2) && can_break);
          if (broke_now) state = st[s] = LB_BROKEN_SHEAR;
          if (RARE(state != LB_INTACT)) {
            if (contact_open(xn)) {
              // broken in shear while in tension: the contact is open
              if (TALLY) {
                q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
                q_break_s += planar_heat(p.ks, s1, dtan, 0.0);
              }
              sh[0] = 0.0;
              continue;
            }
            if (FRICTION) {
              const double limit = friction_limit(p.mu_p, fn);    // sliding friction of a contact
              if (slides(fs2, limit)) {
                const double slid = planar_slid(p.ks, limit, sig);
                if (TALLY) {
                  const double q = planar_heat(p.ks, s1, dtan, slid);
                  if (broke_now) q_break_s += q;
                  else q_friction += q;
                }
                sig = slid;
              }
            } else {
              // broke in shear just now: a frictionless contact keeps no spring
              if (TALLY) q_break_s += planar_heat(p.ks, s1, dtan, 0.0);
              sig = 0.0;
            }
          }
          sh[0] = sig;
          // force on the owner -Ks sig t
          fsx = p.ks * sig * ny;
          fsy = -p.ks * sig * nx;
          if (EVFLAG) es = planar_spring_energy(p.ks, sig);
        } else if (!PLANAR && has_shear && (FRICTION || state == LB_INTACT)) {
          // compiled only into the 3D loops: the 2D loops' code does not depend on it
          if constexpr (!PLANAR) {
            double s0x = sh[0], s0y = sh[1], s0z = sh[2];
            // shear_frame corotational: the spring turned with the pair's rotation
            if (COROTATE) rotate_spring(w[i], w[j], s0x, s0y, s0z);
            // turned into the new tangent plane, plus the tangential increment
            const SpringStep step = spring_step(nx, ny, nz, s0x, s0y, s0z, ux, uy, uz);
            double sx = step.sx, sy = step.sy, sz = step.sz;
            const double fs2 = shear_force_squared(p.ks, step.s2);
            const bool broke_now =
                state == LB_INTACT && RARE(breaks_in_shear(p.fs0, p.mu_p, fn, fs2) && can_break);
            if (broke_now) state = st[s] = LB_BROKEN_SHEAR;
            if (RARE(state != LB_INTACT)) {
              // the two parts of the step (for the heat): the turned old spring and the increment
              const double s1[3] = {step.s1x, step.s1y, step.s1z}, t[3] = {step.tx, step.ty, step.tz};
              if (contact_open(xn)) {
                // broken in shear while in tension: the contact is open
                if (TALLY) {
                  const double none[3] = {0.0, 0.0, 0.0};
                  q_break_n += normal_release(touch, p.kn, xn, dx - ddx, dy - ddy, dz - ddz);
                  q_break_s += shear_heat(p.ks, s1, t, none);
                }
                clear_spring<NC>(sh);
                continue;
              }
              if (FRICTION) {
                const double limit = friction_limit(p.mu_p, fn);    // sliding friction of a contact
                if (slides(fs2, limit)) {
                  const double scale = slide_scale(p.ks, limit, step.s2);
                  sx *= scale;
                  sy *= scale;
                  sz *= scale;
                  if (TALLY) {
                    const double s2[3] = {sx, sy, sz};
                    const double q = shear_heat(p.ks, s1, t, s2);
                    if (broke_now) q_break_s += q;
                    else q_friction += q;
                  }
                }
              } else {
                // broke in shear just now: a frictionless contact keeps no spring
                if (TALLY) {
                  const double none[3] = {0.0, 0.0, 0.0};
                  q_break_s += shear_heat(p.ks, s1, t, none);
                }
                sx = sy = sz = 0.0;
              }
            }
            sh[0] = sx;
            sh[1] = sy;
            sh[2] = sz;
            fsx = -p.ks * sx;
            fsy = -p.ks * sy;
            fsz = -p.ks * sz;
            if (EVFLAG) es = spring_energy(p.ks, sx * sx + sy * sy + sz * sz);
          }
        } else if (has_shear) {
          clear_spring<NC>(sh);    // a frictionless closed contact
        }

        // force on the owner i; the partner gets the opposite
        const double fx = -fn * nx + fsx, fy = -fn * ny + fsy;
        const double fz = PLANAR ? 0.0 : -fn * nz + fsz;
        fxi += fx;
        fyi += fy;
        f[j][0] -= fx;
        f[j][1] -= fy;
        if (!PLANAR) {
          fzi += fz;
          f[j][2] -= fz;
        }

        if (EVFLAG) {
          const double e = eflag_either ? normal_energy_from_force(fn, xn) + es : 0.0;
          ev_tally_xyz(i, j, nlocal, 1, e, 0.0, fx, fy, fz, dx, dy, dz);
        }
      }
      f[i][0] += fxi;
      f[i][1] += fyi;
      if (!PLANAR) f[i][2] += fzi;
    }
    i0 = i1;
  }
  if (TALLY) {
    heat[0] += q_break_n;
    heat[1] += q_break_s;
    heat[2] += q_friction;
  }
}

/* ----------------------------------------------------------------------
   forward communication: the step's displacements of the ghosts' owners,
   plus, for a ghost across a periodic boundary of a box that changed since
   the last force evaluation, the change of its periodic shift (a ghost is its
   owner plus a lattice vector of the box, which strains with the box: see
   FixLatticeBondStore::BoxStep); or the owners' rotations, or their
   heterogeneity properties
------------------------------------------------------------------------- */

int PairLatticeBond::pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  const double *disp = fix_store->displacements();
  const int dim = domain->dimension;    // 2D: the force loop reads x and y only
  int m = 0;
  if (comm_what == COMM_SPIN) {    // the rotations (2D: about z only)
    const int c0 = (dim == 2) ? 2 : 0;
    for (int k = 0; k < n; k++)
      for (int c = c0; c < 3; c++) buf[m++] = spin[list[k]][c];
    return m;
  }
  if (comm_what == COMM_HETERO) {    // stiffness factor and grain ID (exact as a double)
    for (int k = 0; k < n; k++) {
      buf[m++] = stiffness_factor ? stiffness_factor[list[k]] : 1.0;
      buf[m++] = grain_id ? (double) grain_id[list[k]] : 0.0;
    }
    return m;
  }
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
  double *disp = fix_store->displacements();
  const int dim = domain->dimension;
  int m = 0;
  if (comm_what == COMM_SPIN) {
    const int c0 = (dim == 2) ? 2 : 0;
    for (int i = first; i < first + n; i++)
      for (int c = c0; c < 3; c++) spin[i][c] = buf[m++];
    return;
  }
  if (comm_what == COMM_HETERO) {
    for (int i = first; i < first + n; i++) {
      if (stiffness_factor) stiffness_factor[i] = buf[m];
      if (grain_id) grain_id[i] = (int) buf[m + 1];
      m += 2;
    }
    return;
  }
  for (int i = first; i < first + n; i++)
    for (int c = 0; c < dim; c++) disp[3 * i + c] = buf[m++];
}

/* ----------------------------------------------------------------------
   elastic energy of the records owned by this rank at the current positions
   (the springs as the last force evaluation left them)
------------------------------------------------------------------------- */

double PairLatticeBond::local_elastic_energy() const
{
  if (!fix_store || !partner_idx) return 0.0;
  double **x = atom->x;
  const Radii radius = radii();
  double energy = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    const LatticeBondState *st = fix_store->states(i);
    const int *idx = partner_idx + (bigint) i * partner_stride;
    for (int s = 0; s < fix_store->nrec[i]; s++) {
      const int j = idx[s];
      if (j < 0) continue;
      const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
      const double xn = normal_stretch(sqrt(dx * dx + dy * dy + dz * dz), radius[i] + radius[j]);
      if (st[s] != LB_INTACT && contact_open(xn)) continue;
      const BondParams p = bond_params(i, j);
      energy += record_energy(p.kn, xn, p.ks, fix_store->spring_squared(i, s));
    }
  }
  return energy;
}

/* ---------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   settings: tolerance, then a negative settings format (files before the
   shear_frame keyword have maxslot >= 1 there), maxslot, cutoff, shear_frame;
   format 3 adds the heterogeneity keywords, format 4 the keyword diameter
------------------------------------------------------------------------- */

static constexpr int SETTINGS_FORMAT = 4;

static void write_string(FILE *fp, const std::string &text)
{
  const int n = (int) text.size();
  fwrite(&n, sizeof(int), 1, fp);
  if (n) fwrite(text.data(), sizeof(char), n, fp);
}

void PairLatticeBond::write_restart_settings(FILE *fp)
{
  const int format = -SETTINGS_FORMAT;
  fwrite(&tolerance, sizeof(double), 1, fp);
  fwrite(&format, sizeof(int), 1, fp);
  fwrite(&maxslot, sizeof(int), 1, fp);
  fwrite(&cut_user, sizeof(double), 1, fp);
  fwrite(&shear_frame, sizeof(int), 1, fp);
  fwrite(&hetero_flag, sizeof(int), 1, fp);
  write_string(fp, stiffness_name);
  write_string(fp, grain_name);
  const double range[3] = {strength_min, strength_max, boundary_strength};
  fwrite(range, sizeof(double), 3, fp);
  fwrite(&strength_seed, sizeof(bigint), 1, fp);
  fwrite(&diameter, sizeof(double), 1, fp);
}

/* ----------------------------------------------------------------------
   a string written by write_string, read on rank 0 and sent to all
------------------------------------------------------------------------- */

static std::string read_string(LAMMPS *lmp, FILE *fp)
{
  int n = 0;
  std::string text;
  if (lmp->comm->me == 0) utils::sfread(FLERR, &n, sizeof(int), 1, fp, nullptr, lmp->error);
  MPI_Bcast(&n, 1, MPI_INT, 0, lmp->world);
  if (n < 0 || n > 4096) lmp->error->all(FLERR, "Corrupt pair_style lattice/bond restart settings");
  text.resize(n);
  if (lmp->comm->me == 0 && n)
    utils::sfread(FLERR, &text[0], sizeof(char), n, fp, nullptr, lmp->error);
  if (n) MPI_Bcast(&text[0], n, MPI_CHAR, 0, lmp->world);
  return text;
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
  hetero_flag = 0;
  stiffness_name.clear();
  grain_name.clear();
  strength_min = strength_max = 1.0;
  boundary_strength = DEFAULT_BOUNDARY_STRENGTH;
  strength_seed = 0;
  if (word <= -3) {
    if (comm->me == 0) utils::sfread(FLERR, &hetero_flag, sizeof(int), 1, fp, nullptr, error);
    MPI_Bcast(&hetero_flag, 1, MPI_INT, 0, world);
    stiffness_name = read_string(lmp, fp);
    grain_name = read_string(lmp, fp);
    double range[3] = {1.0, 1.0, DEFAULT_BOUNDARY_STRENGTH};
    if (comm->me == 0) {
      utils::sfread(FLERR, range, sizeof(double), 3, fp, nullptr, error);
      utils::sfread(FLERR, &strength_seed, sizeof(bigint), 1, fp, nullptr, error);
    }
    MPI_Bcast(range, 3, MPI_DOUBLE, 0, world);
    MPI_Bcast(&strength_seed, 1, MPI_LMP_BIGINT, 0, world);
    strength_min = range[0];
    strength_max = range[1];
    boundary_strength = range[2];
  }
  // format 4: the keyword diameter; older files come from atom_style sphere
  diameter = 0.0;
  if (word <= -4) {
    if (comm->me == 0) utils::sfread(FLERR, &diameter, sizeof(double), 1, fp, nullptr, error);
    MPI_Bcast(&diameter, 1, MPI_DOUBLE, 0, world);
  }
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
  bytes += (double) partner_nmax * partner_stride * sizeof(int);
  bytes += (double) bond_factor.capacity() * sizeof(double);
  bytes += (double) cand_i.capacity() * 2 * sizeof(int);
  bytes += (double) spin_nmax * 3 * sizeof(double);
  bytes += (double) fit_sums.capacity() * sizeof(double);
  return bytes;
}
