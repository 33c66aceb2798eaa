#pragma once
// The description of one goal functional (doc/method.md §4), as read from the config or
// given by a scene as its default goals: plain data below the goal layer (goal/ builds
// the functionals from it).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace anisodwr
{
struct GoalSpec
{
  std::string name;
  std::string kind = "point"; ///< the name of its GoalType (goal/goal_type.h)
  bool over_time = false; ///< true: int_I j(u(t)) dt; false: j(u(T))
  /// Where the goal is, as the numbers of one location of its kind (GoalType::syntax;
  /// the kind's file in goal/ reads them): a point goal's centre x, y; a mean goal's
  /// rectangle x0, y0, x1, y1; a flux goal's boundary ids.
  std::vector<double> location;
  double radius = 0; ///< mollifier radius s (kinds with GoalType::has_radius)
  double weight = 1;
  /// goal.reference: the goal's reference value and its uncertainty (NaN: none given;
  /// uncertainty 0 where the value was given without one)
  double reference = std::nan(""), reference_uncertainty = std::nan("");
};

/// The rectangle x0, y0, x1, y1 that holds a goal's spatial support: a point goal's
/// (radius > 0) disk's bounding square, a mean goal's rectangle. False for other kinds
/// (flux goals, point values without a mollifier).
inline bool support_rectangle(const GoalSpec &g, std::array<double, 4> &r)
{
  if (g.kind == "point" && g.radius > 0 && g.location.size() == 2)
    r = {{g.location[0] - g.radius, g.location[1] - g.radius, g.location[0] + g.radius,
          g.location[1] + g.radius}};
  else if (g.kind == "mean" && g.location.size() == 4)
    r = {{g.location[0], g.location[1], g.location[2], g.location[3]}};
  else
    return false;
  return true;
}

/// The extent of a goal's support along the unit vector (nx, ny): 2 r for a point goal's
/// disk, |nx| (x1 - x0) + |ny| (y1 - y0) for a mean goal's rectangle; 0 for other kinds.
inline double support_extent(const GoalSpec &g, double nx, double ny)
{
  std::array<double, 4> r;
  if (!support_rectangle(g, r))
    return 0.;
  if (g.kind == "point")
    return 2 * g.radius;
  return std::abs(nx) * (r[2] - r[0]) + std::abs(ny) * (r[3] - r[1]);
}

/// The goal with weight 1 (the per-goal values and estimates are unweighted).
inline GoalSpec unweighted(const GoalSpec &goal)
{
  GoalSpec g = goal;
  g.weight = 1;
  return g;
}
/// The weight of a goal with value J whose error is taken to have the sign of s
/// (goal.weights = auto: s = J(I_2h u_h) - J(u_h); estimate: s = the goal's own
/// estimate): sign(s) / max(|J|, 1e-12). Where |s| <= `unseen` * |J| the error is not
/// seen (for `auto`: the lift does not change u_h on the goal's support, e.g. none of
/// its cells has a patch, and s is 0 up to rounding), and the weight is +1 / |J|, so
/// that it does not depend on the summation order.
inline double signed_goal_weight(double s, double J, double unseen = 0)
{
  const double a = std::max(std::abs(J), 1e-12);
  return (std::abs(s) <= unseen * a || s >= 0 ? 1. : -1.) / a;
}

/// goal.weights = estimate: the weight's denominator is at least this fraction of the
/// goal applied to the solution's largest value, estimate_weight_floor |J_i(1)| max|u_h|.
constexpr double estimate_weight_floor = 1e-2;

/// Relative size below which the lift difference of goal.weights = auto counts as zero.
constexpr double auto_weight_unseen = 1e-8;
/// The goal section of a config and, for messages, where goal.locations, goal.radius,
/// goal.weights and goal.reference came from (a config file's path, "--set" or
/// "default"; for a custom scene locations_source is where scene.goals came from, since
/// its goals are given there).
struct GoalInput
{
  std::string kind = "scene"; ///< scene or the name of a GoalType
  std::string locations = ""; ///< the kind's locations, separated by ";"
  bool over_time = false;
  double radius = 0.01;
  std::string weights = "estimate"; ///< auto, one number or one per goal
  std::string reference = ""; ///< "J_1[+-u_1], ...": reference values, or empty
  std::string locations_source = "default", radius_source = "default",
              weights_source = "default", reference_source = "default";
};

} // namespace anisodwr
