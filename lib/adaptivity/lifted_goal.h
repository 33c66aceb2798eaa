#pragma once
// The goal's change under the patch lift of the primal: J_i(u~) - J_i(u_h) with
// u~ = I_2h u_h, whose sign the `auto` goal weights take.
#include "scene/goal_spec.h"
#include "space/space.h"
#include "time/temporal_basis.h"
#include "time/time_mesh.h"

#include <vector>

namespace anisodwr
{
/// J_i(u~) - J_i(u_h) (goal unweighted) with u~ the patch lift I_2h u_h of U. Both
/// values use one quadrature (the goal's local vectors in the weight element Q_2p), and
/// cells without a patch (where u~ = u_h) are skipped, so the difference is exactly 0
/// where the lift changes nothing, not the difference of two quadratures.
double lift_difference(const Space<2> &primal, const GoalSpec &goal, const TimeMesh &mesh,
                       const TemporalBasis &basis,
                       const std::vector<dealii::Vector<double>> &U);
} // namespace anisodwr
