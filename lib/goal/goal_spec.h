#pragma once
// The description of one goal functional (SPEC §3), as read from the config.
#include <string>
#include <vector>

namespace anisodwr
{
struct GoalSpec
{
  std::string name;
  std::string kind =
      "point";            ///< point (mollified, s = 0: Dirac) or mean (over a rectangle)
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
