#pragma once
// MUMPS (the Debian build, through its C interface) for a deal.II SparseMatrix, on the
// processes of the run: one process, or every rank of an mpirun in which each rank holds
// the same matrix (the mesh and the slab systems are replicated). Each rank hands MUMPS
// the entries of its contiguous block of rows; the factors are distributed over the
// ranks, the right-hand side and the solution are gathered on rank 0 and broadcast.
// MPI is initialized on first use if the program has not done so (a singleton MPI
// process, about 0.3 s) and finalized at exit.
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>

namespace anisodwr
{
struct DirectSolverInfo;

class MumpsSolver
{
public:
  /// `refinement_steps`: MUMPS's iterative refinement steps per solve (ICNTL(10))
  explicit MumpsSolver(unsigned int refinement_steps = 0);
  ~MumpsSolver();
  MumpsSolver(const MumpsSolver &) = delete;
  MumpsSolver &operator=(const MumpsSolver &) = delete;

  /// Copies this rank's rows of A and runs MUMPS's analysis (ordering, predicted memory)
  /// on all ranks. Collective.
  void analyze(const dealii::SparseMatrix<double> &A, DirectSolverInfo &info);
  /// Numeric factorization; fills info's peak_mb (the sum over the ranks) and factor_mb.
  /// Without refinement steps the copy of A is freed afterwards. Collective.
  void factorize(DirectSolverInfo &info);
  /// x := A^{-1} x, or A^{-T} x; x is the same on every rank before and after.
  /// Collective. Used through DirectSolver::solve, which checks that the factors exist
  /// and the size of x.
  void solve(dealii::Vector<double> &x, bool transpose) const;
  bool factorized() const { return have_factors; }
  void clear();

private:
  struct Instance;
  std::unique_ptr<Instance> mumps;
  unsigned int refinement_steps;
  bool have_factors = false;
};
} // namespace anisodwr
