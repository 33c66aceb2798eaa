#pragma once
// The goals of a run from the goal section of a config: the scene's default goals, or
// points and rectangles given as text, with their weights.
#include "goal/goal_spec.h"
#include "scene/scene.h"

#include <string>
#include <vector>

namespace anisodwr
{
/// The goal section of a config and, for messages, where goal.locations, goal.radius
/// and goal.weights came from (a config file's path, "--set" or "default").
struct GoalInput
{
  GoalKind kind = GoalKind::scene;
  std::string locations = ""; ///< "x,y; ..." (point) or "x0,y0,x1,y1; ..." (mean)
  bool over_time = false;
  double radius = 0.01;
  std::string weights = "1"; ///< auto, one number or one per goal
  std::string reference = ""; ///< "J_1[+-u_1], ...": reference values, or empty
  std::string locations_source = "default", radius_source = "default",
              weights_source = "default", reference_source = "default";
};

/// The goals of a run (InputError naming the key on bad input).
std::vector<GoalSpec> make_goals(const GoalInput &in, const Scene<2> &scene);
} // namespace anisodwr
