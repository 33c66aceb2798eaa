#pragma once
// The goal of the patch lift of the primal: J_i(u~) with u~ = I_2h u_h, the
// reconstruction behind the `auto` goal weights.
#include "goal/goal_spec.h"
#include "space/space.h"
#include "time/temporal_basis.h"
#include "time/time_mesh.h"

#include <vector>

namespace anisodwr
{
/// J_i(u~) (goal unweighted) with u~ the patch lift I_2h u_h of U (cells without a patch
/// keep u_h).
double lifted_goal(const Space<2> &primal, const GoalSpec &goal, const TimeMesh &mesh,
                   const TemporalBasis &basis,
                   const std::vector<dealii::Vector<double>> &U);
} // namespace anisodwr
