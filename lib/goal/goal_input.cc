#include "goal/goal_input.h"

#include "base/errors.h"
#include "base/parse_number.h"
#include "base/text.h"
#include "goal/goal.h"
#include "space/space.h"


#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace anisodwr
{
using namespace dealii;

std::string six_digits(double v)
{
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

namespace
{
std::vector<std::string> split(const std::string &s, char sep)
{
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep))
  {
    const auto a = item.find_first_not_of(" \t"), b = item.find_last_not_of(" \t");
    out.push_back(a == std::string::npos ? "" : item.substr(a, b - a + 1));
  }
  return out;
}

std::vector<double> numbers(const std::string &s, const std::string &key, unsigned int n,
                            const std::string &source)
{
  std::vector<double> v;
  for (const auto &x : split(s, ','))
  {
    double value = 0;
    const NumberStatus status = parse_double(x, value);
    if (status == NumberStatus::underflow)
      throw InputError(source + ": invalid value '" + s + "' in key '" + key + "': '" +
                       x + "' " + underflow_text());
    if (status != NumberStatus::ok)
      throw InputError(source + ": invalid value '" + s + "' in key '" + key +
                       "'; expected " + (n > 0 ? std::to_string(n) : "one or more") +
                       " comma-separated finite numbers");
    v.push_back(value);
  }
  if (n > 0 && v.size() != n)
    throw InputError(source + ": invalid value '" + s + "' in key '" + key +
                     "'; expected " + std::to_string(n) +
                     " comma-separated numbers, got " + std::to_string(v.size()));
  return v;
}
/// goal.reference into the goals: one "value" or "value+-uncertainty" per goal.
void set_references(const GoalInput &in, const Scene<2> &scene,
                    std::vector<GoalSpec> &goals)
{
  if (in.reference.find_first_not_of(" \t") == std::string::npos)
    return;
  const std::string bad = in.reference_source + ": invalid value '" + in.reference +
                          "' for key 'goal.reference'; ";
  if (scene.exact() != nullptr)
    throw InputError(bad + "scene '" + scene.name() +
                     "' has an exact solution, from which the goals' errors are "
                     "computed; reference values are for scenes without one");
  const auto items = split(in.reference, ',');
  if (items.size() != goals.size())
    throw InputError(bad + "expected " + std::to_string(goals.size()) +
                     " comma-separated values (one per goal, each optionally "
                     "value+-uncertainty, or empty for none), got " +
                     std::to_string(items.size()));
  for (std::size_t g = 0; g < goals.size(); ++g)
  {
    if (items[g].empty())
      continue; // no reference value for this goal
    const auto pm = items[g].find("+-");
    const std::string value = items[g].substr(0, pm);
    const std::string unc = pm == std::string::npos ? "0" : items[g].substr(pm + 2);
    goals[g].reference = numbers(value, "goal.reference", 1, in.reference_source)[0];
    goals[g].reference_uncertainty =
        numbers(unc, "goal.reference", 1, in.reference_source)[0];
    if (goals[g].reference_uncertainty < 0)
      throw InputError(bad + "the uncertainty of goal " + goals[g].name +
                       " must be >= 0");
  }
}
} // namespace

void check_goal_names(const std::vector<GoalSpec> &goals, const std::string &key,
                      const std::string &where)
{
  for (std::size_t i = 0; i < goals.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (goals[i].name == goals[j].name)
        throw InputError(where + ": goal name '" + goals[i].name + "' appears twice in key '" +
                         key + "' (goals " + std::to_string(j + 1) + " and " +
                         std::to_string(i + 1) +
                         "); expected distinct names (an unnamed goal i is <kind>_i)");
}

GoalSpec parse_goal_item(const std::string &text, std::size_t i, const GoalSpec &defaults,
                         const std::string &key, const std::string &where,
                         const Scene<2> &scene)
{
  std::string item = trim_ws(text);
  GoalSpec g = defaults;
  if (const auto eq = item.find('='); eq != std::string::npos)
  {
    g.name = trim_ws(item.substr(0, eq));
    item = trim_ws(item.substr(eq + 1));
    if (g.name.empty() ||
        g.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                 "0123456789_") != std::string::npos)
      throw InputError(where + ": invalid goal name '" + g.name + "' in key '" + key +
                       "'; a goal name consists of letters, digits and _");
  }
  const auto space = item.find_first_of(" \t");
  for (const GoalType *t : goal_types())
    if (space != std::string::npos && item.substr(0, space) == t->name())
    {
      g.kind = t->name();
      item = trim_ws(item.substr(space + 1));
    }
  if (g.kind.empty())
  {
    std::string forms;
    for (const GoalType *t : goal_types())
      forms += (forms.empty() ? "" : " or ") + std::string("[name =] ") + t->name() +
               " " + t->syntax();
    throw InputError(where + ": invalid goal '" + trim_ws(text) + "' in key '" + key +
                     "'; expected " + forms);
  }
  const GoalType &type = goal_type(g.kind);
  if (g.name.empty())
    g.name = g.kind + "_" + std::to_string(i + 1);
  if (!type.has_radius())
    g.radius = 0;
  type.set_location(numbers(item, key, type.n_numbers(), where), scene,
                    where + ": invalid " + type.noun() + " '" + item + "' in key '" + key +
                        "'; ",
                    g);
  return g;
}

