#pragma once
// The slab solver choice (config section solver) without the solvers' types.
#include "base/choice.h"
#include "solver/direct_engine.h"
#include "solver/iterative_options.h"

#include <string>
#include <vector>

namespace anisodwr
{
/// direct: UMFPACK; iterative: Krylov (IterativeOptions); automatic ("auto"): see
/// SlabSolverOptions::auto_memory_mb.
enum class SolverType
{
  direct,
  iterative,
  automatic
};
inline const std::vector<Named<SolverType>> &names(SolverType)
{
  static const std::vector<Named<SolverType>> table{{SolverType::direct, "direct"},
                                                    {SolverType::iterative, "iterative"},
                                                    {SolverType::automatic, "auto"}};
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
  /// the sparse direct solver (direct solves, fallbacks)
  DirectEngine direct_solver = DirectEngine::umfpack;
  /// iterative refinement steps per direct solve
  unsigned int refinement_steps = 0;
  /// auto: UMFPACK while its predicted factorization peak (predicted_lu_mb) is at most
  /// auto_memory_mb (0: half the physical memory); with a factorization per slab
  /// (coefficients that depend on time, or no reuse) iterative from N_space (r+1)^2 >=
  /// auto_threshold (0: by the spatial degree, auto_size_threshold).
  double auto_threshold = 0.;
  double auto_memory_mb = 0.;
  Fallback fallback = Fallback::direct;
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
