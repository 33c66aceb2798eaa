#include "goal/goal_input.h"

#include "base/errors.h"
#include "base/parse_number.h"
#include "goal/goal.h"

#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// v with 6 significant digits (g.radius is finite here)
std::string six_digits(double v)
{
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

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
                       "'; expected " + std::to_string(n) +
                       " comma-separated finite numbers");
    v.push_back(value);
  }
  if (v.size() != n)
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
                     "value+-uncertainty), got " +
                     std::to_string(items.size()));
  for (std::size_t g = 0; g < goals.size(); ++g)
  {
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

std::vector<GoalSpec> make_goals(const GoalInput &in, const Scene<2> &scene)
{
  const std::string where = in.locations_source;
  std::vector<GoalSpec> goals;
  if (in.kind == GoalKind::scene)
    goals = scene.default_goals(in.radius);
  else
  {
    const auto items = split(in.locations, ';');
    if (in.locations.empty() || items.empty())
      throw InputError(where + ": key 'goal.locations' is empty; goal.kind = " +
                       name(in.kind) + " needs at least one location");
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      GoalSpec g;
      g.kind = in.kind;
      g.over_time = in.over_time;
      g.name = name(in.kind) + "_" + std::to_string(i + 1);
      if (g.kind == GoalKind::point)
      {
        g.center = numbers(items[i], "goal.locations", 2, where);
        g.radius = in.radius;
        if (!scene.contains(Point<2>(g.center[0], g.center[1])))
          throw InputError(where + ": invalid point '" + items[i] +
                           "' in key 'goal.locations'; it lies outside the domain " +
                           scene.domain_text() + " of scene '" + scene.name() + "'");
      }
      else
      {
        const auto v = numbers(items[i], "goal.locations", 4, where);
        g.lower = {v[0], v[1]};
        g.upper = {v[2], v[3]};
        if (!(v[2] > v[0] && v[3] > v[1]))
          throw InputError(
              where + ": invalid rectangle '" + items[i] +
              "' in key 'goal.locations'; expected x0,y0,x1,y1 with x1 > x0, "
              "y1 > y0");
        if (!scene.contains_box(Point<2>(v[0], v[1]), Point<2>(v[2], v[3])))
          throw InputError(where + ": invalid rectangle '" + items[i] +
                           "' in key 'goal.locations'; it is not inside the domain " +
                           scene.domain_text() + " of scene '" + scene.name() + "'");
      }
      goals.push_back(g);
    }
  }
  // a mollifier wider than the domain is no point goal (and makes J a domain mean)
  const auto box = scene.bounding_box();
  const double diameter = box[0].distance(box[1]);
  for (const auto &g : goals)
    if (g.kind == GoalKind::point && !(g.radius <= diameter))
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

namespace
{
/// The integral of the goal's weight function by its quadrature on the space's mesh:
/// the sum of its goal vector (the shape functions sum to 1).
double total_weight(const Space<2> &space, const GoalSpec &goal)
{
  Vector<double> j;
  assemble_goal_vector(space, goal, j);
  return std::accumulate(j.begin(), j.end(), 0.);
}

/// Whether the goal's weight integrates to its exact value (w: the integral).
bool resolved(const Space<2> &space, const GoalSpec &goal, const Scene<2> &scene,
              double &w)
{
  w = total_weight(space, goal);
  const double s = goal.kind == GoalKind::point ? goal.radius : 0.;
  if (s > 0 && !scene.contains_box(Point<2>(goal.center[0] - s, goal.center[1] - s),
                                   Point<2>(goal.center[0] + s, goal.center[1] + s)))
    return w > 0 && w <= 1 + goal_weight_tolerance(goal.kind); // leaves the domain
  return std::abs(w - 1.) <= goal_weight_tolerance(goal.kind);
}
} // namespace

void check_goal_weights(const Space<2> &space, const std::vector<GoalSpec> &goals,
                        const GoalInput &in, const Scene<2> &scene)
{
  const auto box = scene.bounding_box();
  const double diameter = box[0].distance(box[1]);
  for (const GoalSpec &goal : goals)
  {
    GoalSpec g = unweighted(goal);
    double w = 0, grown_w = 0;
    if (resolved(space, g, scene, w))
      continue;
    const std::string integrates = "the weight of goal " + g.name + " integrates to " +
                                   six_digits(w) + " instead of 1 on the mesh of loop 1";
    // the smallest size accepted: the goal grown about its centre by factors of 2
    if (g.kind == GoalKind::point)
    {
      std::string smallest = "no radius up to the domain's diameter is accepted there";
      for (double s = 2. * g.radius; s <= diameter; s *= 2.)
        if (g.radius = s; resolved(space, g, scene, grown_w))
        {
          smallest =
              "the smallest radius (in steps of 2) accepted there is " + six_digits(s);
          break;
        }
      throw InputError(in.radius_source + ": invalid value '" + six_digits(goal.radius) +
                       "' for key 'goal.radius': " + integrates +
                       " (the mollifier is too small for the cells); expected a radius "
                       "whose mollifier the mesh resolves: " +
                       smallest);
    }
    const double cx = 0.5 * (g.lower[0] + g.upper[0]),
                 cy = 0.5 * (g.lower[1] + g.upper[1]);
    double hx = 0.5 * (g.upper[0] - g.lower[0]), hy = 0.5 * (g.upper[1] - g.lower[1]);
    std::string smallest =
        "none of the larger rectangles about its centre (in steps of 2) "
        "inside the domain is accepted there; refine the initial mesh "
        "(discretization.initial_refinements)";
    // the shorter side doubled first (a thin strip widened), then both
    const auto grow = [&]()
    {
      const double x = hx, y = hy;
      hx = x <= y ? 2. * x : x;
      hy = y <= x ? 2. * y : y;
    };
    for (grow();
         scene.contains_box(Point<2>(cx - hx, cy - hy), Point<2>(cx + hx, cy + hy));
         grow())
    {
      g.lower = {cx - hx, cy - hy};
      g.upper = {cx + hx, cy + hy};
      if (resolved(space, g, scene, grown_w))
      {
        smallest =
            "the smallest one about its centre (in steps of 2) accepted there is " +
            six_digits(2. * hx) + " x " + six_digits(2. * hy);
        break;
      }
    }
    throw InputError(in.locations_source + ": invalid value '" + in.locations +
                     "' in key 'goal.locations': " + integrates +
                     " (the rectangle is too small for the cells it cuts, which are "
                     "not axis-parallel); expected a rectangle the mesh resolves: " +
                     smallest);
  }
}
} // namespace anisodwr
