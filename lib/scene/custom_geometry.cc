#include "scene/custom_geometry.h"

#include "base/errors.h"
#include "base/text.h"
#include "scene/mesh_check.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

namespace anisodwr
{
using namespace dealii;

namespace
{
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
} // namespace

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
      bad + "'" + path.string() +
      "' is not a Gmsh mesh of quadrilaterals deal.II can read: ";
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

void CustomScene::Geometry::make(Triangulation<2> &tria) const
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

void CustomScene::Geometry::build(const SceneOptions &o, std::string &domain)
{
  if (!trim_ws(o.custom.mesh_file).empty())
  {
    read_mesh(o, domain);
    manifolds =
        parse_manifolds(o.custom.manifolds, coarse, o.source("scene.manifolds"), domain);
  }
  else
  {
    if (!trim_ws(o.custom.manifolds).empty())
      throw InputError(o.source("scene.manifolds") +
                       ": key 'scene.manifolds' is for a "
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
  const std::string key =
      trim_ws(o.custom.mesh_file).empty() ? "scene.grid" : "scene.mesh_file";
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
                     ": the domain " + domain +
                     " cannot be refined: " + one_line(e.what()));
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
            {face->center(), outward_normal(*cell, f), face->boundary_id()});
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