namespace
{
/// The goals of a list's items (goal.locations, scene.goals) by parse_goal_item, their
/// names checked by check_goal_names.
std::vector<GoalSpec> parse_goal_list(const std::vector<std::string> &items,
                                      const GoalSpec &defaults, const std::string &key,
                                      const std::string &where, const Scene<2> &scene)
{
  std::vector<GoalSpec> goals;
  for (std::size_t i = 0; i < items.size(); ++i)
    goals.push_back(parse_goal_item(items[i], i, defaults, key, where, scene));
  check_goal_names(goals, key, where);
  return goals;
}
} // namespace

std::vector<GoalSpec> make_goals(const GoalInput &in, const Scene<2> &scene)
{
  const std::string where = in.locations_source;
  std::vector<GoalSpec> goals;
  const Scene<2>::GoalText text = scene.goal_text();
  if (in.kind == "scene" && !trim_ws(text.items).empty())
  {
    GoalSpec defaults; // the kind must be given
    defaults.kind = "";
    defaults.over_time = text.over_time;
    defaults.radius = in.radius;
    goals = parse_goal_list(split_ws(text.items, ';'), defaults, "scene.goals", where,
                            scene);
  }
  else if (in.kind == "scene")
    goals = scene.default_goals(in.radius);
  else
  {
    const auto items = split(in.locations, ';');
    if (in.locations.empty() || items.empty())
      throw InputError(where + ": key 'goal.locations' is empty; goal.kind = " + in.kind +
                       " needs at least one location (" + goal_type(in.kind).syntax() +
                       ")");
    GoalSpec defaults;
    defaults.kind = in.kind;
    defaults.over_time = in.over_time;
    defaults.radius = in.radius;
    goals = parse_goal_list(items, defaults, "goal.locations", where, scene);
  }
  // a mollifier wider than the domain is no point goal (and makes J a domain mean)
  const auto box = scene.bounding_box();
  const double diameter = box[0].distance(box[1]);
  for (const auto &g : goals)
    if (goal_type(g.kind).has_radius() && !(g.radius <= diameter))
      throw InputError(in.radius_source + ": invalid value '" + six_digits(g.radius) +
                       "' for key 'goal.radius'; expected a number >= 0 and at most the "
                       "diameter " +
                       six_digits(diameter) + " of the domain " +
                       scene.domain_text() + " of scene '" + scene.name() + "'");
  if (in.weights != "auto" && in.weights != "estimate")
  {
    const auto w = split(in.weights, ',');
    if (w.size() != 1 && w.size() != goals.size())
      throw InputError(in.weights_source + ": invalid value '" + in.weights +
                       "' for key 'goal.weights'; "
                       "expected auto, estimate, one number or " +
                       std::to_string(goals.size()) +
                       " comma-separated numbers (one per goal)");
    const auto v = numbers(in.weights, "goal.weights", w.size(), in.weights_source);
    for (std::size_t g = 0; g < goals.size(); ++g)
      goals[g].weight = v[w.size() == 1 ? 0 : g];
  }
  set_references(in, scene, goals);
  return goals;
}


double goal_of_one(const Space<2> &space, const GoalSpec &goal)
{
  Vector<double> j;
  assemble_goal_vector(space, goal, j);
  return std::accumulate(j.begin(), j.end(), 0.);
}

bool goal_weight_resolved(const Space<2> &space, const GoalSpec &goal,
                          const Scene<2> &scene, double &w)
{
  w = goal_of_one(space, goal);
  return goal_type(goal.kind).weight_accepted(goal, scene, w);
}

void check_goal_weights(const Space<2> &space, const std::vector<GoalSpec> &goals,
                        const GoalInput &in, const Scene<2> &scene)
{
  for (const GoalSpec &goal : goals)
  {
    const GoalSpec g = unweighted(goal);
    double w = 0;
    const bool resolved = goal_weight_resolved(space, g, scene, w);
    if (!resolved)
      throw InputError(goal_type(g.kind).unresolved(
          space, g, in, scene,
          "the weight of goal " + g.name + " integrates to " + six_digits(w) +
              " instead of 1 on the mesh of loop 1"));
  }
}
} // namespace anisodwr
