/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Stopping a run with a message that reaches the user: see lattice_errors.h
------------------------------------------------------------------------- */

#include "lattice_errors.h"

#include "comm.h"
#include "error.h"
#include "exceptions.h"
#include "lammps.h"

#include <chrono>
#include <cstdio>
#include <thread>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

void LAMMPS_NS::lattice_error_one(LAMMPS *lmp, const char *file, int line,
                                  const std::string &message)
{
  try {
    lmp->error->one(file, line, message);
  } catch (LAMMPSException &) {
    // error->one has written the message and throws; lmp aborts on catching it
    if (lmp->screen) fflush(lmp->screen);
    if (lmp->logfile) fflush(lmp->logfile);
    fflush(stdout);
    fflush(stderr);
    if (lmp->comm->nprocs > 1)
      std::this_thread::sleep_for(std::chrono::duration<double>(ABORT_GRACE_SECONDS));
    throw;
  }
}

/* ---------------------------------------------------------------------- */

void LAMMPS_NS::lattice_error_from_any_rank(LAMMPS *lmp, const char *file, int line, bool mine,
                                            const std::string &message)
{
  const int nprocs = lmp->comm->nprocs, me = lmp->comm->me;
  int rank = mine ? me : nprocs, first = nprocs;
  MPI_Allreduce(&rank, &first, 1, MPI_INT, MPI_MIN, lmp->world);
  if (first >= nprocs) return;
  int len = (me == first) ? (int) message.size() : 0;
  MPI_Bcast(&len, 1, MPI_INT, first, lmp->world);
  std::string text = (me == first) ? message : std::string(len, ' ');
  MPI_Bcast(&text[0], len, MPI_CHAR, first, lmp->world);
  lmp->error->all(file, line, text);
}
