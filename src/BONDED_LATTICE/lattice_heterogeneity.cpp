/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Heterogeneous rock of pair_style lattice/bond: see lattice_heterogeneity.h
------------------------------------------------------------------------- */

#include "lattice_heterogeneity.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "lattice_errors.h"

#include <cmath>
#include <cstdint>

using namespace LAMMPS_NS;

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

LatticeHeterogeneity::LatticeHeterogeneity(LAMMPS *lmp) :
    Pointers(lmp), flag(0), strength_min(1.0), strength_max(1.0),
    boundary_strength(DEFAULT_BOUNDARY_STRENGTH), seed(0), stiffness_index(-1), grain_index(-1),
    strength_index(-1), stiffness_factor(nullptr), grain_id(nullptr), particle_strength(nullptr)
{
}

/* ----------------------------------------------------------------------
   [stiffness d_name] [grain i_name] [strength min max] [strength_factor
   d_name] [seed n] [boundary_strength f]; the caller checked that key has a
   value
------------------------------------------------------------------------- */

int LatticeHeterogeneity::parse_keyword(int narg, char **arg, int iarg)
{
  const std::string key = arg[iarg];
  if (key == "stiffness" || key == "grain" || key == "strength_factor") {
    const std::string name = arg[iarg + 1];
    const bool integer = (key == "grain");
    const char *prefix = integer ? "i_" : "d_";
    const char *what = integer ? "an integer grain ID"
        : (key == "stiffness") ? "a floating-point stiffness factor"
                               : "a floating-point strength factor";
    if (name.size() < 3 || name.compare(0, 2, prefix) != 0)
      error->all(FLERR, "pair_style lattice/bond {} {}: give a per-atom property of fix "
                 "property/atom as {}name ({} per particle)", key, name, prefix, what);
    (key == "stiffness" ? stiffness_name : integer ? grain_name : strength_name) = name.substr(2);
    flag = 1;
    return 2;
  }
  if (key == "strength") {
    if (iarg + 2 >= narg)
      error->all(FLERR, "pair_style lattice/bond strength needs two values: min max");
    strength_min = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    strength_max = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
    if (!(strength_min > 0.0) || !(strength_max >= strength_min))
      error->all(FLERR, "pair_style lattice/bond strength {} {} is out of range: need 0 < min "
                 "<= max (factors of the breaking force Kn*Xb and of Fs0)", strength_min,
                 strength_max);
    flag = 1;
    return 3;
  }
  if (key == "seed") {
    seed = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
    if (seed <= 0)
      error->all(FLERR, "pair_style lattice/bond seed {} is out of range: need a positive integer",
                 seed);
    return 2;
  }
  if (key == "boundary_strength") {
    boundary_strength = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    if (!(boundary_strength > 0.0))
      error->all(FLERR, "pair_style lattice/bond boundary_strength {} is out of range: need > 0 "
                 "(a factor of the strength of bonds between different grains)", boundary_strength);
    return 2;
  }
  return 0;
}

/* ---------------------------------------------------------------------- */

void LatticeHeterogeneity::check_keywords() const
{
  if (strength_max > strength_min && seed <= 0)
    error->all(FLERR, "pair_style lattice/bond strength {} {} draws a random strength per bond: "
               "give its seed (keyword seed, a positive integer)", strength_min, strength_max);
  if (boundary_strength != DEFAULT_BOUNDARY_STRENGTH && grain_name.empty())
    error->all(FLERR, "pair_style lattice/bond boundary_strength needs the keyword grain (which "
               "particles belong to which grain)");
}

/* ----------------------------------------------------------------------
   the per-atom properties named by the keywords stiffness, grain and
   strength_factor (fix property/atom), checked on every run.  Their ghost values are sent by
   share_ghosts() at every reneighbouring, so the fix does not need
   "ghost yes"
------------------------------------------------------------------------- */

