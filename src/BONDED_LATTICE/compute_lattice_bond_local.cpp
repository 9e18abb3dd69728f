/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   compute ID group lattice/bond/local value ...
   One row per bond or contact record of pair_style lattice/bond whose owner
   (the particle with the lower ID) is a local atom in the group.
------------------------------------------------------------------------- */

#include "compute_lattice_bond_local.h"

#include "atom.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "memory.h"
#include "pair_lattice_bond.h"
#include "update.h"

#include <cmath>
#include <map>
#include <string>

using namespace LAMMPS_NS;

static const std::map<std::string, int> VALUE_NAMES = {
    {"id1", 0}, {"id2", 1}, {"state", 2}, {"dist", 3}, {"x", 4},    {"y", 5},    {"z", 6},
    {"fn", 7},  {"fs", 8},  {"kn", 9},    {"fb", 10},  {"fs0", 11}, {"ratio", 12}};

/* ---------------------------------------------------------------------- */

ComputeLatticeBondLocal::ComputeLatticeBondLocal(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), pair(nullptr), nmax(0), vlocal(nullptr), alocal(nullptr)
{
  if (narg < 4)
    error->all(FLERR, "compute lattice/bond/local needs at least one value: id1 id2 state dist x "
               "y z fn fs kn fb fs0 ratio");
  for (int iarg = 3; iarg < narg; iarg++) {
    const auto found = VALUE_NAMES.find(arg[iarg]);
    if (found == VALUE_NAMES.end())
      error->all(FLERR, "compute lattice/bond/local value {} is not valid: use id1 id2 state dist "
                 "x y z fn fs kn fb fs0 ratio", arg[iarg]);
    values.push_back(found->second);
  }
  local_flag = 1;
  size_local_cols = (values.size() == 1) ? 0 : (int) values.size();
}

/* ---------------------------------------------------------------------- */

ComputeLatticeBondLocal::~ComputeLatticeBondLocal()
{
  memory->destroy(vlocal);
  memory->destroy(alocal);
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeBondLocal::init()
{
  pair = PairLatticeBond::find(force);
  if (!pair) error->all(FLERR, "compute lattice/bond/local requires pair_style lattice/bond");
}

/* ----------------------------------------------------------------------
   the springs are those of the last force evaluation, the geometry that of
   the current positions (the same after a run).  A record whose partner is
   not on this rank (a broken bond whose particles separated far) has dist,
   fn, fs and ratio 0 and the owner's position
------------------------------------------------------------------------- */

void ComputeLatticeBondLocal::compute_local()
{
  invoked_local = update->ntimestep;
  FixLatticeBondStore *store = pair->store();
  const int *idx = pair->partner_index();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  int rows = 0;
  if (store && idx)
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) rows += store->record_count(i);
  if (rows > nmax) {
    nmax = rows;
    memory->destroy(vlocal);
    memory->destroy(alocal);
    if (size_local_cols == 0) memory->create(vlocal, nmax, "lattice/bond/local:vector");
    else memory->create(alocal, nmax, size_local_cols, "lattice/bond/local:array");
  }
  vector_local = vlocal;
  array_local = alocal;
  size_local_rows = rows;
  if (!rows) return;

  double **x = atom->x;
  const tagint *tag = atom->tag;
  const int stride = pair->partner_index_stride();
  int row = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const tagint *pt = store->partners(i);
    const LatticeBondState *st = store->states(i);
    for (int s = 0; s < store->record_count(i); s++, row++) {
      const int j = idx[(bigint) i * stride + s];
      const int jj = (j >= 0) ? j : i;
      BreakMode mode;
      const PairLatticeBond::BondLoad load = pair->bond_load(i, s, mode);
      const PairLatticeBond::BondParams &p = load.p;
      for (size_t v = 0; v < values.size(); v++) {
        double value = 0.0;
        switch (values[v]) {
          case ID1: value = (double) tag[i]; break;
          case ID2: value = (double) pt[s]; break;
          case STATE: value = st[s]; break;
          case DIST: value = load.dist; break;
          case X: case Y: case Z: {
            const int k = values[v] - X;
            value = 0.5 * (x[i][k] + x[jj][k]);
            break;
          }
          case FN: value = load.fn; break;
          case FS: value = load.fs; break;
          case KN: value = p.kn; break;
          case FB: value = p.kn * p.xb; break;
          case FS0: value = p.fs0; break;
          case RATIO: value = load.ratio; break;
        }
        if (size_local_cols == 0) vlocal[row] = value;
        else alocal[row][v] = value;
      }
    }
  }
}

/* ---------------------------------------------------------------------- */

double ComputeLatticeBondLocal::memory_usage()
{
  return (double) nmax * values.size() * sizeof(double);
}
