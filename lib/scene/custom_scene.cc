#include "scene/custom_scene.h"

#include "base/errors.h"
#include "base/text.h"
#include "scene/mesh_check.h"
#include "scene/mesh_manifolds.h"
#include "scene/separable.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
const std::vector<std::string> xyt{"x", "y", "t"};
const std::vector<std::string> xyt_n{"x", "y", "t", "nx", "ny"};

/// A library's (deal.II's) error text in one line: its "Additional information", else
/// its first non-empty line.
std::string one_line(const std::string &what)
{
  std::string text = what;
  const auto info = text.find("Additional information:");
  if (info != std::string::npos)
    text = text.substr(info + 23);
  const auto end = text.find("\n\n", text.find_first_not_of(" \n"));
  text = text.substr(0, end == std::string::npos ? std::string::npos : end);
  std::string out;
  bool space = false;
  for (const char c : text)
    if (std::isspace(static_cast<unsigned char>(c)))
      space = !out.empty();
    else
    {
      if (space)
        out += ' ';
      out += c;
      space = false;
    }
  return out;
}

/// The unit normal of the straight face f of cell, pointing out of the cell.
Tensor<1, 2> outward_normal(const Triangulation<2>::active_cell_iterator &cell, unsigned int f)
{
  const auto face = cell->face(f);
  const Tensor<1, 2> e = face->vertex(1) - face->vertex(0);
  Tensor<1, 2> n({e[1], -e[0]});
  if (n * (face->center() - cell->center()) < 0)
    n = -n;
  return n / n.norm();
}

/// True if x lies in the polygon v (counter-clockwise or not) or within tol of its edges.
bool in_polygon(const Point<2> &x, const std::array<Point<2>, 4> &v, double tol)
{
  bool inside = false;
  for (unsigned int i = 0, j = 3; i < 4; j = i++)
  {
    const Point<2> &a = v[i], &b = v[j];
    if ((a[1] > x[1]) != (b[1] > x[1]) &&
        x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0])
      inside = !inside;
    // distance to the edge a-b
    const Tensor<1, 2> e = b - a;
    const double l2 = e.norm_square();
    const double s = l2 > 0 ? std::clamp((x - a) * e / l2, 0., 1.) : 0.;
    if ((x - (a + s * e)).norm() <= tol)
      return true;
  }
  return inside;
}

/// True if the segment a-b meets the open box (lo, hi) (Liang-Barsky clipping).
bool segment_meets_box(const Point<2> &a, const Point<2> &b, const Point<2> &lo,
                       const Point<2> &hi)
{
  double t0 = 0, t1 = 1;
  for (unsigned int d = 0; d < 2; ++d)
  {
    const double p = b[d] - a[d];
    for (const auto &[q, sign] :
         {std::pair{a[d] - lo[d], -1.}, std::pair{hi[d] - a[d], 1.}})
    {
      const double pd = sign * p;
      if (pd == 0.)
      {
        if (q <= 0.)
          return false;
      }
      else
      {
        const double r = q / pd;
        if (pd < 0)
          t0 = std::max(t0, r);
        else
          t1 = std::min(t1, r);
      }
    }
  }
  return t0 < t1;
}

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

/// The coarse mesh, and the cells and boundary faces of a refined copy (curved
/// boundaries follow their manifolds) for contains(), the bounding box and the samples.
struct CustomScene::Geometry
{
  Triangulation<2> coarse, fine;
  std::vector<std::array<Point<2>, 4>> cells; ///< counter-clockwise vertices
  std::vector<std::array<Point<2>, 2>> cell_boxes;
  std::vector<std::array<Point<2>, 2>> segments; ///< boundary faces
  std::array<Point<2>, 2> box;
  double tol = 0;
  std::set<types::boundary_id> ids;
  /// a generator's name and arguments; empty for a mesh file
  std::string generator, arguments;
  /// a mesh file's manifolds (scene.manifolds)
  std::vector<ManifoldItem> manifolds;

