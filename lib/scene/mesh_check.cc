#include "scene/mesh_check.h"

#include "base/errors.h"
#include "base/text.h"

#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <vector>

namespace anisodwr
{
using namespace dealii;

namespace
{
std::string point(const Point<2> &p)
{
  std::ostringstream s;
  s.precision(8);
  s << "(" << p[0] << ", " << p[1] << ")";
  return s.str();
}

double cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
{
  return a[0] * b[1] - a[1] * b[0];
}
} // namespace

namespace
{
/// InputError if a cell is not a quadrilateral.
void check_quadrilaterals(const Triangulation<2> &tria, const std::string &head)
{
  unsigned int other = 0;
  for (const auto &cell : tria.active_cell_iterators())
    if (!cell->reference_cell().is_hyper_cube())
      ++other;
  if (other > 0)
    throw InputError(head + " has " + std::to_string(other) + " of its " +
                     std::to_string(tria.n_active_cells()) +
                     " cells that are not quadrilaterals (triangles); expected "
                     "quadrilaterals only (Gmsh: 'Recombine Surface' in the .geo file, or "
                     "Mesh.RecombineAll = 1 and Mesh.Algorithm = 8)");
}

/// The distance below which two points count as one: 1e-12 of the bounding box's
/// diagonal of the used vertices `ids`; InputError for a coordinate beyond 1e8 or not
/// finite.
double check_coordinates(const std::vector<Point<2>> &vertices,
                         const std::vector<unsigned int> &ids, const std::string &head)
{
  Point<2> lo = vertices[ids[0]], hi = lo;
  for (const unsigned int v : ids)
    for (unsigned int d = 0; d < 2; ++d)
    {
      lo[d] = std::min(lo[d], vertices[v][d]);
      hi[d] = std::max(hi[d], vertices[v][d]);
    }
  // coordinates whose squares, areas and quadrature weights overflow or lose every digit
  constexpr double largest = 1e8;
  for (unsigned int d = 0; d < 2; ++d)
    if (!std::isfinite(lo[d]) || !std::isfinite(hi[d]) ||
        std::max(std::abs(lo[d]), std::abs(hi[d])) > largest)
    {
      std::ostringstream v;
      v << (std::abs(lo[d]) > std::abs(hi[d]) ? lo[d] : hi[d]);
      throw InputError(head + " has a vertex coordinate " + (d == 0 ? "x" : "y") + " = " +
                       v.str() + " beyond 1e8 in size; expected a domain within [-1e8, 1e8]^2 "
                       "(rescale x, and eps, b and the data with it)");
    }
  return 1e-12 * lo.distance(hi);
}

/// InputError if two of the vertices `ids` (sorted by x) lie within tol.
void check_distinct_nodes(const std::vector<Point<2>> &vertices,
                          const std::vector<unsigned int> &ids, double tol,
                          const std::string &head)
{
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (std::size_t j = i + 1;
         j < ids.size() && vertices[ids[j]][0] - vertices[ids[i]][0] <= tol; ++j)
      if (vertices[ids[i]].distance(vertices[ids[j]]) <= tol)
        throw InputError(head + " has two nodes at the point " + point(vertices[ids[i]]) +
                         " that its cells do not share (a crack: the interface between "
                         "the cells becomes boundary); expected each point once");
}

/// InputError for a cell with a degenerate or inverted corner (deal.II's vertex order
/// is 0, 1, 3, 2 counter-clockwise).
void check_cell_corners(const Triangulation<2> &tria, const std::string &head)
{
  static constexpr std::array<std::array<unsigned int, 3>, 4> corners{
      {{{0, 1, 2}}, {{1, 3, 0}}, {{3, 2, 1}}, {{2, 0, 3}}}};
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &c : corners)
    {
      const Tensor<1, 2> a = cell->vertex(c[1]) - cell->vertex(c[0]),
                         b = cell->vertex(c[2]) - cell->vertex(c[0]);
      if (!(cross(a, b) > 1e-10 * a.norm() * b.norm()))
        throw InputError(head + ": its cell " + std::to_string(cell->index()) +
                         " with the vertices " + point(cell->vertex(0)) + ", " +
                         point(cell->vertex(1)) + ", " + point(cell->vertex(3)) + ", " +
                         point(cell->vertex(2)) + " has zero area, crossed edges or the "
                         "wrong orientation at its corner " + point(cell->vertex(c[0])) +
                         "; expected convex cells with positive area");
    }
}

/// InputError for a vertex inside a boundary face (a hanging coarse node); ids: the used
/// vertices sorted by x.
void check_no_hanging_nodes(const Triangulation<2> &tria,
                            const std::vector<unsigned int> &ids, double tol,
                            const std::string &head)
{
  const auto &vertices = tria.get_vertices();
  std::vector<std::array<unsigned int, 2>> faces;
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
        faces.push_back({{face->vertex_index(0), face->vertex_index(1)}});
  for (const auto &f : faces)
  {
    const Point<2> &a = vertices[f[0]], &b = vertices[f[1]];
    const Tensor<1, 2> e = b - a;
    const double l2 = e.norm_square();
    const double x0 = std::min(a[0], b[0]) - tol, x1 = std::max(a[0], b[0]) + tol;
    auto first = std::lower_bound(ids.begin(), ids.end(), x0,
                                  [&](unsigned int v, double x) { return vertices[v][0] < x; });
    for (auto it = first; it != ids.end() && vertices[*it][0] <= x1; ++it)
    {
      const unsigned int v = *it;
      if (v == f[0] || v == f[1])
        continue;
      const double s = (vertices[v] - a) * e / l2;
      if (s <= 0. || s >= 1.)
        continue;
      if (std::abs(cross(e, vertices[v] - a)) / std::sqrt(l2) <= tol)
        throw InputError(head + " has the node " + point(vertices[v]) +
                         " inside the boundary edge from " + point(a) + " to " + point(b) +
                         " (a hanging coarse node: the cells on the two sides do not "
                         "share their edge); expected a conforming mesh");
    }
  }
}
} // namespace