void LatticeHeterogeneity::find()
{
  stiffness_index = grain_index = strength_index = -1;
  stiffness_factor = particle_strength = nullptr;
  grain_id = nullptr;
  if (!flag) return;
  auto lookup = [&](const std::string &name, int want_double) -> int {
    int dflag = -1, cols = -1;
    const int index = atom->find_custom(name.c_str(), dflag, cols);
    const char *what = want_double ? "d_" : "i_";
    if (index < 0)
      error->all(FLERR, "pair_style lattice/bond: per-atom property {}{} does not exist; define it "
                 "with fix property/atom {}{} before the run (and give its values, e.g. read_data "
                 "... fix ID NULL Section, or set)", what, name, what, name);
    if (dflag != want_double || cols != 0)
      error->all(FLERR, "pair_style lattice/bond: per-atom property {} must be a single {} value "
                 "per atom ({}{})", name, want_double ? "floating-point" : "integer", what, name);
    return index;
  };
  std::string bad;    // the first atom with a value out of range on this rank
  // a factor property: its index and array; the first atom whose value is not finite > 0
  const auto factor = [&](const std::string &name, const char *what, const char *effect,
                          int &index) -> double * {
    index = lookup(name, 1);
    double *value = atom->dvector[index];
    for (int i = 0; i < atom->nlocal && bad.empty(); i++)
      if (!(value[i] > 0.0) || !std::isfinite(value[i]))
        bad = fmt::format("pair_style lattice/bond: atom {} has {} factor d_{} = {}; need a "
                          "finite value > 0 (it multiplies {})", atom->tag[i], what, name,
                          value[i], effect);
    return value;
  };
  if (!stiffness_name.empty())
    stiffness_factor = factor(stiffness_name, "stiffness", "Kn and Ks", stiffness_index);
  if (!grain_name.empty()) {
    grain_index = lookup(grain_name, 0);
    grain_id = atom->ivector[grain_index];
    for (int i = 0; i < atom->nlocal && bad.empty(); i++)
      if (grain_id[i] < 0)
        bad = fmt::format("pair_style lattice/bond: atom {} has grain ID i_{} = {}; need >= 0",
                          atom->tag[i], grain_name, grain_id[i]);
  }
  if (!strength_name.empty())
    particle_strength = factor(strength_name, "strength", "the breaking force Kn*Xb and Fs0",
                               strength_index);
  // (every rank is here, at init: the message of any rank, printed by rank 0)
  lattice_error_from_any_rank(lmp, FLERR, !bad.empty(), bad);
}

/* ---------------------------------------------------------------------- */

void LatticeHeterogeneity::fetch()
{
  stiffness_factor = (stiffness_index >= 0) ? atom->dvector[stiffness_index] : nullptr;
  grain_id = (grain_index >= 0) ? atom->ivector[grain_index] : nullptr;
  particle_strength = (strength_index >= 0) ? atom->dvector[strength_index] : nullptr;
}

/* ---------------------------------------------------------------------- */

void LatticeHeterogeneity::share_ghosts(LatticeCommCarrier &carrier)
{
  carrier.carry_forward(this);
}

/* ----------------------------------------------------------------------
   the bond's stiffness factor: the mean of its particles' factors (the
   average stiffness of two grains across their boundary)
------------------------------------------------------------------------- */

double LatticeHeterogeneity::bond_stiffness_factor(int i, int j) const
{
  return stiffness_factor ? 0.5 * (stiffness_factor[i] + stiffness_factor[j]) : 1.0;
}

/* ----------------------------------------------------------------------
   the bond's strength factor: uniform in [strength_min, strength_max] per
   bond, times the mean of the particles' strength factors, times
   boundary_strength if the particles belong to different grains
------------------------------------------------------------------------- */

double LatticeHeterogeneity::bond_strength_factor(int i, int j) const
{
  double g = strength_min;
  if (strength_max > strength_min)
    g += (strength_max - strength_min) * bond_uniform(seed, atom->tag[i], atom->tag[j]);
  if (particle_strength) g *= 0.5 * (particle_strength[i] + particle_strength[j]);
  if (grain_id && grain_id[i] != grain_id[j]) g *= boundary_strength;
  return g;
}

/* ----------------------------------------------------------------------
   records without a partner here (idx -1) get 1, 1 (unused)
------------------------------------------------------------------------- */