  void build(const SceneOptions &o, std::string &domain);
  /// The coarse mesh into `tria`: a generator's is generated again (its manifolds, e.g.
  /// a TransfiniteInterpolationManifold, then belong to `tria`), a file's copied.
  void make(Triangulation<2> &tria) const
  {
    if (generator.empty())
    {
      // created from the file's cells, not copied: copy_triangulation would copy the
      // mesh smoothing too, and `tria` keeps its own (the DWR meshes' anisotropic closure)
      const auto [vertices, cells, faces] = GridTools::get_coarse_mesh_description(coarse);
      tria.create_triangulation(vertices, cells, faces);
      attach_manifolds(manifolds, tria);
    }
    else
      GridGenerator::generate_from_name_and_arguments(tria, generator, arguments);
  }
  void read_mesh(const SceneOptions &o, std::string &domain);
};

void CustomScene::Geometry::read_mesh(const SceneOptions &o, std::string &domain)
{
  namespace fs = std::filesystem;
  const std::string key = "scene.mesh_file", where = o.source(key);
  fs::path path(o.custom.mesh_file);
  // a relative path in a config file is relative to the config file's directory
  if (path.is_relative() && where != "--set" && where != "default")
    path = fs::path(where).parent_path() / path;
  const std::string bad =
      where + ": invalid value '" + o.custom.mesh_file + "' for key '" + key + "': ";
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError(bad + "'" + path.string() +
                     "' is a directory; expected a Gmsh .msh file");
  std::ifstream in(path);
  if (!in)
    throw InputError(bad + "cannot read the file '" + path.string() +
                     "'; expected a Gmsh .msh file");
  const std::string unreadable =
      bad + "'" + path.string() + "' is not a Gmsh mesh of quadrilaterals deal.II can read: ";
  check_msh_file(in, unreadable);
  in.clear();
  in.seekg(0);
  try
  {
    GridIn<2> grid_in;
    grid_in.attach_triangulation(coarse);
    grid_in.read_msh(in);
  }
  catch (const std::exception &e)
  {
    throw InputError(unreadable + one_line(e.what()));
  }
  domain = "the mesh " + path.string();
}

void CustomScene::Geometry::build(const SceneOptions &o, std::string &domain)
{
  if (!trim_ws(o.custom.mesh_file).empty())
  {
    read_mesh(o, domain);
    manifolds = parse_manifolds(o.custom.manifolds, coarse, o.source("scene.manifolds"),
                                domain);
  }
  else
  {
    if (!trim_ws(o.custom.manifolds).empty())
      throw InputError(o.source("scene.manifolds") + ": key 'scene.manifolds' is for a "
                       "mesh file (scene.mesh_file); the generator scene.grid = '" +
                       o.custom.grid + "' attaches its own manifolds");
    const std::string &name = o.custom.grid, &args = o.custom.grid_arguments;
    check_repetitions(name, args, o.source("scene.grid_arguments"));
    try
    {
      GridGenerator::generate_from_name_and_arguments(coarse, name, args);
      generator = name;
      arguments = args;
    }
    catch (const std::exception &e)
    {
      throw InputError(
          o.source("scene.grid") + ": invalid grid '" + name + "' with arguments '" +
          args + "' (keys 'scene.grid', 'scene.grid_arguments'): " + one_line(e.what()) +
          "; expected the name of a deal.II GridGenerator function and its "
          "arguments after the triangulation, separated by ':'");
    }
    domain = name + "(" + args + ")";
  }
  if (coarse.n_active_cells() == 0)
    throw InputError(
        o.source(trim_ws(o.custom.mesh_file).empty() ? "scene.grid" : "scene.mesh_file") +
        ": the domain " + domain + " has no cells");
  const std::string key = trim_ws(o.custom.mesh_file).empty() ? "scene.grid" : "scene.mesh_file";
  check_coarse_mesh(coarse, o.source(key) + ": key '" + key + "': ", domain);
  for (const auto &face : coarse.active_face_iterators())
    if (face->at_boundary())
      ids.insert(face->boundary_id());

  // a refined copy with at most about 2e4 cells
  try
  {
    make(fine);
    unsigned int k = 0;
    while (k < 3 && fine.n_active_cells() * std::pow(4., k + 1) <= 2e4)
      ++k;
    fine.refine_global(k);
  }
  catch (const std::exception &e)
  {
    throw InputError(o.source(generator.empty() ? "scene.mesh_file" : "scene.grid") +
                     ": the domain " + domain + " cannot be refined: " + one_line(e.what()));
  }
  box = {{fine.begin_active()->vertex(0), fine.begin_active()->vertex(0)}};
  for (const auto &cell : fine.active_cell_iterators())
  {
    const std::array<Point<2>, 4> v{
        {cell->vertex(0), cell->vertex(1), cell->vertex(3), cell->vertex(2)}};
    std::array<Point<2>, 2> b{{v[0], v[0]}};
    for (const auto &p : v)
      for (unsigned int d = 0; d < 2; ++d)
      {
        b[0][d] = std::min(b[0][d], p[d]);
        b[1][d] = std::max(b[1][d], p[d]);
        box[0][d] = std::min(box[0][d], p[d]);
        box[1][d] = std::max(box[1][d], p[d]);
      }
    cells.push_back(v);
    cell_boxes.push_back(b);
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
        segments.push_back({{face->vertex(0), face->vertex(1)}});
  }
  tol = 1e-12 * box[0].distance(box[1]);
}

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

