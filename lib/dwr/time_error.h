#pragma once
// Goal values of a primal march and the measured temporal part of the goal error
// (adaptivity.measure_time_error): the primal on the time mesh, bisected once and twice,
// and Richardson extrapolation.
#include "scene/goal_spec.h"
#include "io/loop_report.h"
#include "slab/primal_march.h"
#include "space/space.h"
#include "time/temporal_basis.h"
#include "time/time_mesh.h"

#include <deal.II/lac/vector.h>

#include <array>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace anisodwr
{
/// J(u) of one goal alone (weight 1) for the interleaved slab solutions U.
double goal_value(const Space<2> &space, const GoalSpec &goal, const TimeMesh &mesh,
                  const TemporalBasis &basis, const std::vector<dealii::Vector<double>> &U);

/// J(inf) - J(N) from J(N), J(2N), J(4N) and the observed order k (Richardson): with
/// d1 = J(2N) - J(N), d2 = J(4N) - J(2N), k = log2(d1 / d2),
/// J(inf) - J(N) = d1 + d2 2^k / (2^k - 1); NaN, NaN when the differences do not
/// contract (k <= 1/2).
std::pair<double, double> richardson(const std::array<double, 3> &J);

/// The temporal part of the goal error on the current spatial mesh, measured (row.err_tau,
/// err_tau_order for the weighted goal, err_tau_goal per goal unweighted): the primal
/// is solved on the time mesh, bisected once and bisected twice, all three with the
/// SUPG parameters of the twice-bisected mesh (delta_K <= supg_tau_factor * tau_n / 4,
/// built by `space(s)` with the bound scaled by s = 1/4, 1/2, 1): delta_K bounded by the
/// slab length is what keeps small slabs stable, so that only the time mesh changes
/// between the three and not the spatial discretization; then richardson().
void measure_time_error(const std::function<std::unique_ptr<Space<2>>(double)> &space,
                        const TimeMesh &mesh, const TemporalBasis &basis,
                        const SlabSolverOptions &solver, const std::vector<GoalSpec> &goals,
                        const MarchOptions &opt, LoopRow &row);
} // namespace anisodwr
