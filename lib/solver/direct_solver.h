#pragma once
// UMFPACK for a deal.II SparseMatrix, with the analysis split from the factorization
// and UMFPACK's figures (memory peak, factor size) exposed: solver.type = auto
// predicts the next factorization's peak from them (slab/slab_operator.h).
#include "solver/direct_engine.h"
#include "solver/umfpack_memory.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace anisodwr
{
class MumpsSolver;

/// UMFPACK's own figures for one matrix (MB).
struct DirectSolverInfo
{
  /// after analyze(): UMFPACK's upper bounds from the symbolic analysis (10-33x the
  /// actual peak on slab matrices: doc/results.md)
  double predicted_peak_mb = 0, predicted_factor_mb = 0;
  /// after factorize(): the actual peak of the factorization and the size of the factors
  double peak_mb = 0, factor_mb = 0;
  /// measured (UMFPACK only): the heap peak of the analysis or the factorization,
  /// whichever is larger, with the solver's copy of the matrix, and the heap UMFPACK
  /// holds afterwards (factors and analysis; solver/umfpack_memory.h)
  double heap_peak_mb = 0, heap_held_mb = 0;
};

/// UMFPACK: with 2 refinement steps (UMFPACK's default) the same arithmetic as
/// dealii::SparseDirectUMFPACK (the matrix passed row-wise, so that UMFPACK factors
/// A^T), hence identical solutions. Without refinement the solves do not read A, and
/// its copy is freed after the factorization. MUMPS (engine mumps) behind the same
/// calls; its figures are summed over the MPI ranks.
class DirectSolver
{
public:
  /// `refinement_steps`: iterative refinement steps per solve (UMFPACK's default: 2)
  explicit DirectSolver(unsigned int refinement_steps = 2,
                        DirectEngine engine = DirectEngine::umfpack);
  ~DirectSolver();
  DirectSolver(const DirectSolver &) = delete;
  DirectSolver &operator=(const DirectSolver &) = delete;

  /// Copies A and runs the symbolic analysis (ordering, predicted fill and memory).
  const DirectSolverInfo &analyze(const dealii::SparseMatrix<double> &A);
  /// Numeric factorization of the analyzed matrix (analyze(A) first if `A` is given).
  void factorize();
  void factorize(const dealii::SparseMatrix<double> &A);
  /// x := A^{-1} x, or A^{-T} x.
  void solve(dealii::Vector<double> &x, bool transpose = false) const;

  bool factorized() const;
  const DirectSolverInfo &info() const { return figures; }
  /// Frees the factors, the analysis and the figures.
  void clear();

private:
  std::vector<long> Ap, Ai;
  std::vector<double> Ax;
  std::size_t n_rows = 0;
  double control[20];
  void *symbolic = nullptr, *numeric = nullptr;
  DirectSolverInfo figures;
  umfpack::HeapMeter meter;
  /// the heap bytes of the copy of A (Ap, Ai, Ax)
  double copy_mb() const;
  std::unique_ptr<MumpsSolver> mumps; // engine mumps
  void release_matrix();
};
} // namespace anisodwr
