/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   compute lattice/bonds
   global vector: [1] intact bonds, [2] bonds broken in tension,
   [3] bonds broken in shear, [4] active contacts (broken bonds and unbonded
   pairs that overlap).  Each bond is counted once, by its lower-tag atom,
   if that atom is in the compute's group.
   per-atom vector: intact bonds of each atom (for dumps and OVITO), or with
   "peratom tension|shear" its bonds broken in that mode (crack and shear-zone
   maps).
------------------------------------------------------------------------- */

#include "compute_lattice_bonds.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_lattice_bond_store.h"
#include "force.h"
#include "lattice_bond_geometry.h"
#include "memory.h"
#include "pair_lattice_bond.h"
#include "update.h"

#include <cstring>
#include <string>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

ComputeLatticeBonds::ComputeLatticeBonds(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), pair(nullptr), peratom_state(LB_INTACT), nmax(0),
    intact_per_atom(nullptr)
{
  if (narg != 3 && narg != 5)
    error->all(FLERR, "Illegal compute lattice/bonds command: expected compute ID group "
               "lattice/bonds [peratom intact|tension|shear]");
  if (narg == 5) {
    if (strcmp(arg[3], "peratom") != 0)
      error->all(FLERR, "Unknown compute lattice/bonds keyword {}: the only keyword is peratom",
                 arg[3]);
    const std::string what = arg[4];
    if (what == "intact") peratom_state = LB_INTACT;
    else if (what == "tension") peratom_state = LB_BROKEN_TENSION;
    else if (what == "shear") peratom_state = LB_BROKEN_SHEAR;
    else
      error->all(FLERR, "compute lattice/bonds peratom {} is not valid: use intact, tension or "
                 "shear", what);
  }
  vector_flag = 1;
  size_vector = 4;
  extvector = 1;
  peratom_flag = 1;
  size_peratom_cols = 0;
  comm_reverse = 1;
  vector = counts;
}

/* ---------------------------------------------------------------------- */

ComputeLatticeBonds::~ComputeLatticeBonds()
{
  memory->destroy(intact_per_atom);
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeBonds::init()
{
  pair = PairLatticeBond::find(force);
  if (!pair) error->all(FLERR, "compute lattice/bonds requires pair_style lattice/bond");
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeBonds::compute_vector()
{
  invoked_vector = update->ntimestep;
  FixLatticeBondStore *store = pair->store();
  const int *idx = pair->partner_index();
  double local[4] = {0.0, 0.0, 0.0, 0.0};
  if (store && idx) {
    double **x = atom->x;
    const PairLatticeBond::Radii radius = pair->radii();
    const int *mask = atom->mask;
    const int stride = pair->partner_index_stride();
    for (int i = 0; i < atom->nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      const LatticeBondState *st = store->states(i);
      for (int s = 0; s < store->record_count(i); s++) {
        const LatticeBondState state = st[s];
        if (state == LB_INTACT) {
          local[0] += 1.0;
          continue;
        }
        if (state == LB_BROKEN_TENSION) local[1] += 1.0;
        else if (state == LB_BROKEN_SHEAR) local[2] += 1.0;
        // a broken bond or unbonded pair is an active contact while it overlaps
        const int j = idx[(bigint) i * stride + s];
        if (j < 0) continue;
        if (pair_touches(pair_separation(x, i, j), radius.touch(i, j))) local[3] += 1.0;
      }
    }
  }
  MPI_Allreduce(local, counts, 4, MPI_DOUBLE, MPI_SUM, world);
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeBonds::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax) {
    nmax = atom->nmax;
    memory->destroy(intact_per_atom);
    memory->create(intact_per_atom, nmax, "lattice/bonds:intact");
    vector_atom = intact_per_atom;
  }
  const int nall = atom->nlocal + atom->nghost;
  std::memset(intact_per_atom, 0, sizeof(double) * nall);

  FixLatticeBondStore *store = pair->store();
  const int *idx = pair->partner_index();
  if (store && idx) {
    const int stride = pair->partner_index_stride();
    for (int i = 0; i < atom->nlocal; i++) {
      const LatticeBondState *st = store->states(i);
      for (int s = 0; s < store->record_count(i); s++) {
        if (st[s] != peratom_state) continue;
        intact_per_atom[i] += 1.0;
        const int j = idx[(bigint) i * stride + s];
        if (j >= 0) intact_per_atom[j] += 1.0;
      }
    }
  }
  comm->reverse_comm(this);

  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if (!(mask[i] & groupbit)) intact_per_atom[i] = 0.0;
}

/* ---------------------------------------------------------------------- */

int ComputeLatticeBonds::pack_reverse_comm(int n, int first, double *buf)
{
  for (int i = 0; i < n; i++) buf[i] = intact_per_atom[first + i];
  return n;
}

/* ---------------------------------------------------------------------- */

void ComputeLatticeBonds::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int i = 0; i < n; i++) intact_per_atom[list[i]] += buf[i];
}

/* ---------------------------------------------------------------------- */

double ComputeLatticeBonds::memory_usage()
{
  return (double) nmax * sizeof(double);
}
