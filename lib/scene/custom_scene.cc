#include "scene/custom_scene.h"

#include "scene/custom_geometry.h"

#include "base/errors.h"
#include "base/text.h"
#include "scene/separable.h"

#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
const std::vector<std::string> xyt{"x", "y", "t"};
const std::vector<std::string> xyt_n{"x", "y", "t", "nx", "ny"};

/// The scene's exact solution u from its expression; the derivatives (which the
/// assembly of a custom scene does not use: f and the data are expressions) by
/// fourth-order central differences with steps 1e-3 of the domain's size and of T.
class ExpressionSolution : public ExactSolution<2>
{
public:
  ExpressionSolution(Expression u, double hx, double ht) : u(std::move(u)), hx(hx), ht(ht)
  {
  }
  double value(const Point<2> &p, double t) const override { return u(p[0], p[1], t); }
  Tensor<1, 2> gradient(const Point<2> &p, double t) const override
  {
    Tensor<1, 2> g;
    g[0] = d1([&](double s) { return u(p[0] + s, p[1], t); }, hx);
    g[1] = d1([&](double s) { return u(p[0], p[1] + s, t); }, hx);
    return g;
  }
  double laplacian(const Point<2> &p, double t) const override
  {
    return d2([&](double s) { return u(p[0] + s, p[1], t); }, hx) +
           d2([&](double s) { return u(p[0], p[1] + s, t); }, hx);
  }
  double time_derivative(const Point<2> &p, double t) const override
  {
    return d1([&](double s) { return u(p[0], p[1], t + s); }, ht);
  }

private:
  Expression u;
  double hx, ht;
  template <class F> static double d1(const F &f, double h)
  {
    return (-f(2 * h) + 8 * f(h) - 8 * f(-h) + f(-2 * h)) / (12 * h);
  }
  template <class F> static double d2(const F &f, double h)
  {
    return (-f(2 * h) + 16 * f(h) - 30 * f(0) + 16 * f(-h) - f(-2 * h)) / (12 * h * h);
  }
};
} // namespace

CustomScene::CustomScene(const SceneOptions &o) : geometry(std::make_unique<Geometry>())
{
  const CustomSceneOptions &c = o.custom;
  epsilon = o.epsilon;
  end_time = o.end_time;
  geometry->build(o, domain);
  const Constants constants =
      parse_constants(c.constants, {{"eps", o.epsilon}, {"pi", M_PI}}, "scene.constants",
                      o.source("scene.constants"));
  const auto parse = [&](const std::string &text, const std::string &key)
  { return Expression(text, xyt, constants, key, o.source(key)); };
  const auto parts = split_ws(c.convection, ';');
  if (parts.size() != 2)
    throw InputError(o.source("scene.convection") + ": invalid value '" + c.convection +
                     "' for key 'scene.convection'; expected two expressions b_x; b_y "
                     "separated by ';'");
  b[0] = parse(parts[0], "scene.convection");
  b[1] = parse(parts[1], "scene.convection");
  alpha = parse(c.reaction, "scene.reaction");
  f = parse(c.rhs, "scene.rhs");
  u0 = parse(c.initial_value, "scene.initial_value");
  time_dependent = b[0].uses("t") || b[1].uses("t") || alpha.uses("t");
  const SamplePoints samples = sample_points();
  if (!time_dependent)
  {
    const Expression rhs = f;
    // checked also on a 4 x 4 grid in every cell of the refined copy of the domain
    std::vector<Point<2>> centres;
    for (const auto &v : geometry->cells) // counter-clockwise vertices
      for (const double a : {0.125, 0.375, 0.625, 0.875})
        for (const double c : {0.125, 0.375, 0.625, 0.875})
          centres.push_back((1 - a) * (1 - c) * v[0] + a * (1 - c) * v[1] + a * c * v[2] +
                            (1 - a) * c * v[3]);
    separable = separate_in_time([rhs](const Point<2> &x, double t)
                                 { return rhs(x[0], x[1], t); },
                                 f.uses("t"), samples.interior, centres, end_time,
                                 load_terms);
  }
  read_boundary_data(o, constants);
  check_data_finite(o);
  goals = {o.custom.goals, o.custom.goals_over_time};
  if (!trim_ws(c.exact_solution).empty())
  {
    const double length = geometry->box[0].distance(geometry->box[1]);
    exact_solution = std::make_unique<ExpressionSolution>(
        parse(c.exact_solution, "scene.exact_solution"), 1e-3 * length, 1e-3 * end_time);
    DataKeys keys;
    for (const auto &key : {keys.rhs, keys.initial_value, keys.dirichlet, keys.neumann})
      keys.sources[key] = o.source(key);
    check_against_exact(*this, samples, c.check_tolerance,
                        o.source("scene.exact_solution"), keys);
  }
}

