#pragma once
// The options of the Krylov slab solvers (config section solver); no deal.II or
// Trilinos types. Each choice is an enum with one name table (base/choice.h): the
// names are the config values, and adding a value here adds it to the key's choices.
#include "base/choice.h"

#include <string>
#include <vector>

namespace anisodwr
{
enum class Krylov
{
  gmres,
  fgmres,
  bicgstab
};
inline const std::vector<Named<Krylov>> &names(Krylov)
{
  static const std::vector<Named<Krylov>> table{
      {Krylov::gmres, "gmres"}, {Krylov::fgmres, "fgmres"}, {Krylov::bicgstab, "bicgstab"}};
  return table;
}

/// Preconditioner of the slab system: Ifpack2 ones on the assembled K, or the
/// Kronecker ones (matrix-free K, one spatial block solve per temporal mode).
enum class Preconditioner
{
  none,
  ilut,
  riluk,
  block_jacobi,
  block_gauss_seidel,
  block_ilu,
  kronecker,
  kronecker_presb,
  modes
};
inline const std::vector<Named<Preconditioner>> &names(Preconditioner)
{
  static const std::vector<Named<Preconditioner>> table{
      {Preconditioner::none, "none"},
      {Preconditioner::ilut, "ilut"},
      {Preconditioner::riluk, "riluk"},
      {Preconditioner::block_jacobi, "block_jacobi"},
      {Preconditioner::block_gauss_seidel, "block_gauss_seidel"},
      {Preconditioner::block_ilu, "block_ilu"},
      {Preconditioner::kronecker, "kronecker"},
      {Preconditioner::kronecker_presb, "kronecker_presb"},
      {Preconditioner::modes, "modes"}};
  return table;
}
/// True for the Kronecker preconditioners (they work on the matrix-free K).
inline bool is_kronecker(Preconditioner p)
{
  return p == Preconditioner::kronecker || p == Preconditioner::kronecker_presb;
}

/// Inner solver of the kronecker* preconditioners per temporal mode block.
enum class SpatialPreconditioner
{
  ilu,
  amg
};
inline const std::vector<Named<SpatialPreconditioner>> &names(SpatialPreconditioner)
{
  static const std::vector<Named<SpatialPreconditioner>> table{
      {SpatialPreconditioner::ilu, "ilu"}, {SpatialPreconditioner::amg, "amg"}};
  return table;
}

enum class AmgSmoother
{
  ilu,
  gauss_seidel,
  chebyshev
};
inline const std::vector<Named<AmgSmoother>> &names(AmgSmoother)
{
  static const std::vector<Named<AmgSmoother>> table{{AmgSmoother::ilu, "ilu"},
                                                     {AmgSmoother::gauss_seidel, "gauss_seidel"},
                                                     {AmgSmoother::chebyshev, "chebyshev"}};
  return table;
}

/// Krylov method, preconditioner and stopping rule (config section solver).
struct IterativeOptions
{
  Krylov krylov = Krylov::gmres;
  Preconditioner preconditioner = Preconditioner::kronecker_presb;
  double tolerance = 1e-10;          ///< on ||b - K x|| / ||b||
  unsigned int restart = 30;         ///< GMRES restart length
  unsigned int max_iterations = 500;
  double ilu_fill = 2.;  ///< RILUK/RBILUK level of fill (rounded), ILUT fill ratio
  double ilut_drop = 0.; ///< ILUT drop tolerance
  /// Inner solver of the kronecker* preconditioners per temporal mode block: ILU
  /// (Ifpack2 ILU(k), ilu_fill) or AMG (ML smoothed aggregation for nonsymmetric
  /// matrices through deal.II's TrilinosWrappers::PreconditionAMG on Epetra, one V-cycle
  /// per application, smoother amg_smoother).
  SpatialPreconditioner spatial_preconditioner = SpatialPreconditioner::ilu;
  AmgSmoother amg_smoother = AmgSmoother::ilu;
  /// Inner iterations of the kronecker* preconditioners: 0 = each temporal mode block
  /// is approximated by one application of its spatial preconditioner (ILU or AMG);
  /// k > 0 = solved by at most k right-preconditioned GMRES iterations to the relative
  /// residual inner_tolerance (complex pairs: GMRES on the 2n x 2n block with PRESB or
  /// the 2n ILU as its preconditioner). The preconditioner then varies between
  /// applications, so gmres runs flexible (as fgmres); bicgstab is rejected.
  unsigned int inner_iterations = 0;
  double inner_tolerance = 1e-2;
  /// Stagnation: a solve whose residual has not fallen by stagnation_factor over the
  /// last stagnation_window iterations stops and counts as failed (window 0 or
  /// factor <= 1: off). gmres/fgmres watch the implicit residual every iteration;
  /// bicgstab runs in chunks of `window` iterations and compares true residuals.
  unsigned int stagnation_window = 50;
  double stagnation_factor = 10.;
  /// preconditioner = modes: the exact mode solve of the slab operator with its
  /// coefficients frozen (at the slab's middle), factorized once and reused over the
  /// following slabs until a Krylov solve needs more than refactor_iterations
  /// iterations (then the next slab refactorizes at its own middle).
  unsigned int refactor_iterations = 10;
};
} // namespace anisodwr
