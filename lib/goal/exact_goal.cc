// The exact value of a goal (exact_goal, goal/goal.h) for scenes with an exact
// solution: the goal kind's spatial value by the nested adaptive quadrature of
// base/nested_quadrature.h, composite Gauss in time.
#include "base/errors.h"
#include "base/nested_quadrature.h"
#include "goal/goal.h"

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
using nested::NestedIntegrals;

/// An exact goal value that misses tol: kept with a warning while it is accurate to
/// 1e-8 of its scale, else InputError.
void check_accuracy(const GoalSpec &goal, const NestedIntegrals &n, double tol)
{
  const double rel = std::max(
      n.error / std::max(n.scale, std::numeric_limits<double>::min()), n.inner_rel);
  if (!n.converged && !(rel <= tol))
  {
    // Fallback: keep the value when it is still accurate to 1e-8 of its scale
    // (J_error and I_eff are then only that accurate); otherwise refuse.
    std::ostringstream msg;
    msg.precision(2);
    msg << "goal '" << goal.name
        << "': the exact goal value reaches a relative accuracy of " << rel << " (wanted "
        << tol << ")"
        << (n.budget.exhausted ? " within the work limit of " +
                                     std::to_string(nested::budget_limit) + " evaluations"
                               : "");
    if (!(rel <= 1e-8))
      throw InputError(msg.str() +
                       "; the layer (scene.epsilon) or the goal (goal.radius, "
                       "goal.locations) is too extreme for an exact value");
    std::cerr << "anisodwr: warning: " << msg.str() << "; J_error and I_eff use it"
              << std::endl;
  }
}
} // namespace

template <int dim>
double exact_goal(const Scene<dim> &scene, const GoalSpec &goal, double tol)
{
  static_assert(dim == 2, "exact goals are implemented in 2D");
  const auto *u = scene.exact();
  if (!u)
    throw InputError("goal '" + goal.name + "': the scene has no exact solution");
  const GoalType &type = goal_type(goal.kind);
  NestedIntegrals nested(tol);
  auto spatial = [&](double t) { return type.exact_value(scene, goal, t, nested); };
  double J = 0;
  if (!goal.over_time)
    J = spatial(scene.end_time);
  else
  {
    // composite 12-point Gauss in time on 16 panels (the scenes are smooth in t)
    const QIterated<1> q(QGauss<1>(12), 16);
    for (unsigned int i = 0; i < q.size(); ++i)
      J += q.weight(i) * scene.end_time * spatial(q.point(i)[0] * scene.end_time);
  }
  if (!std::isfinite(J))
    throw InputError("goal '" + goal.name +
                     "': the exact goal value is not finite (the exact solution is not "
                     "finite on the goal's support); check goal.locations, goal.radius "
                     "and the scene's parameters");
  check_accuracy(goal, nested, tol);
  return J;
}

template double exact_goal<2>(const Scene<2> &, const GoalSpec &, double);
} // namespace anisodwr
