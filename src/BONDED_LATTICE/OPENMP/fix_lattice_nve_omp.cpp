/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: fix lattice/nve/omp.
------------------------------------------------------------------------- */

#include "fix_lattice_nve_omp.h"

#include "comm.h"

#include "omp_compat.h"

#include <algorithm>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   one block of atoms per thread (comm->nthreads, set by `package omp`)
------------------------------------------------------------------------- */

bool FixLatticeNVEOMP::run_ranges(RangeFn loop, int n, const Measure &m)
{
  const int nthreads = comm->nthreads;
  const int block = n / nthreads + 1;
  int ok = 1;
#if defined(_OPENMP)
#pragma omp parallel for LMP_DEFAULT_NONE LMP_SHARED(loop, n, m, nthreads, block) \
    reduction(& : ok) schedule(static, 1)
#endif
  for (int t = 0; t < nthreads; t++) {
    const int begin = std::min(t * block, n), end = std::min(begin + block, n);
    ok &= (this->*loop)(begin, end, m) ? 1 : 0;
  }
  return ok != 0;
}
