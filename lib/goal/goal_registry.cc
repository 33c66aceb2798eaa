// The registry of goal kinds: a new kind is its file (a GoalType and its GoalPart)
// and one line in the table below.
#include "base/errors.h"
#include "goal/goal_type.h"

namespace anisodwr
{
const GoalType &point_goal(); // goal/point_goal.cc
const GoalType &mean_goal();  // goal/mean_goal.cc
const GoalType &flux_goal();  // goal/flux_goal.cc

const std::vector<const GoalType *> &goal_types()
{
  static const std::vector<const GoalType *> table{&point_goal(), &mean_goal(), &flux_goal()};
  return table;
}

const GoalType &goal_type(const std::string &kind)
{
  for (const GoalType *t : goal_types())
    if (t->name() == kind)
      return *t;
  std::string list;
  for (const GoalType *t : goal_types())
    list += (list.empty() ? "" : ", ") + t->name();
  throw InputError("unknown goal kind '" + kind + "'; expected one of " + list);
}

std::string goal_kind_choices(const std::string &separator)
{
  std::string list = "scene";
  for (const GoalType *t : goal_types())
    list += separator + t->name();
  return list;
}

std::string goal_kind_doc()
{
  std::string doc = "scene: the scene's goals (moving_hump: mollified u(x_e1,T), "
                    "u(x_e2,T); boundary_layer: mean of u(T) over (0.5,1)x(0,1); hemker: "
                    "u_xe1_I, u_xe2_I; custom: scene.goals; others: u(0.5,0.5,T))";
  for (const GoalType *t : goal_types())
    doc += "; " + t->name() + ": " + t->doc();
  return doc + ".";
}

std::string goal_locations_doc()
{
  std::string doc = "The goals of goal.kind (not scene), one per location, separated by "
                    "';'; a location '[name =] [kind] numbers' may name its goal and take "
                    "another kind (e.g. 'x1 = 4, 1; heat = flux 1')";
  for (const GoalType *t : goal_types())
    doc += "; " + t->name() + ": '" + t->syntax() + "'";
  return doc + ".";
}
} // namespace anisodwr
