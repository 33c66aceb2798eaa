#pragma once
// The goals of a run from the goal section of a config: the scene's default goals, or
// points and rectangles given as text, with their weights.
#include "goal/goal_spec.h"
#include "scene/scene.h"

#include <string>
#include <vector>

namespace anisodwr
{

/// The goals of a run (InputError naming the key on bad input).
std::vector<GoalSpec> make_goals(const GoalInput &in, const Scene<2> &scene);

template <int dim> class Space;

/// Largest relative deviation of a goal's total weight on the mesh from its exact value
/// that check_goal_weights accepts: 1e-6 for mollifiers (their quadrature reaches
/// 1e-12 once the cells resolve them, and fails abruptly below that), 1e-3 for
/// rectangles (exact on axis-parallel cells; on other cells cut by the rectangle's
/// edges 32 x 32 sub-cells reach about 1e-5 to 1e-4 for rectangles of the cells' size).
inline double goal_weight_tolerance(GoalKind kind)
{
  return kind == GoalKind::point ? 1e-6 : 1e-3;
}

/// Refuses goals too small for the mesh of `space` (InputError naming goal.radius or
/// goal.locations, its source and the smallest size accepted there): the integral of a
/// goal's weight function by the goal's quadrature on this mesh (the sum of its goal
/// vector; 1 for a mollifier, a Dirac or a rectangle's mean) must be within
/// goal_weight_tolerance of 1, or, for a mollifier whose support leaves the domain,
/// in (0, 1 + tolerance].
void check_goal_weights(const Space<2> &space, const std::vector<GoalSpec> &goals,
                        const GoalInput &in, const Scene<2> &scene);
} // namespace anisodwr
