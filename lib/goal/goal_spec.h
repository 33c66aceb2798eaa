#pragma once
// The description of one goal functional (doc/method.md §4), as read from the config.
#include "base/choice.h"

#include <string>
#include <vector>

namespace anisodwr
{
/// goal.kind, and the kind of one goal (point or mean).
enum class GoalKind
{
  scene, ///< goal.kind only: the scene's own goals
  point, ///< mollified point value (s = 0: Dirac)
  mean   ///< mean over a rectangle
};

inline const std::vector<Named<GoalKind>> &names(GoalKind)
{
  static const std::vector<Named<GoalKind>> table{
      {GoalKind::scene, "scene"}, {GoalKind::point, "point"}, {GoalKind::mean, "mean"}};
  return table;
}

struct GoalSpec
{
  std::string name;
  GoalKind kind = GoalKind::point; ///< point or mean
  bool over_time = false; ///< true: int_I j(u(t)) dt; false: j(u(T))
  std::vector<double> center;       ///< point goals
  double radius = 0;                ///< mollifier radius s
  std::vector<double> lower, upper; ///< mean goals: the rectangle
  double weight = 1;
};

/// The goal with weight 1 (the per-goal values and estimates are unweighted).
inline GoalSpec unweighted(const GoalSpec &goal)
{
  GoalSpec g = goal;
  g.weight = 1;
  return g;
}
} // namespace anisodwr
