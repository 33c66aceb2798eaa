#pragma once
// Backward march of the adjoint of the stabilized discrete problem (doc/method.md §5):
//   K_n^T Z_n = J_n + (y e^T (x) M(t_n)^T) Z_{n+1},   Z_{N+1} = 0,
// with the same SlabOperator code (transposed solve) in the adjoint space.
#include "goal/goal.h"
#include "slab/primal_march.h"

namespace anisodwr
{
template <int dim>
std::vector<dealii::Vector<double>> march_adjoint(const Space<dim> &space, const TimeMesh &mesh,
                                                  const TemporalBasis &basis,
                                                  SlabOperator<dim> &op, const GoalVectors &goal,
                                                  const MarchOptions &options);

/// One adjoint march per goal vector with the same operator: per slab one prepare and
/// the goals' transposed solves side by side (SlabOperator::solve_transposed); each
/// result equals march_adjoint's for that goal.
template <int dim>
std::vector<std::vector<dealii::Vector<double>>>
march_adjoints(const Space<dim> &space, const TimeMesh &mesh, const TemporalBasis &basis,
               SlabOperator<dim> &op, const std::vector<GoalVectors> &goals,
               const MarchOptions &options);

/// z(T^+) = M^{-1} j_T: the representer of the goals' end-time part in `adjoint`'s space
/// (mass matrix with its constraints, solved by UMFPACK); the estimator's E_tau z at T.
template <int dim>
dealii::Vector<double> end_time_representer(const Space<dim> &adjoint,
                                            const std::vector<GoalSpec> &goals);
} // namespace anisodwr
