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

/// Refuses goals too small for the mesh of `space` (InputError naming goal.radius or
/// goal.locations, its source and the smallest size accepted there): the integral of a
/// goal's weight function by the goal's quadrature on this mesh (the sum of its goal
/// vector; 1 for a mollifier, a Dirac or a rectangle's mean) must be what the goal's
/// kind accepts (GoalType::weight_accepted).
void check_goal_weights(const Space<2> &space, const std::vector<GoalSpec> &goals,
                        const GoalInput &in, const Scene<2> &scene);
} // namespace anisodwr
