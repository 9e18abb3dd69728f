/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   fix LATTICE/ENERGY, created by compute lattice/energy (see its doc page).

   Work on a prescribed group (e.g. end layers moved by fix move):
       W = sum over steps of [ dKE_group - 1/2 (f_old + f_new) . dx ]
   per atom, f the force the rest of the system exerts on it, dx its
   displacement; the trapezoidal rule is what velocity Verlet conserves.
   The per-atom history holds the last force and position of group atoms.

   The sources' tallies (LatticeEnergySource: the pair style, the viscous
   and wall fixes) are plain per-rank sums that start at zero when the source is created; this fix takes a base
   at the first setup (and after a restart) and reports the differences,
   plus the totals carried in a restart file.
------------------------------------------------------------------------- */

#include "fix_lattice_energy.h"

#include "atom.h"
#include "comm.h"
#include "compute_lattice_energy.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "pair_lattice_bond.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ----------------------------------------------------------------------
   fix ID all LATTICE/ENERGY compute-ID [group ...]
------------------------------------------------------------------------- */

FixLatticeEnergy::FixLatticeEnergy(LAMMPS *lmp, int narg, char **arg) :
    FixLatticeAtomHistory(lmp, narg, arg), workbit(0), group_work(0.0),
    group_ke_prev(0.0), need_base(1), start_set(0), energy0(0.0)
{
  if (narg < 4) error->all(FLERR, "Illegal fix LATTICE/ENERGY command (internal fix)");
  compute_id = arg[3];
  for (int iarg = 4; iarg < narg; iarg++) {
    const int igroup = group->find(arg[iarg]);
    if (igroup < 0)
      error->all(FLERR, "compute lattice/energy work group {} does not exist: define it with the "
                 "group command first", arg[iarg]);
    work_groups.emplace_back(arg[iarg]);
    workbit |= group->bitmask[igroup];
  }
  for (int k = 0; k < NTALLY; k++) carried[k] = base[k] = 0.0;
  restart_global = 1;
  if (workbit) create_history(6);
}

/* ---------------------------------------------------------------------- */

int FixLatticeEnergy::setmask()
{
  return workbit ? END_OF_STEP : 0;
}

/* ----------------------------------------------------------------------
   find the sources and switch their tallies on (again at every run: styles
   may have been added or replaced since): the pair style (lattice/bond; it
   is meant as the only pair style, and a sub-style of pair hybrid is reached
   by its name, the only way the public headers give) and every fix that
   implements LatticeEnergySource, in the order of their definition
------------------------------------------------------------------------- */

void FixLatticeEnergy::init()
{
  energy_sources.clear();
  auto *pair = dynamic_cast<LatticeEnergySource *>(force->pair);
  if (!pair) pair = static_cast<LatticeEnergySource *>(PairLatticeBond::find(force));
  if (!pair) error->all(FLERR, "compute lattice/energy requires pair_style lattice/bond");
  energy_sources.push_back(pair);
  for (auto *fix : modify->get_fix_list())
    if (auto *source = dynamic_cast<LatticeEnergySource *>(fix)) energy_sources.push_back(source);
  for (auto *source : energy_sources) source->enable_energy_tallies(true);
  gravity = modify->get_fix_by_style("^gravity");
  // the starting energy and the work groups' forces are taken in setup(): the
  // fixes that add forces or energy must have done their setup by then
  const int me = modify->find_fix(id);
  for (int i = me + 1; i < modify->nfix; i++) {
    const std::string style = modify->fix[i]->style;
    if (dynamic_cast<LatticeEnergySource *>(modify->fix[i]) || utils::strmatch(style, "^gravity"))
      error->all(FLERR, "compute lattice/energy {} is defined before fix {} {}: define the "
                 "compute after the fixes that add forces (lattice/wall, lattice/viscous, "
                 "gravity), so that the accounting starts from their energies",
                 compute_id, modify->fix[i]->id, style);
  }
  warn_uncounted();
}

/* ----------------------------------------------------------------------
   the balance counts the pair style, fix lattice/viscous, fix lattice/wall,
   fix gravity and the work on the work groups.  A fix that exchanges energy
   otherwise (a thermostat, other damping, other forces, motion or box and
   radius changes it prescribes outside the work groups) leaves its share in
   the balance error: say so, once per fix (rank 0).  fix move on atoms that
   are all in work groups is counted there.  (Collective: group counts.)
------------------------------------------------------------------------- */

