/* -*- c++ -*- ----------------------------------------------------------
   BONDED_LATTICE package for LAMMPS: bonded close-packed lattice DEM.

   LatticeThreadPool: nthreads - 1 workers waiting on a condition variable.
   run() hands out the tasks 0..ntask-1 (an atomic counter) to the workers
   and the calling thread (thread 0) and returns when all are done,
   rethrowing the exception of the lowest task that threw.  One run() at a
   time.  Standalone (C++17 standard library only), like the sparse factor
   that keeps one (lattice_sparse_cholesky.h).

   for_blocks(): a loop over [0, n) cut into blocks of a fixed size (not a
   share per thread), so that whatever a block computes, and any reduction
   made block by block in block order, is the same for any number of
   threads.
------------------------------------------------------------------------- */

#ifndef LMP_LATTICE_THREAD_POOL_H
#define LMP_LATTICE_THREAD_POOL_H

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace LAMMPS_NS {

class LatticeThreadPool {
 public:
  explicit LatticeThreadPool(int nthreads)
  {
    for (int id = 1; id < nthreads; ++id) workers_.emplace_back([this, id] { work(id); });
  }
  ~LatticeThreadPool()
  {
    {
      std::lock_guard<std::mutex> lk(m_);
      stop_ = true;
    }
    start_.notify_all();
    for (auto &w : workers_) w.join();
  }
  int size() const { return (int) workers_.size() + 1; }

  void run(int ntask, const std::function<void(int, int)> &fn)
  {
    if (ntask <= 0) return;
    std::lock_guard<std::mutex> one(run_m_);
    if (workers_.empty() || ntask == 1) {
      for (int k = 0; k < ntask; ++k) fn(k, 0);
      return;
    }
    {
      std::lock_guard<std::mutex> lk(m_);
      job_ = &fn;
      ntask_ = ntask;
      next_.store(0);
      busy_ = (int) workers_.size();
      error_ = nullptr;
      error_task_ = ntask;
      ++generation_;
    }
    start_.notify_all();
    take(0);
    std::unique_lock<std::mutex> lk(m_);
    done_.wait(lk, [this] { return busy_ == 0; });
    job_ = nullptr;
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::vector<std::thread> workers_;
  std::mutex m_, run_m_;
  std::condition_variable start_, done_;
  const std::function<void(int, int)> *job_ = nullptr;
  int ntask_ = 0, busy_ = 0, error_task_ = 0;
  std::atomic<int> next_{0};
  unsigned long generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;

  void take(int id)
  {
    for (int k = next_.fetch_add(1); k < ntask_; k = next_.fetch_add(1)) {
      try {
        (*job_)(k, id);
      } catch (...) {
        std::lock_guard<std::mutex> lk(m_);
        if (k < error_task_) {
          error_ = std::current_exception();
          error_task_ = k;
        }
      }
    }
  }

  void work(int id)
  {
    unsigned long seen = 0;
    for (;;) {
      {
        std::unique_lock<std::mutex> lk(m_);
        start_.wait(lk, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
      }
      take(id);
      std::lock_guard<std::mutex> lk(m_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
};
// fn(block, begin, end) for the blocks [b * block, min(n, (b + 1) * block)) of [0, n),
// on the pool's threads (serially without a pool); the number of blocks
inline std::size_t for_blocks(LatticeThreadPool *pool, std::size_t n, std::size_t block,
                              const std::function<void(std::size_t, std::size_t, std::size_t)> &fn)
{
  const std::size_t nblocks = (n + block - 1) / block;
  if (!pool || nblocks < 2) {
    for (std::size_t b = 0; b < nblocks; ++b) fn(b, b * block, std::min(n, (b + 1) * block));
    return nblocks;
  }
  pool->run((int) nblocks, [&](int b, int) {
    fn((std::size_t) b, (std::size_t) b * block, std::min(n, ((std::size_t) b + 1) * block));
  });
  return nblocks;
}

}    // namespace LAMMPS_NS

#endif