CustomScene::~CustomScene() = default;

void CustomScene::read_boundary_data(const SceneOptions &o, const Constants &constants)
{
  dirichlet_ids.clear();
  neumann_ids.clear();
  for (const std::string key : {"scene.dirichlet", "scene.neumann"})
  {
    const bool is_dirichlet = key == "scene.dirichlet";
    const std::string &text = is_dirichlet ? o.custom.dirichlet : o.custom.neumann;
    const std::string where = o.source(key);
    if (trim_ws(text).empty())
      continue;
    for (const auto &item : split_ws(text, ';'))
    {
      const auto colon = item.find(':');
      const std::string id_list = colon == std::string::npos ? "" : item.substr(0, colon);
      const bool ids_ok =
          !trim_ws(id_list).empty() &&
          id_list.find_first_not_of("0123456789, \t") == std::string::npos;
      if (!ids_ok)
        throw InputError(where + ": invalid item '" + item + "' in key '" + key +
                         "'; expected 'ids: expression' with comma-separated boundary "
                         "ids, items separated by ';'");
      const Expression g(item.substr(colon + 1), is_dirichlet ? xyt : xyt_n, constants,
                         key, where);
      for (const auto &s : split_ws(id_list, ','))
      {
        if (s.empty() || s.size() > 9 ||
            s.find_first_not_of("0123456789") != std::string::npos ||
            std::stoul(s) >= numbers::internal_face_boundary_id)
          throw InputError(where + ": invalid boundary id '" + s + "' in key '" + key +
                           "'; expected a number below " +
                           std::to_string(numbers::internal_face_boundary_id));
        const auto id = static_cast<types::boundary_id>(std::stoul(s));
        if (!geometry->ids.count(id))
          throw InputError(where + ": boundary id " + s + " in key '" + key +
                           "' is not a boundary id of the domain " + domain +
                           " (its ids: " + ids_text(geometry->ids) + ")");
        if (dirichlet_ids.count(id) || neumann_ids.count(id))
          throw InputError(where + ": boundary id " + s + " in key '" + key +
                           "' has a condition already (each id is in scene.dirichlet or "
                           "scene.neumann, once)");
        (is_dirichlet ? dirichlet_ids : neumann_ids).insert(id);
        (is_dirichlet ? g_dirichlet : g_neumann).emplace(id, g);
      }
    }
  }
  for (const auto id : geometry->ids)
    if (!dirichlet_ids.count(id) && !neumann_ids.count(id))
      throw InputError(o.source("scene.dirichlet") + ": boundary id " +
                       std::to_string(id) + " of the domain " + domain +
                       " has no condition; give it in scene.dirichlet or scene.neumann "
                       "(the domain's ids: " +
                       ids_text(geometry->ids) + ")");
}

void CustomScene::make_coarse_grid(Triangulation<2, 2> &tria) const
{
  geometry->make(tria);
}

