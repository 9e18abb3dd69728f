/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.
   Per-atom history that migrates with its atoms and survives restarts.
------------------------------------------------------------------------- */

#include "fix_lattice_atom_history.h"

#include "atom.h"
#include "domain.h"
#include "memory.h"

#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

FixLatticeAtomHistory::FixLatticeAtomHistory(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), nvalues(0), hist(nullptr)
{
}

/* ---------------------------------------------------------------------- */

FixLatticeAtomHistory::~FixLatticeAtomHistory()
{
  if (nvalues) {
    atom->delete_callback(id, Atom::GROW);
    atom->delete_callback(id, Atom::RESTART);
  }
  memory->sfree(hist);
}

/* ---------------------------------------------------------------------- */

void FixLatticeAtomHistory::create_history(int n)
{
  nvalues = n;
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange = nvalues;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

/* ---------------------------------------------------------------------- */

void FixLatticeAtomHistory::grow_arrays(int nmax)
{
  hist = (double *) memory->srealloc(hist, sizeof(double) * nvalues * (bigint) nmax,
                                     "lattice:history");
}

/* ---------------------------------------------------------------------- */

void FixLatticeAtomHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  std::memcpy(history(j), history(i), sizeof(double) * nvalues);
}

/* ---------------------------------------------------------------------- */

int FixLatticeAtomHistory::pack_exchange(int i, double *buf)
{
  std::memcpy(buf, history(i), sizeof(double) * nvalues);
  return nvalues;
}

/* ---------------------------------------------------------------------- */

int FixLatticeAtomHistory::unpack_exchange(int nlocal, double *buf)
{
  std::memcpy(history(nlocal), buf, sizeof(double) * nvalues);
  return nvalues;
}

/* ----------------------------------------------------------------------
   restart layout per atom: total length (LAMMPS convention), then values
------------------------------------------------------------------------- */

int FixLatticeAtomHistory::pack_restart(int i, double *buf)
{
  buf[0] = nvalues + 1;
  return 1 + pack_exchange(i, buf + 1);
}

/* ---------------------------------------------------------------------- */

void FixLatticeAtomHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  unpack_exchange(nlocal, &extra[nlocal][m + 1]);
}

/* ---------------------------------------------------------------------- */

int FixLatticeAtomHistory::size_restart(int /*i*/)
{
  return nvalues + 1;
}

/* ---------------------------------------------------------------------- */

int FixLatticeAtomHistory::maxsize_restart()
{
  return nvalues + 1;
}

/* ---------------------------------------------------------------------- */

double FixLatticeAtomHistory::memory_usage()
{
  return (double) atom->nmax * nvalues * sizeof(double);
}

