#include "slab/auto_solver.h"

#include "solver/iterative_solver.h"
#include "solver/temporal_schur.h"
#include "time/temporal_basis.h"

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
/// The last UMFPACK factorization measured per (degree, m) in this process: unknowns,
/// heap peak and heap held afterwards (MB); the primal and the adjoint may march in two
/// threads.
struct LuRecord
{
  double n = 0, peak = 0, held = 0;
};
std::map<std::pair<unsigned int, unsigned int>, LuRecord> lu_records;
std::mutex lu_records_mutex;
/// One kind of mode LU per degree: unknowns, factor and peak (MB) of the last one.
struct ModeRecord
{
  double n = 0, factor = 0, peak = 0;
};
std::map<std::pair<unsigned int, bool>, ModeRecord> mode_records; // (degree, complex)

/// fitted_lu_mb's factor part: F bytes per slab unknown and temporal DoF, 25% margin (MB).
double fitted_factor_mb(double n, unsigned int degree, unsigned int m)
{
  const double F = degree > 1 ? 540. : 310.;
  return 1.25 * n * F * m / (1024. * 1024.);
}
} // namespace

double fitted_lu_mb(double n, unsigned int degree, unsigned int m)
{
  // Measured UMFPACK peaks (bytes per slab unknown) on the adaptive meshes of
  // moving_hump and hemker, 1e3-2.4e5 unknowns: Q1 755 (m = 1), 1370 (m = 3); Q2 970,
  // 2040 (doc/results.md, "Slab solvers"), i.e. a work space W plus F per temporal
  // DoF; 25% margin. Plus the solver's copy of the matrix (8-byte indices and values,
  // (degree + 2)^2 m entries per row on a uniform mesh), which the measured heap peaks
  // of record_lu include.
  const double W = 450.;
  const double copy = 16. * (degree + 2.) * (degree + 2.) * m + 8.;
  return n * (1.25 * W + copy) / (1024. * 1024.) + fitted_factor_mb(n, degree, m);
}

namespace
{
/// Size per unknown of a record at n0, at n: growing like log n.
double extrapolate(double value, double n0, double n)
{
  return value * (n / n0) *
         std::max(1., std::log2(std::max(n, 2.)) / std::log2(std::max(n0, 2.)));
}
} // namespace

double predicted_lu_mb(double n, unsigned int degree, unsigned int m)
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  const auto record = lu_records.find({degree, m});
  if (record != lu_records.end())
    return extrapolate(record->second.peak, record->second.n, n);
  return fitted_lu_mb(n, degree, m);
}

double predicted_lu_held_mb(double n, unsigned int degree, unsigned int m)
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  const auto record = lu_records.find({degree, m});
  if (record != lu_records.end())
    return extrapolate(record->second.held, record->second.n, n);
  return fitted_factor_mb(n, degree, m);
}

void record_lu(double n, unsigned int degree, unsigned int m, double peak_mb, double held_mb)
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  lu_records[{degree, m}] = {n, peak_mb, held_mb};
}

void reset_lu_records()
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  lu_records.clear();
  mode_records.clear();
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
  if (auto_memory_margin * predicted_lu_mb(n, degree, m) > auto_memory_budget_mb(opt))
    return true;
  return !factorization_reused && n * m >= auto_size_threshold(opt, degree);
}

std::vector<unsigned int> mode_blocks(unsigned int m)
{
  // the real Schur form of dG(m-1)'s T2^{-1} T1 (tau = 1: tau scales every eigenvalue
  // alike and leaves the order), once per m
  static std::map<unsigned int, std::vector<unsigned int>> cache;
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  auto &blocks = cache[m];
  if (blocks.empty() && m > 0)
  {
    const TemporalBasis basis(m - 1);
    for (const auto &b : TemporalSchur(basis.derivative_with_jump(), basis.mass()).blocks)
      blocks.push_back(b.size);
  }
  return blocks;
}