void check_coarse_mesh(const Triangulation<2> &tria, const std::string &prefix,
                       const std::string &domain)
{
  const std::string head = prefix + "the domain " + domain;
  check_quadrilaterals(tria, head);
  const auto &vertices = tria.get_vertices();
  const auto &used = tria.get_used_vertices();
  std::vector<unsigned int> ids;
  for (unsigned int v = 0; v < vertices.size(); ++v)
    if (used[v])
      ids.push_back(v);
  if (ids.empty())
    return;
  const double tol = check_coordinates(vertices, ids, head);
  std::sort(ids.begin(), ids.end(),
            [&](unsigned int a, unsigned int b) { return vertices[a][0] < vertices[b][0]; });
  check_distinct_nodes(vertices, ids, tol, head);
  check_cell_corners(tria, head);
  check_no_hanging_nodes(tria, ids, tol, head);
}

void check_msh_node_tags(std::istream &in, const std::string &prefix)
{
  std::string line;
  double version = 0;
  while (std::getline(in, line))
  {
    if (line.rfind("$MeshFormat", 0) == 0)
    {
      int binary = 0;
      in >> version >> binary;
      if (binary != 0)
        return;
    }
    if (line.rfind("$Nodes", 0) == 0)
      break;
  }
  if (!in)
    return;
  std::set<long long> tags;
  auto add = [&](long long tag)
  {
    if (!tags.insert(tag).second)
      throw InputError(prefix + "the node " + std::to_string(tag) +
                       " is defined twice in $Nodes; expected each node tag once");
  };
  if (version < 4)
  {
    long long n = 0;
    in >> n;
    for (long long i = 0; i < n && in; ++i)
    {
      long long tag;
      double x, y, z;
      in >> tag >> x >> y >> z;
      if (in)
        add(tag);
    }
    return;
  }
  long long blocks = 0, n = 0, min_tag, max_tag;
  in >> blocks >> n >> min_tag >> max_tag;
  for (long long b = 0; b < blocks && in; ++b)
  {
    long long dim, entity, parametric, count;
    in >> dim >> entity >> parametric >> count;
    std::vector<long long> block(std::max(0LL, count));
    for (auto &t : block)
      in >> t;
    for (const long long t : block)
      if (in)
        add(t);
    for (long long i = 0; i < count && in; ++i)
    {
      double x, y, z;
      in >> x >> y >> z;
      for (long long p = 0; p < (parametric ? dim : 0); ++p)
        in >> x;
    }
  }
}
void check_repetitions(const std::string &name, const std::string &arguments,
                       const std::string &where)
{
  const std::size_t count = name == "subdivided_hyper_rectangle" ? 2
                            : name == "subdivided_hyper_cube"     ? 1
                                                                  : 0;
  if (count == 0)
    return;
  const std::string first = arguments.substr(0, arguments.find(':'));
  const std::vector<std::string> numbers = split_ws(first, ',');
  double cells = 1;
  bool whole = numbers.size() == count;
  for (const std::string &n : numbers)
  {
    whole = whole && !n.empty() && n.size() <= 9 &&
            n.find_first_not_of("0123456789") == std::string::npos && std::stoul(n) >= 1;
    if (whole)
      cells *= std::stod(n);
  }
  if (!whole || cells > 1e6)
    throw InputError(where + ": key 'scene.grid_arguments' = '" + arguments + "': the " +
                     name + " repetitions '" + first + "' " +
                     (whole ? "ask for " + std::to_string(static_cast<long long>(cells)) +
                                  " cells"
                            : std::string("are not ") + (count == 2 ? "two" : "one") +
                                  " whole number" + (count == 2 ? "s" : "") + " >= 1") +
                     "; expected " + (count == 2 ? "two whole numbers 'nx, ny'" : "one whole number n") +
                     " >= 1 with at most 1e6 cells (refine further with "
                     "discretization.initial_refinements)");
}
} // namespace anisodwr
