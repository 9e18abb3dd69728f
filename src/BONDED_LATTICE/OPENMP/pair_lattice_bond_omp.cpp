/* ----------------------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: pair_style lattice/bond/omp.
------------------------------------------------------------------------- */

#include "pair_lattice_bond_omp.h"

#include "pair_lattice_bond_eval.h"

#include "atom.h"
#include "comm.h"
#include "suffix.h"
#include "timer.h"

#include "omp_compat.h"

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

PairLatticeBondOMP::PairLatticeBondOMP(LAMMPS *lmp) :
    PairLatticeBond(lmp), ThrOMP(lmp, THR_PAIR), eflag_step(0), vflag_step(0)
{
  suffix_flag |= Suffix::OMP;
  // ThrOMP::reduce_thr() sums the threads' f . r virial (virial_fdotr_compute per thread)
  virial_in_threads = true;
}

/* ---------------------------------------------------------------------- */

void PairLatticeBondOMP::compute(int eflag, int vflag)
{
  eflag_step = eflag;
  vflag_step = vflag;
  PairLatticeBond::compute(eflag, vflag);
}

/* ----------------------------------------------------------------------
   the compiled loop of this step on comm->nthreads threads: thread t takes
   the records of its block of local particles (loop_setup_thr)
------------------------------------------------------------------------- */

void PairLatticeBondOMP::run_force_loop()
{
  check_spring_components();
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int nthreads = comm->nthreads;
  thread_heat.assign(3 * (size_t) nthreads, 0.0);
  const ThreadFn loop = THREAD_TABLE[scene_features()];

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(loop, nlocal, nall, nthreads)
#endif
  {
    int ifrom, ito, tid;
    loop_setup_thr(ifrom, ito, tid, nlocal, nthreads);
    ThrData *thr = fix->get_thr(tid);
    thr->timer(Timer::START);
    ev_setup_thr(eflag_step, vflag_step, nall, eatom, vatom, nullptr, thr);
    (this->*loop)(ifrom, ito, tid, thr);
    thr->timer(Timer::PAIR);
    reduce_thr(this, eflag_step, vflag_step, thr);
  }
  for (int t = 0; t < nthreads; t++)
    for (int k = 0; k < 3; k++) heat[k] += thread_heat[3 * t + k];
}

/* ---------------------------------------------------------------------- */

template <int F> void PairLatticeBondOMP::eval_thread(int ifrom, int ito, int tid, ThrData *thr)
{
  ThreadTally tally{this, thr, thread_heat.data() + 3 * tid};
  eval<F>(ifrom, ito, reinterpret_cast<double(*)[3]>(thr->get_f()[0]), tally);
}

template <std::size_t... I>
constexpr std::array<PairLatticeBondOMP::ThreadFn, sizeof...(I)>
PairLatticeBondOMP::make_thread_table(std::index_sequence<I...>)
{
  return {&PairLatticeBondOMP::eval_thread<loop_variant(static_cast<int>(I))>...};
}

const std::array<PairLatticeBondOMP::ThreadFn, PairLatticeBond::LB_NFEATURES>
    PairLatticeBondOMP::THREAD_TABLE =
        PairLatticeBondOMP::make_thread_table(std::make_index_sequence<LB_NFEATURES>{});

/* ---------------------------------------------------------------------- */

double PairLatticeBondOMP::memory_usage()
{
  double bytes = memory_usage_thr();
  bytes += PairLatticeBond::memory_usage();
  return bytes;
}