ModesMemory predicted_modes_memory(double n_space, unsigned int degree, unsigned int m)
{
  // Without a record: fitted_lu_mb's work space and factor part for one real LU; a
  // complex LU holds 1.8 times the real factors (measured on moving_hump: 1.80 for Q2
  // and Q3) and about the same work space.
  const double fit = fitted_lu_mb(n_space, degree, 1),
               fit_factor = fitted_factor_mb(n_space, degree, 1);
  ModeRecord real{n_space, fit_factor, fit},
      complex{n_space, 1.8 * fit_factor, fit + 0.8 * fit_factor};
  {
    const std::lock_guard<std::mutex> lock(lu_records_mutex);
    for (const bool is_complex : {false, true})
    {
      const auto r = mode_records.find({degree, is_complex});
      if (r != mode_records.end())
        (is_complex ? complex : real) =
            ModeRecord{n_space, extrapolate(r->second.factor, r->second.n, n_space),
                       extrapolate(r->second.peak, r->second.n, n_space)};
    }
  }
  // each mode's factorization peak beside the factors of the modes before it, in the
  // order of the Schur form's blocks
  ModesMemory mem;
  for (const unsigned int size : mode_blocks(m))
  {
    const ModeRecord &mode = size == 2 ? complex : real;
    mem.peak_mb = std::max(mem.peak_mb, mem.factors_mb + mode.peak);
    mem.factors_mb += mode.factor;
  }
  return mem;
}

double predicted_modes_mb(double n_space, unsigned int degree, unsigned int m)
{
  return predicted_modes_memory(n_space, degree, m).peak_mb;
}

void record_modes(double n_space, unsigned int degree, const ModeLuFigures &f)
{
  const std::lock_guard<std::mutex> lock(lu_records_mutex);
  if (f.real_peak_mb > 0)
    mode_records[{degree, false}] = {n_space, f.real_factor_mb, f.real_peak_mb};
  if (f.complex_peak_mb > 0)
    mode_records[{degree, true}] = {n_space, f.complex_factor_mb, f.complex_peak_mb};
}

bool auto_picks_modes(const SlabSolverOptions &opt, double n_space, unsigned int m,
                      unsigned int degree, bool factorization_reused)
{
  return m >= 2 && factorization_reused && opt.direct_solver == DirectEngine::umfpack &&
         auto_memory_margin * predicted_modes_mb(n_space, degree, m) <=
             auto_memory_budget_mb(opt);
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

bool auto_picks_frozen_modes(const SlabSolverOptions &opt, double n_space, unsigned int m,
                             unsigned int degree, bool coefficients_constant)
{
  return !coefficients_constant && opt.reuse_factorization &&
         opt.direct_solver == DirectEngine::umfpack &&
         auto_memory_margin * predicted_modes_mb(n_space, degree, m) <=
             auto_memory_budget_mb(opt);
}

bool solves_by_frozen_modes(const SlabSolverOptions &options, double n_space,
                            unsigned int m, unsigned int degree, bool coefficients_constant)
{
  return (options.type == SolverType::iterative &&
          options.iterative.preconditioner == Preconditioner::modes) ||
         (options.type == SolverType::automatic &&
          auto_picks_frozen_modes(options, n_space, m, degree, coefficients_constant));
}

bool solves_iteratively(const SlabSolverOptions &options, double n_space, unsigned int m,
                        unsigned int degree, bool coefficients_constant)
{
  const bool reused = options.reuse_factorization && coefficients_constant;
  return options.type == SolverType::iterative ||
         (options.type == SolverType::automatic &&
          (auto_picks_frozen_modes(options, n_space, m, degree, coefficients_constant) ||
           (!options.no_trilinos && !auto_picks_modes(options, n_space, m, degree, reused) &&
            auto_picks_iterative(options, n_space * m, m, degree, reused))));
}

bool solves_without_trilinos(const SlabSolverOptions &options, double n_space,
                             unsigned int m, unsigned int degree, bool coefficients_constant)
{
  if (!solves_iteratively(options, n_space, m, degree, coefficients_constant))
    return true;
  // auto's frozen-modes path always runs GMRES (SlabOperator::choose_solver)
  return options.type == SolverType::automatic
             ? auto_picks_frozen_modes(options, n_space, m, degree, coefficients_constant)
             : IterativeSlabSolver::runs_without_trilinos(options.iterative);
}
} // namespace anisodwr
