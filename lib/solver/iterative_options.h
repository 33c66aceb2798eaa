#pragma once
// The options of the Krylov slab solvers (config section solver); no deal.II or
// Trilinos types.
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
} // namespace anisodwr
