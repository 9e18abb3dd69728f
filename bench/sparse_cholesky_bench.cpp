// Timing of LatticeSparseCholesky on the scenes' triangular lattice (bench/sparse_cholesky.py
// compiles and runs it).  Usage: sparse_cholesky_bench NX NY [LEAF] [MODS] [THREADS]
// NX x NY nodes (rows along x, odd rows shifted by 1/2), 2 free dof per node, the bottom and
// top rows held, one spring per nearest-neighbour pair with k Gaussian (mean 1, sd 0.15,
// redrawn until positive).  THREADS: comma-separated thread counts (e.g. 1,2): per count, the
// factorisation and the best of 5 solves of the same factor (wall and process CPU time), and
// whether the factor and the
// solution are bit-identical to those of the first count (a hash of their bits), and the cores
// the machine offers at that moment: nt x (time of a fixed arithmetic loop on one thread) / (time
// of the same loop on each of nt threads at once), nt for an idle machine.  Prints "name value"
// lines.

#include "lattice_sparse_cholesky.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <vector>

using LAMMPS_NS::LatticeSparseCholesky;
using LAMMPS_NS::LatticeSpring;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// r = K x - b on the free dofs (springs only, no shift), returns ||r|| / ||b||
double residual(const std::vector<LatticeSpring> &springs, const std::vector<unsigned char> &free,
                double shift, const std::vector<double> &x, const std::vector<double> &b)
{
  std::vector<double> r(x.size(), 0.0);
  for (const auto &s : springs) {
    double e = 0.0;    // g . x
    for (int c = 0; c < 2; ++c) e += s.n[c] * (x[2 * s.b + c] * free[2 * s.b + c] - x[2 * s.a + c] * free[2 * s.a + c]);
    for (int c = 0; c < 2; ++c) {
      r[2 * s.b + c] += s.k * e * s.n[c];
      r[2 * s.a + c] -= s.k * e * s.n[c];
    }
  }
  double num = 0.0, den = 0.0;
  for (std::size_t d = 0; d < x.size(); ++d)
    if (free[d]) {
      const double v = r[d] + shift * x[d] - b[d];
      num += v * v;
      den += b[d] * b[d];
    }
  return std::sqrt(num / den);
}

// FNV-1a over the bits of n doubles, folded into h
std::uint64_t hash_bits(const double *v, std::size_t n, std::uint64_t h)
{
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t b;
    std::memcpy(&b, v + i, sizeof b);
    for (int q = 0; q < 8; ++q) {
      h ^= (b >> (8 * q)) & 0xffu;
      h *= 1099511628211ull;
    }
  }
  return h;
}

// user + system CPU time of the process (all its threads)
double cpu_seconds()
{
  rusage r;
  getrusage(RUSAGE_SELF, &r);
  return r.ru_utime.tv_sec + 1e-6 * r.ru_utime.tv_usec + r.ru_stime.tv_sec + 1e-6 * r.ru_stime.tv_usec;
}

// nt x (a fixed loop on one thread) / (the loop on each of nt threads at once): the cores free
double free_cores(int nt)
{
  static volatile double sink;
  auto loop = [] {
    double s = 0.0;
    for (long i = 0; i < 150000000L; ++i) s += (double) i * 1e-9;
    sink = s;
  };
  auto t0 = std::chrono::steady_clock::now();
  loop();
  const double t1 = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> th;
  for (int k = 0; k < nt; ++k) th.emplace_back(loop);
  for (auto &t : th) t.join();
  return nt * t1 / seconds_since(t0);
}

std::uint64_t hash_factor(const LatticeSparseCholesky &chol)
{
  std::uint64_t h = 1469598103934665603ull;
  for (int t = 0; t < chol.ntree(); ++t) {
    const std::size_t n = chol.col_end(t) - chol.col_begin(t);
    h = hash_bits(chol.block(t), (n + chol.nrows(t)) * n, h);
  }
  return h;
}

}    // namespace

