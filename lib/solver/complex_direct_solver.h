#pragma once
// UMFPACK's complex LU (umfpack_zl) of C = z S1 + S2 for a complex shift z and two real
// sparse matrices on one sparsity pattern: the 2x2 blocks (complex pairs) of the
// temporal mode solver (solver/mode_solver.h). The real and imaginary parts are kept
// in separate arrays; nothing of size 2n x 2n is formed.
#include "solver/direct_solver.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <complex>
#include <vector>

namespace anisodwr
{
class ComplexDirectSolver
{
public:
  /// `refinement_steps`: UMFPACK's iterative refinement steps per solve.
  explicit ComplexDirectSolver(unsigned int refinement_steps = 0);
  ~ComplexDirectSolver();
  ComplexDirectSolver(const ComplexDirectSolver &) = delete;
  ComplexDirectSolver &operator=(const ComplexDirectSolver &) = delete;

  /// Analysis and numeric factorization of z S1 + S2 (S1, S2 on one pattern). Without
  /// iterative refinement the copy of the matrix is freed afterwards.
  void factorize(std::complex<double> z, const dealii::SparseMatrix<double> &S1,
                 const dealii::SparseMatrix<double> &S2);
  /// (re + i im) := C^{-1} (re + i im), or C^{-T} (the transpose, not the conjugate
  /// transpose).
  void solve(dealii::Vector<double> &re, dealii::Vector<double> &im,
             bool transpose = false) const;

  bool factorized() const { return numeric != nullptr; }
  /// UMFPACK's figures of the factorization (peak and factor size, MB).
  const DirectSolverInfo &info() const { return figures; }
  void clear();

private:
  std::vector<long> Ap, Ai;
  std::vector<double> Ax, Az;
  std::size_t n_rows = 0;
  double control[20];
  void *numeric = nullptr;
  DirectSolverInfo figures;
};
} // namespace anisodwr