void FixLatticeEnergy::warn_uncounted()
{
  // style names: "x/" or "x" matches the style x and its variants x/...
  // (suffixes like /omp, /kk included), "x$" only x itself
  struct Kind {
    std::vector<std::string> styles;
    const char *what;
  };
  static const Kind KINDS[] = {
      {{"langevin", "temp/", "nvt", "npt", "nph", "gld$", "gle$", "ttm", "heat$", "ehex",
        "press/"},
       "it exchanges heat with a bath or work with a barostat"},
      {{"viscous", "damping/", "nve/limit", "momentum", "recenter", "drag$"},
       "it damps or removes motion outside fix lattice/viscous"},
      {{"addforce", "aveforce", "setforce", "efield", "spring", "smd$", "indent$", "external$",
        "tmd$", "wall/"},
       "the work of the forces it adds or removes is not counted (for setforce: none only while "
       "the atoms it holds do not move)"},
      {{"move$", "deform", "adapt"},
       "it moves atoms, or changes the box or the radii, outside the work groups (for fix "
       "move: list its group after the keyword work of the compute)"}};
  const auto matches = [](const std::string &style, const std::string &name) {
    if (name.back() == '$') return style == name.substr(0, name.size() - 1);
    if (name.back() == '/') return style.compare(0, name.size(), name) == 0;
    return style == name || style.compare(0, name.size() + 1, name + "/") == 0;
  };
  for (auto *other : modify->get_fix_list()) {
    const std::string style = other->style;
    // wall/reflect turns velocities around: no energy exchanged
    if (other == this || warned.count(other->id) || matches(style, "wall/reflect")) continue;
    const char *what = nullptr;
    for (const auto &kind : KINDS)
      for (const auto &name : kind.styles)
        if (!what && matches(style, name)) what = kind.what;
    if (!what) continue;
    // prescribed motion of atoms that all belong to work groups is counted as work
    if (style == "move" && workbit) {
      bigint outside_local = 0, outside = 0;
      for (int i = 0; i < atom->nlocal; i++)
        if ((atom->mask[i] & other->groupbit) && !(atom->mask[i] & workbit)) outside_local++;
      MPI_Allreduce(&outside_local, &outside, 1, MPI_LMP_BIGINT, MPI_SUM, world);
      if (outside == 0) continue;
    }
    warned.insert(other->id);
    if (comm->me == 0)
      error->warning(FLERR, "compute lattice/energy {}: fix {} ({}) adds or removes energy that "
                     "is not in the balance: {}. The balance error (element 10) includes it",
                     compute_id, other->id, style, what);
  }
}

/* ---------------------------------------------------------------------- */

void FixLatticeEnergy::setup(int /*vflag*/)
{
  if (workbit) {
    for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
    group_ke_prev = group_kinetic();
  }
  if (need_base) {
    raw(base);
    need_base = 0;
  }
  if (!start_set) {
    auto *c = dynamic_cast<ComputeLatticeEnergy *>(modify->get_compute_by_id(compute_id));
    if (!c) error->all(FLERR, "fix LATTICE/ENERGY: compute {} is gone", compute_id);
    energy0 = c->stored_energy();
    start_set = 1;
  }
}

/* ---------------------------------------------------------------------- */

void FixLatticeEnergy::end_of_step()
{
  double **x = atom->x;
  double **f = atom->f;
  const int *mask = atom->mask;
  double work = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & workbit)) continue;
    double *h = history(i);
    double dx[3] = {x[i][0] - h[3], x[i][1] - h[4], x[i][2] - h[5]};
    unwrap_step(dx);
    work -= 0.5 * ((h[0] + f[i][0]) * dx[0] + (h[1] + f[i][1]) * dx[1] + (h[2] + f[i][2]) * dx[2]);
    for (int k = 0; k < 3; k++) {
      h[k] = f[i][k];
      h[3 + k] = x[i][k];
    }
  }
  const double ke = group_kinetic();
  group_work += work + ke - group_ke_prev;
  group_ke_prev = ke;
}

/* ---------------------------------------------------------------------- */

void FixLatticeEnergy::set_arrays(int i)
{
  if (!nvalues) return;
  for (int k = 0; k < 3; k++) {
    history(i)[k] = atom->f[i][k];
    history(i)[3 + k] = atom->x[i][k];
  }
}

/* ---------------------------------------------------------------------- */

double FixLatticeEnergy::group_kinetic() const
{
  double **v = atom->v;
  const double *rmass = atom->rmass;    // per-atom masses, or per-type ones
  const double *mass = atom->mass;
  const int *type = atom->type;
  const int *mask = atom->mask;
  double ke = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & workbit) {
      const double m = rmass ? rmass[i] : mass[type[i]];
      ke += 0.5 * m * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    }
  return ke * force->mvv2e;    // in energy units, as compute ke
}

/* ---------------------------------------------------------------------- */

void FixLatticeEnergy::raw(double *local)
{
  for (int k = 0; k < NTALLY; k++) local[k] = 0.0;
  for (const auto *source : energy_sources) source->add_energy_tallies(local);
  local[LatticeEnergySource::WORK] += group_work;
}

/* ---------------------------------------------------------------------- */

void FixLatticeEnergy::totals(double *out)
{
  double local[NTALLY];
  raw(local);
  for (int k = 0; k < NTALLY; k++) local[k] -= base[k];
  MPI_Allreduce(local, out, NTALLY, MPI_DOUBLE, MPI_SUM, world);
  for (int k = 0; k < NTALLY; k++) out[k] += carried[k];
}

/* ----------------------------------------------------------------------
   restart: the totals so far and the starting energy; written by rank 0,
   but totals() is collective, and this is called on every rank
------------------------------------------------------------------------- */

void FixLatticeEnergy::write_restart(FILE *fp)
{
  double list[NTALLY + 2];
  totals(list);
  list[NTALLY] = start_set;
  list[NTALLY + 1] = energy0;
  if (comm->me == 0) {
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), NTALLY + 2, fp);
  }
}

/* ---------------------------------------------------------------------- */

void FixLatticeEnergy::restart(char *buf)
{
  auto list = (double *) buf;
  for (int k = 0; k < NTALLY; k++) carried[k] = list[k];
  start_set = static_cast<int>(list[NTALLY]);
  energy0 = list[NTALLY + 1];
  need_base = 1;
}
