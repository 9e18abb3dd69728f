/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   Per-atom bond and contact records owned by pair_style lattice/bond.

   The fix is created by pair_style lattice/bond at the first run.  It keeps
   the records with their atoms when atoms migrate between ranks, are sorted,
   or are written to and read from restart files.
------------------------------------------------------------------------- */

#include "fix_lattice_bond_store.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixLatticeBondStore::FixLatticeBondStore(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), nrec(nullptr), rec(nullptr), bonds_created(0), nmax_store(0)
{
  if (narg != 4) error->all(FLERR, "Illegal fix {} command: expected one argument (maxslot)", style);
  maxslot = utils::inumeric(FLERR, arg[3], false, lmp);
  if (maxslot < 1) error->all(FLERR, "Fix {} maxslot {} must be >= 1", style, maxslot);

  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange = 1 + maxslot * RECORD_DOUBLES;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nmax; i++) nrec[i] = 0;
}

/* ---------------------------------------------------------------------- */

FixLatticeBondStore::~FixLatticeBondStore()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(nrec);
  memory->sfree(rec);
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::setmask()
{
  return 0;
}

/* ---------------------------------------------------------------------- */

LatticeBondRecord *FixLatticeBondStore::add_record(int i)
{
  if (nrec[i] >= maxslot)
    error->one(FLERR,
               "Atom {} has more than maxslot = {} bonds and contacts; "
               "increase the pair_style lattice/bond keyword maxslot",
               atom->tag[i], maxslot);
  LatticeBondRecord *r = records(i) + nrec[i]++;
  std::memset(r, 0, sizeof(LatticeBondRecord));
  return r;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::remove_record(int i, int slot)
{
  LatticeBondRecord *r = records(i);
  const int last = --nrec[i];
  if (slot != last) r[slot] = r[last];
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::grow_arrays(int nmax)
{
  memory->grow(nrec, nmax, "lattice/bond/store:nrec");
  rec = (LatticeBondRecord *) memory->srealloc(rec, (bigint) nmax * maxslot * sizeof(LatticeBondRecord),
                                               "lattice/bond/store:rec");
  nmax_store = nmax;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::copy_arrays(int i, int j, int /*delflag*/)
{
  nrec[j] = nrec[i];
  if (nrec[i]) std::memcpy(records(j), records(i), nrec[i] * sizeof(LatticeBondRecord));
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::set_arrays(int i)
{
  nrec[i] = 0;
}

/* ----------------------------------------------------------------------
   one atom's records as doubles: count, then 8 values per record
------------------------------------------------------------------------- */

int FixLatticeBondStore::pack_atom(int i, double *buf) const
{
  int m = 0;
  buf[m++] = ubuf(nrec[i]).d;
  const LatticeBondRecord *r = records(i);
  for (int s = 0; s < nrec[i]; s++) {
    buf[m++] = ubuf(r[s].partner).d;
    buf[m++] = ubuf(r[s].state).d;
    for (int k = 0; k < 3; k++) buf[m++] = r[s].shear[k];
    for (int k = 0; k < 3; k++) buf[m++] = r[s].dx_prev[k];
  }
  return m;
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::unpack_atom(int i, const double *buf)
{
  int m = 0;
  const int n = (int) ubuf(buf[m++]).i;
  if (n > maxslot)
    error->one(FLERR,
               "Atom {} carries {} bond records but maxslot is {}; use a pair_style "
               "lattice/bond maxslot of at least {}",
               atom->tag[i], n, maxslot, n);
  nrec[i] = n;
  LatticeBondRecord *r = records(i);
  for (int s = 0; s < n; s++) {
    r[s].partner = (tagint) ubuf(buf[m++]).i;
    r[s].state = (int) ubuf(buf[m++]).i;
    for (int k = 0; k < 3; k++) r[s].shear[k] = buf[m++];
    for (int k = 0; k < 3; k++) r[s].dx_prev[k] = buf[m++];
  }
  return m;
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::pack_exchange(int i, double *buf)
{
  return pack_atom(i, buf);
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::unpack_exchange(int nlocal, double *buf)
{
  return unpack_atom(nlocal, buf);
}

/* ----------------------------------------------------------------------
   restart layout per atom: total length (LAMMPS convention), then the
   same layout as pack_exchange
------------------------------------------------------------------------- */

int FixLatticeBondStore::pack_restart(int i, double *buf)
{
  const int m = pack_atom(i, buf + 1);
  buf[0] = m + 1;
  return m + 1;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  unpack_atom(nlocal, &extra[nlocal][m + 1]);
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::size_restart(int i)
{
  return 2 + nrec[i] * RECORD_DOUBLES;
}

/* ---------------------------------------------------------------------- */

int FixLatticeBondStore::maxsize_restart()
{
  return 2 + maxslot * RECORD_DOUBLES;
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    double list[2] = {(double) bonds_created, (double) maxslot};
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 2, fp);
  }
}

/* ---------------------------------------------------------------------- */

void FixLatticeBondStore::restart(char *buf)
{
  auto list = (double *) buf;
  bonds_created = static_cast<int>(list[0]);
}

/* ---------------------------------------------------------------------- */

double FixLatticeBondStore::memory_usage()
{
  return (double) nmax_store * (sizeof(int) + (double) maxslot * sizeof(LatticeBondRecord));
}