std::array<Point<2>, 2> CustomScene::bounding_box() const
{
  return geometry->box;
}

bool CustomScene::contains(const Point<2> &x) const
{
  const Geometry &G = *geometry;
  for (std::size_t c = 0; c < G.cells.size(); ++c)
    if (x[0] >= G.cell_boxes[c][0][0] - G.tol && x[0] <= G.cell_boxes[c][1][0] + G.tol &&
        x[1] >= G.cell_boxes[c][0][1] - G.tol && x[1] <= G.cell_boxes[c][1][1] + G.tol &&
        in_polygon(x, G.cells[c], G.tol))
      return true;
  return false;
}

bool CustomScene::contains_box(const Point<2> &lo, const Point<2> &hi) const
{
  if (!contains(lo) || !contains(hi) || !contains(Point<2>(lo[0], hi[1])) ||
      !contains(Point<2>(hi[0], lo[1])))
    return false;
  const Tensor<1, 2> shrink({geometry->tol, geometry->tol});
  for (const auto &s : geometry->segments)
    if (segment_meets_box(s[0], s[1], lo + shrink, hi - shrink))
      return false;
  return true;
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
        const Tensor<1, 2> n = outward_normal(cell, fi);
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

SamplePoints CustomScene::sample_points() const
{
  const Geometry &G = *geometry;
  SamplePoints s;
  s.length = G.box[0].distance(G.box[1]);
  for (const double a : {0.1, 0.35, 0.6, 0.85, 1.})
    s.times.push_back(a * end_time);
  const unsigned int n_cells = G.fine.n_active_cells();
  const unsigned int stride = std::max(1u, n_cells / 300);
  unsigned int i = 0;
  for (const auto &cell : G.fine.active_cell_iterators())
    if (i++ % stride == 0)
      s.interior.push_back(cell->center());
  // boundary: about 300 face centres, at least a few of every boundary id
  std::map<types::boundary_id, std::vector<SamplePoints::OnBoundary>> by_id;
  for (const auto &cell : G.fine.active_cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->at_boundary(f))
      {
        const auto face = cell->face(f);
        by_id[face->boundary_id()].push_back(
            {face->center(), outward_normal(cell, f), face->boundary_id()});
      }
  for (const auto &[id, points] : by_id)
  {
    const std::size_t step = std::max<std::size_t>(1, points.size() * by_id.size() / 300);
    for (std::size_t j = 0; j < points.size(); j += step)
      s.boundary.push_back(points[j]);
  }
  return s;
}
} // namespace anisodwr
