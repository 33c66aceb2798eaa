#include "slab/solver_choice.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>

namespace anisodwr
{
double physical_memory_mb()
{
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? double(pages) * double(size) / (1024. * 1024.) : 8192.;
}

namespace
{
/// The last UMFPACK factorization measured per (degree, m) in this process: unknowns and
/// peak (MB); the primal and the adjoint may march in two threads.
std::map<std::pair<unsigned int, unsigned int>, std::pair<double, double>> lu_records;
std::mutex lu_records_mutex;
} // namespace

double fitted_lu_mb(double n, unsigned int degree, unsigned int m)
{
  // Measured UMFPACK peaks (bytes per slab unknown) on the adaptive meshes of
  // moving_hump and hemker, 1e3-2.4e5 unknowns: Q1 755 (m = 1), 1370 (m = 3); Q2 970,
  // 2040 (doc/results.md, "Slab solvers"), i.e. a work space W plus F per temporal
  // DoF; 25% margin.
  const double W = 450., F = degree > 1 ? 540. : 310.;
  return 1.25 * n * (W + F * m) / (1024. * 1024.);
}

double predicted_lu_mb(double n, unsigned int degree, unsigned int m)
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  const auto record = lu_records.find({degree, m});
  if (record != lu_records.end())
  {
    // UMFPACK's peak per unknown of the last factorization, allowed to grow like log n
    const auto [n0, peak0] = record->second;
    return 1.1 * peak0 * (n / n0) *
           std::max(1., std::log2(std::max(n, 2.)) / std::log2(std::max(n0, 2.)));
  }
  return fitted_lu_mb(n, degree, m);
}

void record_lu(double n, unsigned int degree, unsigned int m, double peak_mb)
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  lu_records[{degree, m}] = {n, peak_mb};
}

void reset_lu_records()
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  lu_records.clear();
}

double auto_memory_budget_mb(const SlabSolverOptions &opt)
{
  return opt.auto_memory_mb > 0 ? opt.auto_memory_mb : physical_memory_mb() / 2.;
}

double auto_size_threshold(const SlabSolverOptions &opt, unsigned int degree)
{
  if (opt.auto_threshold > 0.)
    return opt.auto_threshold;
  // Measured with OpenBLAS (r = 1, moving hump slabs): Q1 iterative 1.5-5x faster from
  // 4e3 on; Q2 even at 2.6e5, 1.8-1.9x faster at 1.05e6; the Q4 adjoint 0.37x at 2.6e5
  // (its ILUs are dense). Q3 lies between; beyond Q4 the Q4 value is kept.
  static constexpr double by_degree[] = {2e4, 3e5, 1e6, 3e6};
  return by_degree[std::min<unsigned int>(std::max(degree, 1u), 4u) - 1];
}

bool auto_picks_iterative(const SlabSolverOptions &opt, double n, unsigned int m,
                          unsigned int degree, bool factorization_reused)
{
  // UMFPACK factorizes once and back-substitutes per slab (1 s/slab against 4.9 s for
  // the best Krylov solver at 2.1e6 unknowns, even with the factorization amortized over
  // 10 slabs): while the factors fit, it wins.
  if (predicted_lu_mb(n, degree, m) > auto_memory_budget_mb(opt))
    return true;
  return !factorization_reused && n * m >= auto_size_threshold(opt, degree);
}

double predicted_modes_mb(double n_space, unsigned int degree, unsigned int m)
{
  // The modes' factors are each about the factor part of one N_space LU; the last
  // factorization adds its work space. A complex pair's LU has twice the values of a
  // real one and about the same integer part: counted as two real LUs.
  return m * predicted_lu_mb(n_space, degree, 1);
}

bool auto_picks_modes(const SlabSolverOptions &opt, double n_space, unsigned int m,
                      unsigned int degree, bool factorization_reused)
{
  return m >= 2 && factorization_reused && opt.direct_solver == DirectEngine::umfpack &&
         predicted_modes_mb(n_space, degree, m) <= auto_memory_budget_mb(opt);
}

bool solves_by_modes(const SlabSolverOptions &options, double n_space, unsigned int m,
                     unsigned int degree, bool coefficients_constant,
                     bool factorization_reused)
{
  return (options.type == SolverType::modes && coefficients_constant) ||
         (options.type == SolverType::automatic &&
          auto_picks_modes(options, n_space, m, degree, factorization_reused));
}

bool releases_assembly_matrices(const SlabSolverOptions &options,
                                bool coefficients_constant)
{
  return coefficients_constant && options.reuse_factorization &&
         options.refinement_steps == 0;
}

bool solves_iteratively(const SlabSolverOptions &options, double n_space, unsigned int m,
                        unsigned int degree, bool factorization_reused)
{
  return options.type == SolverType::iterative ||
         (options.type == SolverType::automatic && !options.direct_only &&
          !auto_picks_modes(options, n_space, m, degree, factorization_reused) &&
          auto_picks_iterative(options, n_space * m, m, degree, factorization_reused));
}
} // namespace anisodwr
