#pragma once
// The choice-valued options of the adaptivity section (adaptivity.mode, .marking,
// .time_indicator, .space_indicator, .adjoint_stabilization, .tolerance_measure,
// .goal_estimate), each
// with its name table (base/choice.h); light, so that config/parameters.h can hold them.
#include "base/choice.h"

namespace anisodwr
{
/// Which form of the temporal error representation eta_tau uses.
enum class TimeIndicator
{
  /// 1/2 rho(u)(E z - z) + 1/2 rho*(u,z)(E u - u) (doc/method.md §8)
  average,
  /// rho*(u,z)(E u - u): the adjoint residual weighted by the primal's temporal error.
  /// J(e) = rho*(u, z_tau h)(u - u_tau h) holds exactly for the discrete adjoint, so
  /// only the primal has to be resolved in time; the primal-residual form needs
  /// E z - z ~ z - z_tau h, which fails when the adjoint is a pulse crossing the
  /// mollifier in a fraction of a slab (moving hump: |b| tau / s = 18).
  adjoint_residual,
  /// rho*(u,z)(u_r+1 - u) with u_r+1 the primal solved once more in dG(r+1) on the same
  /// slabs and mesh (HigherOrderPrimal), including J_T's end part J_T(u_r+1(T) - u(T)).
  /// The Radau reconstruction E u assumes dG(r)'s nodal superconvergence (E u - u = 0
  /// at t_n), which a layer that crosses a slab destroys; u_r+1 does not. For q = p,
  /// no SUPG and u_r+1 = u, eta_tau = J(u) - J(u_tau h) exactly.
  higher_order
};

/// Which form of the spatial error representation eta_h,i uses.
enum class SpaceIndicator
{
  /// 1/2 rho(u)(z - R_i z) + 1/2 rho*(u, R_h z)(I_2h,i u - u) + S terms
  /// (doc/method.md §8); on a (cell, direction) without a lift only the primal half
  average,
  /// rho(u)(z - R_i z) + S(u)(R_h z) share: the primal-residual form alone, which needs
  /// no lift of u (exact up to z ~ z_tau h and the directional split)
  primal_residual
};

/// adaptivity.goal_estimate: what each goal's own estimate (eta_<goal>) is.
enum class GoalEstimate
{
  /// the goal's DWR indicators summed: eta_h,x + eta_h,y + eta_tau from its own adjoint
  dwr,
  /// J_i(u_q) - J_i(u_h) + eta_tau,i: u_q the primal solved once more in the adjoint's
  /// degree q on the loop's mesh and slabs, with the same stabilization. For a
  /// Galerkin primal with conforming weights it equals the DWR's spatial sum (the
  /// adjoint identity rho(u_h)(z_q) = J(u_q) - J(u_h)); with SUPG and a differently
  /// stabilized adjoint it does not, and the DWR sum then carries the two
  /// stabilizations' mismatch. The DWR indicators still mark the cells.
  enriched,
  /// J_i(u_q) - J_i(u_h) + eta_tau,i with u_q solving the adjoint's own slab operator
  /// (degree q, the adjoint's stabilization) untransposed, by its factorization after
  /// the adjoints: the residual of u_h in the adjoint's stabilized form weighted by z_i
  /// itself, the DWR identity without the interpolant and the stabilizations' mismatch.
  consistent,
  /// both u_q (enriched's and consistent's), each goal's estimate the larger in size:
  /// two references stabilized differently, the stop waits until neither sees an error
  /// above the tolerance
  both
};

inline const std::vector<Named<GoalEstimate>> &names(GoalEstimate)
{
  static const std::vector<Named<GoalEstimate>> table{
      {GoalEstimate::dwr, "dwr"},
      {GoalEstimate::enriched, "enriched"},
      {GoalEstimate::consistent, "consistent"},
      {GoalEstimate::both, "both"}};
  return table;
}

/// adaptivity.tolerance_measure: what adaptivity.tolerance is compared with.
enum class ToleranceMeasure
{
  /// |eta_tau h|, the signed sum of all indicators
  eta,
  /// LoopRow::eta_parts_abs(): |eta_h,x| + |eta_h,y| + |eta_tau| without signs, per goal
  /// where each goal has its own estimate; cancellation between the parts or between
  /// the goals cannot make it small
  parts,
  /// LoopRow::eta_goals_max(): max_i |w_i eta_i|, each goal's own signed estimate
  /// (one adjoint per goal); with goal.weights = auto or estimate the largest relative
  /// error estimate of a single goal. The goals cannot cancel each other; a goal's
  /// space and time parts can (each goal's signed estimate is trusted)
  goals
};

inline const std::vector<Named<ToleranceMeasure>> &names(ToleranceMeasure)
{
  static const std::vector<Named<ToleranceMeasure>> table{
      {ToleranceMeasure::eta, "eta"},
      {ToleranceMeasure::parts, "parts"},
      {ToleranceMeasure::goals, "goals"}};
  return table;
}

inline const std::vector<Named<TimeIndicator>> &names(TimeIndicator)
{
  static const std::vector<Named<TimeIndicator>> table{
      {TimeIndicator::average, "average"},
      {TimeIndicator::adjoint_residual, "adjoint_residual"},
      {TimeIndicator::higher_order, "higher_order"}};
  return table;
}

inline const std::vector<Named<SpaceIndicator>> &names(SpaceIndicator)
{
  static const std::vector<Named<SpaceIndicator>> table{
      {SpaceIndicator::average, "average"},
      {SpaceIndicator::primal_residual, "primal_residual"}};
  return table;
}

/// adaptivity.mode: how cells are marked and refined.
enum class AdaptivityMode
{
  anisotropic, ///< mark per direction by |eta_h,i|
  isotropic,   ///< mark by |eta_h|, refine isotropically
  uniform      ///< refine every cell
};

inline const std::vector<Named<AdaptivityMode>> &names(AdaptivityMode)
{
  static const std::vector<Named<AdaptivityMode>> table{
      {AdaptivityMode::anisotropic, "anisotropic"},
      {AdaptivityMode::isotropic, "isotropic"},
      {AdaptivityMode::uniform, "uniform"}};
  return table;
}

/// adaptivity.marking: the anisotropic marking strategy (MarkingOptions::marking).
enum class Marking
{
  joint,         ///< rank all (cell, direction) pairs together
  per_direction, ///< the theta_h fraction of cells in each direction separately
  cell           ///< mark cells by sum_i |eta_h,i^K|, cut where |eta_h,i^K| >= kappa max
};

inline const std::vector<Named<Marking>> &names(Marking)
{
  static const std::vector<Named<Marking>> table{
      {Marking::joint, "joint"},
      {Marking::per_direction, "per_direction"},
      {Marking::cell, "cell"}};
  return table;
}

/// adaptivity.marking_criterion: how many cells (or pairs) theta_h selects.
enum class MarkingCriterion
{
  /// the ceil(theta_h n) largest indicators (fixed fraction of the count)
  count,
  /// bulk (Doerfler) criterion: the fewest largest indicators whose sum reaches
  /// theta_h times the sum of all; few cells where the indicators are concentrated
  bulk
};

inline const std::vector<Named<MarkingCriterion>> &names(MarkingCriterion)
{
  static const std::vector<Named<MarkingCriterion>> table{
      {MarkingCriterion::count, "count"}, {MarkingCriterion::bulk, "bulk"}};
  return table;
}

/// adaptivity.adjoint_stabilization: the adjoint's discretization.
enum class AdjointStabilization
{
  transposed, ///< the transpose of the SUPG-stabilized primal operator in degree q
  none        ///< Galerkin (delta = 0) discretization of the continuous adjoint
};

inline const std::vector<Named<AdjointStabilization>> &names(AdjointStabilization)
{
  static const std::vector<Named<AdjointStabilization>> table{
      {AdjointStabilization::transposed, "transposed"},
      {AdjointStabilization::none, "none"}};
  return table;
}

/// adaptivity.adjoint_outflow: the adjoint's condition on the outflow part of the
/// Dirichlet boundary (b.n > 0), which is the adjoint's inflow boundary.
enum class AdjointOutflow
{
  dirichlet, ///< z = 0 imposed at the DoFs
  goals      ///< natural (eps d_n z + (b.n) z = 0) where a goal's support is at the
             ///< wall, in the wall cell and thinner across the wall than the cell
};

inline const std::vector<Named<AdjointOutflow>> &names(AdjointOutflow)
{
  static const std::vector<Named<AdjointOutflow>> table{
      {AdjointOutflow::dirichlet, "dirichlet"}, {AdjointOutflow::goals, "goals"}};
  return table;
}

/// The marking options (the adaptivity section derives from them).
struct MarkingOptions
{
  AdaptivityMode mode = AdaptivityMode::anisotropic;
  /// anisotropic mode: joint ranks all (cell, direction) pairs by |eta_h,i^K| together
  /// and marks the theta_h fraction of them; per_direction marks the theta_h fraction
  /// of cells separately in each direction (the reference rule, doc/method.md §9; a
  /// cell whose indicators are all large is then cut in every direction even if one
  /// dominates).
  /// cell: mark the theta_h fraction of cells by sum_i |eta_h,i^K|; a marked cell is
  /// cut in direction i iff |eta_h,i^K| >= kappa * max_j |eta_h,j^K| (the directions
  /// the cell needs, not every direction whose pair passed a global threshold).
  Marking marking = Marking::joint;
  /// count: theta_h is a fraction of the cells (pairs); bulk: of the indicators' sum
  MarkingCriterion marking_criterion = MarkingCriterion::count;
  double theta_h = 0.25, theta_coarsen = 0., kappa = 0.75;
};
} // namespace anisodwr
