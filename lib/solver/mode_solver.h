#pragma once
// Exact (direct) solves of a two-term Kronecker sum K = T1 (x) S1 + T2 (x) S2 by its
// temporal modes (solver/temporal_schur.h): one real UMFPACK LU of t S1 + S2 per real
// eigenvalue t of T2^{-1} T1 and one complex LU of (alpha + i beta) S1 + S2 per complex
// pair, then block back substitution over the quasi-triangular Schur factor. K itself
// is never assembled or factorized; the factors take about (r+1) fill(N_space) instead
// of the coupled slab matrix's (r+1)^2 fill(N_space).
//
// The transposed solve (the adjoint's K^T) uses the same factors and the same Schur
// form: K^T = (Q (x) I)(T^T (x) S1^T + I (x) S2^T)(Q^T T2^T (x) I), a block forward
// substitution with the transposed mode solves.
#include "solver/complex_direct_solver.h"
#include "solver/direct_solver.h"
#include "solver/iterative_solver.h"
#include "solver/temporal_schur.h"
#include "solver/mode_figures.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace anisodwr
{
class ModeDirectSolver
{
public:
  /// `refinement_steps`: UMFPACK's iterative refinement steps per mode solve.
  explicit ModeDirectSolver(unsigned int refinement_steps = 0);
  ~ModeDirectSolver();

  /// Schur form of k.T2^{-1} k.T1 and one LU per mode. Keeps a pointer to k.S1 (the
  /// coupling of the Schur form): S1 must stay alive and unchanged while solving; S2 is
  /// not needed after this call.
  void factorize(const KronSplit &k);
  /// x := K^{-1} x, or K^{-T} x (interleaved vectors, i*m + k).
  void solve(dealii::Vector<double> &x, bool transpose = false) const;

  bool factorized() const { return S1 != nullptr; }
  void clear();

  const TemporalSchur &schur() const { return form; }
  /// Sum of the factor sizes of all modes (MB, UMFPACK's figures).
  double factor_mb() const { return factors_mb; }
  /// The largest memory UMFPACK held during the factorizations (MB): the factors of the
  /// modes already done plus the peak of the current one, maximized over the modes.
  double peak_mb() const { return peak; }
  /// Factor size and peak of the largest real and of the largest complex mode LU (MB).
  const ModeLuFigures &mode_figures() const { return figures; }

private:
  unsigned int refinement_steps;
  TemporalSchur form;
  /// T2^{-T} Q: the scatter of the transposed solve
  dealii::FullMatrix<double> RT;
  const dealii::SparseMatrix<double> *S1 = nullptr;
  /// per block of the Schur form: a real LU (1x1) or a complex LU (2x2)
  std::vector<std::unique_ptr<DirectSolver>> real_lu;
  std::vector<std::unique_ptr<ComplexDirectSolver>> complex_lu;
  double factors_mb = 0, peak = 0;
  ModeLuFigures figures;

  void solve_block(std::size_t b, std::vector<dealii::Vector<double>> &y,
                   bool transpose) const;
};
} // namespace anisodwr
