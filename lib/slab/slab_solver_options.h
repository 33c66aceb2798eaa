#pragma once
// The slab solver choice (config section solver) without the solvers' types.
#include "solver/iterative_options.h"

#include <string>

namespace anisodwr
{
/// Slab solver choice (config section solver).
struct SlabSolverOptions
{
  std::string type = "direct"; ///< direct | iterative | auto
  bool reuse_factorization = true;
  /// UMFPACK's iterative refinement steps per direct solve
  unsigned int refinement_steps = 0;
  /// auto: UMFPACK while its predicted factorization peak (predicted_lu_mb) is at most
  /// auto_memory_mb (0: half the physical memory); with a factorization per slab
  /// (coefficients that depend on time, or no reuse) iterative from N_space (r+1)^2 >=
  /// auto_threshold.
  double auto_threshold = 1e6;
  double auto_memory_mb = 0.;
  std::string fallback = "direct"; ///< none | direct
  IterativeOptions iterative;

  static SlabSolverOptions direct(bool reuse)
  {
    SlabSolverOptions o;
    o.reuse_factorization = reuse;
    return o;
  }
};
} // namespace anisodwr
