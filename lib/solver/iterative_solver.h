#pragma once
// Krylov solvers (Trilinos Belos) with Ifpack2 / Kronecker preconditioners for the
// condensed slab matrix K (interleaved ordering i*(r+1)+k, point blocks of size r+1).
//
// All Trilinos types live in iterative_solver.cc (pimpl); this header needs deal.II only.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include "time/kronecker.h"

#include <memory>
#include <stdexcept>
#include <string>

namespace anisodwr
{
/// Krylov method, preconditioner and stopping rule (config section solver).
struct IterativeOptions
{
  std::string krylov = "gmres";                   ///< gmres | fgmres | bicgstab
  std::string preconditioner = "kronecker_presb"; ///< see preconditioner_names()
  double tolerance = 1e-10;                       ///< on ||b - K x|| / ||b||
  unsigned int restart = 30;                      ///< GMRES restart length
  unsigned int max_iterations = 500;
  double ilu_fill = 1.;  ///< RILUK/RBILUK level of fill (rounded), ILUT fill ratio
  double ilut_drop = 0.; ///< ILUT drop tolerance
  /// Stagnation: a solve whose residual has not fallen by stagnation_factor over the
  /// last stagnation_window iterations stops and counts as failed (window 0 or
  /// factor <= 1: off). gmres/fgmres watch the implicit residual every iteration;
  /// bicgstab runs in chunks of `window` iterations and compares true residuals.
  /// Inner solver of the kronecker* preconditioners per temporal mode block: "ilu"
  /// (Ifpack2 ILU(k), ilu_fill) or "amg" (ML smoothed aggregation for nonsymmetric
  /// matrices through deal.II's TrilinosWrappers::PreconditionAMG on Epetra, one V-cycle
  /// per application, smoother amg_smoother).
  std::string spatial_preconditioner = "ilu";
  std::string amg_smoother = "ilu"; ///< ilu | gauss_seidel | chebyshev
  unsigned int stagnation_window = 50;
  double stagnation_factor = 10.;
};

/// "none|ilut|riluk|block_jacobi|block_gauss_seidel|block_ilu|kronecker|kronecker_presb"
const char *preconditioner_names();
/// "ilu|amg" (solver.spatial_preconditioner)
const char *spatial_preconditioner_names();

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
};

/// The slab matrix: assembled (`assembled`), or matrix-free as the Kronecker sum `terms`
/// (used when `assembled` is null; enough for the kronecker preconditioners and none).
struct SlabMatrix
{
  const dealii::SparseMatrix<double> *assembled = nullptr;
  const std::vector<KronTerm> *terms = nullptr;
  unsigned int m = 1;               ///< temporal block size r+1
  const KronSplit *split = nullptr; ///< for the kronecker preconditioners
};

class IterativeSlabSolver
{
public:
  explicit IterativeSlabSolver(const IterativeOptions &options);
  ~IterativeSlabSolver();

  /// True if the preconditioner needs K assembled (all but kronecker*, none).
  static bool needs_assembled_matrix(const IterativeOptions &options);

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