int main(int argc, char **argv)
{
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s NX NY [LEAF] [MODS]\n", argv[0]);
    return 2;
  }
  const int nx = std::atoi(argv[1]), ny = std::atoi(argv[2]);
  const int leaf = argc > 3 ? std::atoi(argv[3]) : 0;
  const int mods = argc > 4 ? std::atoi(argv[4]) : 50;
  std::vector<int> thread_counts;
  if (argc > 5)
    for (const char *p = argv[5]; *p;) {
      char *end = nullptr;
      const long v = std::strtol(p, &end, 10);
      if (end == p || v < 1) {
        std::fprintf(stderr, "THREADS %s: comma-separated counts >= 1 expected\n", argv[5]);
        return 2;
      }
      thread_counts.push_back((int) v);
      p = (*end == ',') ? end + 1 : end;
    }
  const int n = nx * ny;
  std::vector<double> coords;
  const double row = std::sqrt(3.0) / 2.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      coords.push_back(i + 0.5 * (j % 2));
      coords.push_back(j * row);
    }
  std::vector<std::pair<int, int>> pairs;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int u = j * nx + i;
      if (i + 1 < nx) pairs.push_back({u, u + 1});
      if (j + 1 < ny) {
        const int lo = (j % 2) ? i : i - 1;
        for (int ii = lo; ii <= lo + 1; ++ii)
          if (ii >= 0 && ii < nx) pairs.push_back({u, (j + 1) * nx + ii});
      }
    }
  std::vector<unsigned char> free(2 * n, 1);
  for (int i = 0; i < nx; ++i) {
    free[2 * i] = free[2 * i + 1] = 0;
    free[2 * ((ny - 1) * nx + i)] = free[2 * ((ny - 1) * nx + i) + 1] = 0;
  }
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> gauss(1.0, 0.15);
  std::vector<LatticeSpring> springs;
  double ksum = 0.0;
  for (const auto &p : pairs) {
    double k;
    do k = gauss(rng);
    while (!(k > 0.0));
    LatticeSpring s{p.first, p.second, k, {0.0, 0.0, 0.0}};
    double len = 0.0;
    for (int c = 0; c < 2; ++c) {
      s.n[c] = coords[2 * p.second + c] - coords[2 * p.first + c];
      len += s.n[c] * s.n[c];
    }
    for (int c = 0; c < 2; ++c) s.n[c] /= std::sqrt(len);
    springs.push_back(s);
    ksum += k;
  }
  const double shift = 1e-10 * ksum / springs.size();

  LatticeSparseCholesky chol;
  if (leaf > 0) chol.set_leaf_size(leaf);
  auto t0 = std::chrono::steady_clock::now();
  chol.analyse(2, n, coords.data(), free, pairs);
  const double t_analyse = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  chol.factorise(springs, shift);
  const double t_factor = seconds_since(t0);

  std::uniform_real_distribution<double> unif(-1.0, 1.0);
  std::vector<double> b(2 * n, 0.0);
  for (int d = 0; d < 2 * n; ++d)
    if (free[d]) b[d] = unif(rng);
  std::vector<double> x = b;
  t0 = std::chrono::steady_clock::now();
  chol.solve(x.data());
  const double t_solve = seconds_since(t0);
  const double res = residual(springs, free, shift, x, b);

  // the same factorisation and solve on each thread count
  std::uint64_t h_factor0 = 0, h_x0 = 0;
  for (std::size_t q = 0; q < thread_counts.size(); ++q) {
    const int nt = thread_counts[q];
    chol.set_threads(nt);
    double c0 = cpu_seconds();
    t0 = std::chrono::steady_clock::now();
    chol.factorise(springs, shift);
    const double tf = seconds_since(t0), cf = cpu_seconds() - c0;
    double ts = 1e30, cs = 1e30;
    std::vector<double> xt;
    for (int rep = 0; rep < 5; ++rep) {
      xt = b;
      c0 = cpu_seconds();
      t0 = std::chrono::steady_clock::now();
      chol.solve(xt.data());
      ts = std::min(ts, seconds_since(t0));
      cs = std::min(cs, cpu_seconds() - c0);
    }
    const std::uint64_t hf = hash_factor(chol), hx = hash_bits(xt.data(), xt.size(), 1469598103934665603ull);
    if (q == 0) {
      h_factor0 = hf;
      h_x0 = hx;
    }
    const std::string tag = "_t" + std::to_string(nt);
    std::printf("free_cores%s %.3f\n", tag.c_str(), free_cores(nt));
    std::printf("factorise_s%s %.4f\nsolve_best5_s%s %.5f\n", tag.c_str(), tf, tag.c_str(), ts);
    std::printf("factorise_cpu_s%s %.4f\nsolve_cpu_best5_s%s %.5f\n", tag.c_str(), cf, tag.c_str(), cs);
    std::printf("solve_tasks%s %d\nfactorise_tasks%s %d\n", tag.c_str(), chol.solve_tasks(),
                tag.c_str(), chol.factorise_tasks());
    std::printf("identical%s %d\n", tag.c_str(), (int) (hf == h_factor0 && hx == h_x0));
  }
  chol.set_threads(1);

  // downdates of distinct random springs, then the same springs added back
  std::vector<std::size_t> pick;
  std::uniform_int_distribution<std::size_t> which(0, springs.size() - 1);
  std::vector<unsigned char> taken(springs.size(), 0);
  while ((int) pick.size() < mods) {
    const std::size_t s = which(rng);
    if (!taken[s]) {
      taken[s] = 1;
      pick.push_back(s);
    }
  }
  double path_entries = 0.0;
  for (std::size_t s : pick)
    for (int t : chol.path(springs[s].a, springs[s].b))
      path_entries += (double) (chol.col_end(t) - chol.col_begin(t)) *
          (chol.col_end(t) - chol.col_begin(t) + chol.nrows(t));
  t0 = std::chrono::steady_clock::now();
  for (std::size_t s : pick) chol.modify(springs[s], -1);
  const double t_down = seconds_since(t0) / mods;
  std::vector<LatticeSpring> now;
  for (std::size_t s = 0; s < springs.size(); ++s)
    if (!taken[s]) now.push_back(springs[s]);
  x = b;
  chol.solve(x.data());
  const double res_down = residual(now, free, shift, x, b);
  // the same spring set factorised afresh: what the downdated factor's residual compares with
  double res_fresh = 0.0;
  {
    LatticeSparseCholesky fresh;
    if (leaf > 0) fresh.set_leaf_size(leaf);
    fresh.analyse(2, n, coords.data(), free, pairs);
    fresh.factorise(now, shift);
    std::vector<double> xf = b;
    fresh.solve(xf.data());
    res_fresh = residual(now, free, shift, xf, b);
  }
  t0 = std::chrono::steady_clock::now();
  for (std::size_t s : pick) chol.modify(springs[s], +1);
  const double t_up = seconds_since(t0) / mods;
  x = b;
  chol.solve(x.data());
  const double res_up = residual(springs, free, shift, x, b);

  std::printf("nodes %d\nfree_dof %d\nsprings %zu\nleaf_size %d\n", n, chol.ncols(), springs.size(),
              chol.leaf_size());
  std::printf("analyse_s %.4f\nfactorise_s %.4f\nsolve_s %.4f\n", t_analyse, t_factor, t_solve);
  std::printf("downdate_s %.6f\nupdate_s %.6f\npath_block_entries %.4e\n", t_down, t_up,
              path_entries / mods);
  double flops = 0.0;    // leading terms: Cholesky n^3/3, triangular solve r n^2, rank-n update r^2 n
  for (int t = 0; t < chol.ntree(); ++t) {
    const double nt = chol.col_end(t) - chol.col_begin(t), r = chol.nrows(t);
    flops += nt * nt * nt / 3.0 + r * nt * nt + r * r * nt;
  }
  std::printf("factorise_gflops %.3f\n", 1e-9 * flops / t_factor);
  std::printf("factor_entries %.4e\nfactor_bytes %zu\nwork_bytes %zu\ntree_nodes %d\ndepth %d\n",
              chol.factor_entries(), chol.bytes(), chol.work_bytes(), chol.ntree(), chol.depth());
  std::printf("residual %.3e\nresidual_after_downdates %.3e\nresidual_fresh_factor %.3e\n"
              "residual_after_updates %.3e\n", res, res_down, res_fresh, res_up);
  return 0;
}
