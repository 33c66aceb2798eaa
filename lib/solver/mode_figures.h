#pragma once
// The memory figures of one mode-solver factorization (solver/mode_solver.h), read by
// the memory models (slab/auto_solver.h) without the solver's headers.

namespace anisodwr
{
/// One UMFPACK factorization of the mode solver, by kind: the factor size and the peak
/// (factors plus work space) of its largest real N_space LU and of its largest complex
/// one (MB; 0 where it has none).
struct ModeLuFigures
{
  double real_factor_mb = 0, real_peak_mb = 0;
  double complex_factor_mb = 0, complex_peak_mb = 0;
};
} // namespace anisodwr