void LatticeHeterogeneity::cache_bond_factors(int i, const int *idx, int nrec, int stride, int nmax)
{
  const size_t need = (size_t) nmax * stride * 2;
  if (bond_factor.size() != need) bond_factor.assign(need, 1.0);
  double *bf = bond_factor.data() + (size_t) i * stride * 2;
  for (int s = 0; s < nrec; s++) {
    const int j = idx[s];
    bf[2 * s] = (j >= 0) ? bond_stiffness_factor(i, j) : 1.0;
    bf[2 * s + 1] = (j >= 0) ? bond_strength_factor(i, j) : 1.0;
  }
}

/* ----------------------------------------------------------------------
   forward communication: the owners' stiffness factors, grain IDs (a
   grain ID is exact as a double) and strength factors
------------------------------------------------------------------------- */

int LatticeHeterogeneity::pack_forward(int n, const int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    buf[m++] = stiffness_factor ? stiffness_factor[list[k]] : 1.0;
    buf[m++] = grain_id ? (double) grain_id[list[k]] : 0.0;
    buf[m++] = particle_strength ? particle_strength[list[k]] : 1.0;
  }
  return m;
}

/* ---------------------------------------------------------------------- */

void LatticeHeterogeneity::unpack_forward(int n, int first, const double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    if (stiffness_factor) stiffness_factor[i] = buf[m];
    if (grain_id) grain_id[i] = (int) buf[m + 1];
    if (particle_strength) particle_strength[i] = buf[m + 2];
    m += 3;
  }
}

/* ----------------------------------------------------------------------
   restart settings: the flag, the two property names, strength_min,
   strength_max, boundary_strength and the seed
------------------------------------------------------------------------- */

static void write_string(FILE *fp, const std::string &text)
{
  const int n = (int) text.size();
  fwrite(&n, sizeof(int), 1, fp);
  if (n) fwrite(text.data(), sizeof(char), n, fp);
}

void LatticeHeterogeneity::write_restart(FILE *fp) const
{
  fwrite(&flag, sizeof(int), 1, fp);
  write_string(fp, stiffness_name);
  write_string(fp, grain_name);
  const double range[3] = {strength_min, strength_max, boundary_strength};
  fwrite(range, sizeof(double), 3, fp);
  fwrite(&seed, sizeof(bigint), 1, fp);
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

void LatticeHeterogeneity::read_restart(FILE *fp, bool present)
{
  flag = 0;
  stiffness_name.clear();
  grain_name.clear();
  strength_min = strength_max = 1.0;
  boundary_strength = DEFAULT_BOUNDARY_STRENGTH;
  seed = 0;
  if (!present) return;
  if (comm->me == 0) utils::sfread(FLERR, &flag, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&flag, 1, MPI_INT, 0, world);
  stiffness_name = read_string(lmp, fp);
  grain_name = read_string(lmp, fp);
  double range[3] = {1.0, 1.0, DEFAULT_BOUNDARY_STRENGTH};
  if (comm->me == 0) {
    utils::sfread(FLERR, range, sizeof(double), 3, fp, nullptr, error);
    utils::sfread(FLERR, &seed, sizeof(bigint), 1, fp, nullptr, error);
  }
  MPI_Bcast(range, 3, MPI_DOUBLE, 0, world);
  MPI_Bcast(&seed, 1, MPI_LMP_BIGINT, 0, world);
  strength_min = range[0];
  strength_max = range[1];
  boundary_strength = range[2];
}

/* ----------------------------------------------------------------------
   restart settings of format 5: the name of the strength_factor property
   ("" without the keyword); older files have none
------------------------------------------------------------------------- */

void LatticeHeterogeneity::write_restart_strength_factor(FILE *fp) const
{
  write_string(fp, strength_name);
}

void LatticeHeterogeneity::read_restart_strength_factor(FILE *fp, bool present)
{
  strength_name.clear();
  if (present) strength_name = read_string(lmp, fp);
}

/* ---------------------------------------------------------------------- */

double LatticeHeterogeneity::memory_usage() const
{
  return (double) bond_factor.capacity() * sizeof(double);
}
