#pragma once
// The goals of a run from the goal section of a config: the scene's default goals, or
// points and rectangles given as text, with their weights.
#include "scene/goal_spec.h"
#include "scene/scene.h"

#include <string>
#include <vector>

namespace anisodwr
{

/// InputError "<where>: goal name '<name>' appears twice in key '<key>'; ..." if two
/// goals of a list (goal.locations, scene.goals) have one name (given, or the default
/// "<kind>_<i + 1>"): the names are the goals' columns in loops.csv and probes.csv.
void check_goal_names(const std::vector<GoalSpec> &goals, const std::string &key,
                      const std::string &where);

/// One goal of a list of goals (goal.locations, scene.goals), number i + 1:
/// "[name =] [kind] numbers" with a registered kind (GoalType), that of `defaults` where
/// it is omitted (an empty one: it must be given), and the name "<kind>_<i + 1>" where
/// that is. The other fields (over_time, radius) come from `defaults`; the location is
/// set and checked against `scene` by GoalType::set_location. InputError "<where>:
/// invalid ... in key '<key>'; ..." on bad input.
GoalSpec parse_goal_item(const std::string &item, std::size_t i, const GoalSpec &defaults,
                         const std::string &key, const std::string &where,
                         const Scene<2> &scene);

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
