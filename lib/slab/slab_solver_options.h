#pragma once
// The slab solver choice (config section solver) without the solvers' types.
#include "base/choice.h"
#include "solver/direct_engine.h"
#include "solver/iterative_options.h"

#include <string>
#include <vector>

namespace anisodwr
{
/// direct: UMFPACK (or MUMPS) on the coupled slab matrix; iterative: Krylov
/// (IterativeOptions); modes: exact solves by the temporal modes of K = T1 (x) S1 +
/// T2 (x) S2, one UMFPACK LU per mode (solver/mode_solver.h; coefficients constant in
/// time, else the coupled direct solve); automatic ("auto"): see
/// SlabSolverOptions::auto_memory_mb.
enum class SolverType
{
  direct,
  iterative,
  automatic,
  modes
};
inline const std::vector<Named<SolverType>> &names(SolverType)
{
  static const std::vector<Named<SolverType>> table{{SolverType::direct, "direct"},
                                                    {SolverType::iterative, "iterative"},
                                                    {SolverType::automatic, "auto"},
                                                    {SolverType::modes, "modes"}};
  return table;
}

/// What a failed Krylov solve does: none = numerical error; direct = redo it by UMFPACK.
enum class Fallback
{
  none,
  direct
};
inline const std::vector<Named<Fallback>> &names(Fallback)
{
  static const std::vector<Named<Fallback>> table{{Fallback::none, "none"},
                                                  {Fallback::direct, "direct"}};
  return table;
}

/// Slab solver choice (config section solver).
struct SlabSolverOptions
{
  SolverType type = SolverType::direct;
  bool reuse_factorization = true;
  /// coefficients that depend on time: interpolate the spatial matrices in time by the
  /// lowest degree (<= 3) that is exact (SlabOperator::matrices_at)
  bool time_interpolation = true;
  /// the sparse direct solver (direct solves, fallbacks)
  DirectEngine direct_solver = DirectEngine::umfpack;
  /// iterative refinement steps per direct solve
  unsigned int refinement_steps = 0;
  /// auto: the mode solver for r >= 1 when one factorization serves all slabs
  /// (coefficients constant in time, reuse_factorization) and the direct solver is
  /// UMFPACK, while its predicted peak fits auto_memory_mb; else UMFPACK on the coupled
  /// matrix while its predicted factorization peak (predicted_lu_mb) is at most
  /// auto_memory_mb (0: half the physical memory); with a factorization per slab
  /// (coefficients that depend on time, or no reuse) iterative from N_space (r+1)^2 >=
  /// auto_threshold (0: by the spatial degree, auto_size_threshold).
  double auto_threshold = 0.;
  double auto_memory_mb = 0.;
  Fallback fallback = Fallback::direct;
  /// auto picks nothing that runs on Trilinos: a direct solver, or the Krylov solve
  /// preconditioned by a frozen operator's modes, which runs on deal.II's GMRES (set by
  /// the DWR loop for concurrent marches: Trilinos is not called from two threads)
  bool no_trilinos = false;
  /// The operator is only solved transposed (the DWR loop's adjoint march): no Dirichlet
  /// lift, so time-interpolated operators keep no unconstrained A at their nodes
  bool transposed_only = false;
  IterativeOptions iterative;
  /// If not empty: the first slab matrix this operator prepares is written to this path
  /// in Matrix Market format (output.dump_slab_loop)
  std::string dump_matrix;

  static SlabSolverOptions direct(bool reuse)
  {
    SlabSolverOptions o;
    o.reuse_factorization = reuse;
    return o;
  }
};
} // namespace anisodwr