Tensor<1, 2> CustomScene::convection(const Point<2> &x, double t) const
{
  return Tensor<1, 2>({b[0](x[0], x[1], t), b[1](x[0], x[1], t)});
}
double CustomScene::reaction(const Point<2> &x, double t) const
{
  return alpha(x[0], x[1], t);
}
double CustomScene::rhs(const Point<2> &x, double t) const
{
  return f(x[0], x[1], t);
}
double CustomScene::initial_value(const Point<2> &x) const
{
  return u0(x[0], x[1], 0.);
}
double CustomScene::dirichlet_value(const Point<2> &x, double t) const
{
  if (dirichlet_ids.empty())
    throw std::logic_error("custom scene: no Dirichlet boundary");
  return boundary_value(x, t, *dirichlet_ids.begin());
}
double CustomScene::neumann_value(const Point<2> &x, const Tensor<1, 2> &n,
                                  double t) const
{
  if (neumann_ids.empty())
    throw std::logic_error("custom scene: no Neumann boundary");
  return boundary_flux(x, n, t, *neumann_ids.begin());
}
double CustomScene::boundary_value(const Point<2> &x, double t,
                                   types::boundary_id id) const
{
  const auto it = g_dirichlet.find(id);
  if (it == g_dirichlet.end())
    throw std::logic_error("custom scene: no Dirichlet data on boundary id " +
                           std::to_string(id));
  return it->second(x[0], x[1], t);
}
double CustomScene::boundary_flux(const Point<2> &x, const Tensor<1, 2> &n, double t,
                                  types::boundary_id id) const
{
  const auto it = g_neumann.find(id);
  if (it == g_neumann.end())
    throw std::logic_error("custom scene: no Neumann data on boundary id " +
                           std::to_string(id));
  const double v[5] = {x[0], x[1], t, n[0], n[1]};
  return it->second(v);
}

std::vector<GoalSpec> CustomScene::default_goals(double radius) const
{
  GoalSpec g;
  g.name = "u_center_T";
  g.location = {0.5 * (geometry->box[0][0] + geometry->box[1][0]),
                0.5 * (geometry->box[0][1] + geometry->box[1][1])};
  g.radius = radius;
  return {g};
}

void CustomScene::check_data_finite(const SceneOptions &o) const
{
  const Geometry &G = *geometry;
  std::vector<double> times{0.};
  for (const double a : {0.25, 0.5, 0.75, 1.})
    times.push_back(a * end_time);
  auto fail = [&](const Expression &e, double value, const Point<2> &x, double t)
  {
    std::ostringstream at;
    at.precision(6);
    at << "(x, y, t) = (" << x[0] << ", " << x[1] << ", " << t << ")";
    throw InputError(o.source(e.key()) + ": key '" + e.key() + "': the expression '" +
                     e.text() + "' is " + (std::isnan(value) ? "NaN" : "infinite") +
                     " at " + at.str() + "; expected data finite on the domain");
  };
  // the vertices of the refined copy of the domain (where a singularity on a grid line
  // is met) and its cell centres
  std::vector<Point<2>> points;
  for (const auto &cell : G.fine.active_cell_iterators())
  {
    points.push_back(cell->center());
    for (const unsigned int v : cell->vertex_indices())
      points.push_back(cell->vertex(v));
  }
  for (const auto &x : points)
  {
    const double u = u0(x[0], x[1], 0.);
    if (!std::isfinite(u))
      fail(u0, u, x, 0.);
    for (const double t : times)
      for (const Expression *e : {&f, &alpha, &b[0], &b[1]})
      {
        const double v = (*e)(x[0], x[1], t);
        if (!std::isfinite(v))
          fail(*e, v, x, t);
      }
  }
  for (const auto &cell : G.fine.active_cell_iterators())
    for (const auto fi : cell->face_indices())
      if (cell->at_boundary(fi))
      {
        const auto face = cell->face(fi);
        const Tensor<1, 2> n = outward_normal(*cell, fi);
        for (const Point<2> &x : {face->vertex(0), face->vertex(1), face->center()})
          for (const double t : times)
          {
            if (const auto d = g_dirichlet.find(face->boundary_id()); d != g_dirichlet.end())
            {
              const double v = d->second(x[0], x[1], t);
              if (!std::isfinite(v))
                fail(d->second, v, x, t);
            }
            if (const auto g = g_neumann.find(face->boundary_id()); g != g_neumann.end())
            {
              const double a[5] = {x[0], x[1], t, n[0], n[1]};
              const double v = g->second(a);
              if (!std::isfinite(v))
                fail(g->second, v, x, t);
            }
          }
      }
}

} // namespace anisodwr
