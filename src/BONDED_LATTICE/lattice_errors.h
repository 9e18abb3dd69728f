/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   Stopping a run with a message that reaches the user on any number of
   ranks.

   LAMMPS has two ways to stop: error->all, called by every rank (rank 0
   prints the message to the screen and the log file, every rank finalizes
   MPI and exits), and error->one, called by the rank that found the
   problem alone (it prints "ERROR on proc N" to its own screen; LAMMPS opens
   the log file on rank 0 only, so another rank's message is on the screen
   only), after which lmp calls MPI_Abort.  The abort does not wait for the
   output: MPICH's mpiexec kills the job and exits while the last lines the
   aborting rank wrote, even flushed ones, may still be on their way to it,
   and under load the ERROR line is lost (with one core kept busy: 3 of 20
   two-rank runs of an unstable deck; 8 of 40 runs of a C program that
   flushes before MPI_Abort, none with a 2 ms wait before it).  Hence:
   - lattice_error_from_any_rank: at a point every rank reaches (after a
     collective that already exists), the message of the lowest rank that
     has one goes to all, and error->all prints it once, screen and log;
   - lattice_error_one: where only the rank that found the problem knows
     (the force loop has no collective, and adding one to every step would
     cost time), error->one, then the rank flushes its screen, log file and
     stderr and waits ABORT_GRACE_SECONDS before the abort, so that the
     launcher forwards the message first.  The wait is spent only by a run
     that stops, on more than one rank (a single rank exits with its output).
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_ERRORS_H
#define LMP_LATTICE_ERRORS_H

#include <string>

namespace LAMMPS_NS {

class LAMMPS;

// the wait before MPI_Abort of lattice_error_one (a few milliseconds were
// enough in the measurements above; this is ample)
constexpr double ABORT_GRACE_SECONDS = 1.0;

// error->one(file, line, message) on this rank: the message on its screen
// (and log file on rank 0), flushed, then the grace wait on more than one
// rank, then LAMMPS' abort
[[noreturn]] void lattice_error_one(LAMMPS *lmp, const char *file, int line,
                                    const std::string &message);

// collective: if some rank has a message (mine), every rank stops with the
// message of the lowest such rank (error->all: printed once, by rank 0, to
// the screen and the log file); returns if none has one
void lattice_error_from_any_rank(LAMMPS *lmp, const char *file, int line, bool mine,
                                 const std::string &message);

}    // namespace LAMMPS_NS

#endif
