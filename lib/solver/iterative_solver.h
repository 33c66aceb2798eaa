#pragma once
// Krylov solvers (Trilinos Belos) with Ifpack2 / Kronecker preconditioners for the
// condensed slab matrix K (interleaved ordering i*(r+1)+k, point blocks of size r+1);
// GMRES with the frozen operator's modes runs on deal.II's GMRES (no Trilinos).
//
// All Trilinos types live in iterative_solver.cc (pimpl); this header needs deal.II only.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include "solver/iterative_options.h"
#include "time/kronecker.h"

#include <memory>
#include <stdexcept>
#include <string>

namespace anisodwr
{
class ModeDirectSolver;

/// K = T1 (x) S1 + T2 (x) S2 (Kronecker factors in the interleaved ordering, T2
/// invertible, S1 and S2 on one sparsity pattern): the input of the Kronecker
/// preconditioner. For the slab operator: T1 = D, S1 = Mc, T2 = tau Mhat, S2 = Ac.
struct KronSplit
{
  dealii::FullMatrix<double> T1, T2;
  const dealii::SparseMatrix<double> *S1 = nullptr, *S2 = nullptr;
};

/// A Krylov solve that did not reach the tolerance (or broke down).
class KrylovFailure : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

struct KrylovStats
{
  unsigned int iterations = 0;
  double residual = 0; ///< achieved ||b - K x|| / ||b||
  /// GMRES iterations inside the preconditioner (solver.inner_iterations > 0), summed
  /// over its applications in this solve.
  unsigned long inner_iterations = 0;
};

/// The slab matrix: assembled (`assembled`), or matrix-free as the Kronecker sum `terms`
/// (used when `assembled` is null; enough for the kronecker preconditioners and none).
struct SlabMatrix
{
  const dealii::SparseMatrix<double> *assembled = nullptr;
  const std::vector<KronTerm> *terms = nullptr;
  unsigned int m = 1;               ///< temporal block size r+1
  const KronSplit *split = nullptr; ///< for the kronecker preconditioners
  /// preconditioner = modes: the factorized mode solver of a frozen operator (its
  /// transposed solve preconditions K^T)
  const ModeDirectSolver *modes = nullptr;
};

class IterativeSlabSolver
{
public:
  explicit IterativeSlabSolver(const IterativeOptions &options);
  ~IterativeSlabSolver();

  /// True if the preconditioner needs K assembled (all but kronecker*, none).
  static bool needs_assembled_matrix(const IterativeOptions &options);

  /// True for GMRES preconditioned by the modes of a frozen operator: deal.II's GMRES
  /// on deal.II vectors, nothing of Trilinos, so solvers in two threads may run side by
  /// side (the DWR loop's concurrent marches). Its stopping rule, stagnation watch and
  /// acceptance are those of the Belos path.
  static bool runs_without_trilinos(const IterativeOptions &options);

  /// Copies K (or K^T if `transpose`) into Tpetra, assembled or as Kronecker terms, and
  /// builds the preconditioner (from K.split for kronecker*, transposed here as well).
  void setup(const SlabMatrix &K, bool transpose);

  /// Solves (the set-up matrix) x = b; x holds the initial guess on entry.
  /// Throws KrylovFailure naming the solver, preconditioner, iterations and residual.
  KrylovStats solve(const dealii::Vector<double> &b, dealii::Vector<double> &x) const;

  /// "gmres+kronecker" etc.
  std::string name() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl;
};
} // namespace anisodwr
