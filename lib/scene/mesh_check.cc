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

namespace
{
/// Reads the ASCII sections of a Gmsh file token by token; every read that fails or
/// gives a count out of range throws InputError naming the section and the entry.
class MshReader
{
public:
  MshReader(std::istream &in, const std::string &prefix) : in(in), prefix(prefix) {}

  /// Moves to the line that starts with `header`; false at the end of the file.
  bool seek(const std::string &header)
  {
    std::string line;
    while (std::getline(in, line))
      if (line.rfind(header, 0) == 0)
        return true;
    in.clear();
    return false;
  }
  long long integer(const std::string &what, long long lo = 0, long long hi = 100000000)
  {
    long long v = 0;
    std::string token;
    in >> token;
    std::size_t used = 0;
    bool ok = !token.empty();
    try
    {
      v = std::stoll(token, &used);
    }
    catch (const std::exception &)
    {
      ok = false;
    }
    if (!ok || used != token.size() || v < lo || v > hi)
      fail(what + ": '" + token + "' is not a whole number in [" + std::to_string(lo) +
           ", " + std::to_string(hi) + "]");
    return v;
  }
  double real(const std::string &what)
  {
    std::string token;
    in >> token;
    std::size_t used = 0;
    double v = 0;
    bool ok = !token.empty();
    try
    {
      v = std::stod(token, &used);
    }
    catch (const std::exception &)
    {
      ok = false;
    }
    if (!ok || used != token.size() || !std::isfinite(v))
      fail(what + ": '" + token + "' is not a finite number");
    return v;
  }
  void end(const std::string &section)
  {
    std::string token;
    in >> token;
    if (token != "$End" + section)
      fail("expected $End" + section + " after the entries the $" + section +
           " section announces, found '" + token + "' (a wrong count or a malformed entry)");
  }
  /// A format-4 section's blocks: the counts line (blocks, entries, smallest and
  /// largest tag), then per block its line (entity dimension, entity tag, `third`:
  /// parametric flag or element type, at most third_hi; the number of entries, at most
  /// what the section's count leaves) and body(what, third, dim, count), which reads
  /// the block's entries. The blocks must hold the announced number of entries.
  template <typename Body>
  void each_block(const std::string &section, const std::string &third, long long third_hi,
                  const Body &body)
  {
    const long long blocks = integer("$" + section + ": the number of blocks"),
                    n = integer("$" + section + ": the number of entries");
    integer("$" + section + ": the smallest tag");
    integer("$" + section + ": the largest tag");
    long long total = 0;
    for (long long b = 0; b < blocks; ++b)
    {
      const std::string what = "$" + section + ": block " + std::to_string(b + 1);
      const long long dim = integer(what + ", the entity dimension", 0, 3);
      integer(what + ", the entity tag", -100000000);
      const long long v = integer(what + ", " + third, 0, third_hi);
      const long long count = integer(what + ", the number of entries", 0, n - total);
      total += count;
      body(what, v, dim, count);
    }
    if (total != n)
      fail("$" + section + " announces " + std::to_string(n) + " entries, its blocks hold " +
           std::to_string(total));
  }
  [[noreturn]] void fail(const std::string &what) const
  {
    throw InputError(prefix + what);
  }

private:
  std::istream &in;
  const std::string prefix;
};

/// The number of nodes of a Gmsh element type (0 for a type the check does not know).
unsigned int nodes_of_type(long long type)
{
  switch (type)
  {
    case 15: return 1; // point
    case 1: return 2;  // line
    case 8: return 3;  // second-order line
    case 2: return 3;  // triangle
    case 3: return 4;  // quadrilateral
    case 4: return 4;  // tetrahedron
    case 9: return 6;  // second-order triangle
    case 16: return 8; // serendipity quadrilateral
    case 10: return 9; // second-order quadrilateral
    case 5: return 8;  // hexahedron
    default: return 0;
  }
}

void skip_entities(MshReader &r)
{
  if (!r.seek("$Entities"))
    r.fail("format 4 needs an $Entities section");
  const long long n_points = r.integer("$Entities: the number of points"),
                  n_curves = r.integer("$Entities: the number of curves"),
                  n_surfaces = r.integer("$Entities: the number of surfaces"),
                  n_volumes = r.integer("$Entities: the number of volumes");
  for (long long i = 0; i < n_points; ++i)
  {
    const std::string what = "$Entities: point " + std::to_string(i + 1);
    r.integer(what + " tag", -100000000);
    for (int k = 0; k < 3; ++k)
      r.real(what + " coordinate");
    const long long tags = r.integer(what + " number of physical tags", 0, 1000);
    for (long long k = 0; k < tags; ++k)
      r.integer(what + " physical tag", -100000000);
  }
  for (long long i = 0; i < n_curves + n_surfaces + n_volumes; ++i)
  {
    const std::string what = "$Entities: entity " + std::to_string(n_points + i + 1);
    r.integer(what + " tag", -100000000);
    for (int k = 0; k < 6; ++k)
      r.real(what + " bounding box");
    const long long tags = r.integer(what + " number of physical tags", 0, 1000);
    for (long long k = 0; k < tags; ++k)
      r.integer(what + " physical tag", -100000000);
    const long long bounding = r.integer(what + " number of bounding entities", 0, 100000);
    for (long long k = 0; k < bounding; ++k)
      r.integer(what + " bounding entity", -100000000);
  }
  r.end("Entities");
}
} // namespace

namespace
{
/// $MeshFormat: whether the file is ASCII (false: binary, which deal.II refuses itself)
/// and of format 4.1 (`v4`), else 2.x.
bool read_format(MshReader &r, bool &v4)
{
  if (!r.seek("$MeshFormat"))
    r.fail("no $MeshFormat section (deal.II reads Gmsh's ASCII format 2.2 or 4.1)");
  const double version = r.real("$MeshFormat: the version");
  const long long binary = r.integer("$MeshFormat: the file type", 0, 1);
  if (binary != 0)
    return false;
  if (!(version >= 2 && version < 3) && version != 4.1)
    r.fail("format version " + std::to_string(version) +
           "; deal.II reads Gmsh's ASCII format 2.2 or 4.1");
  r.integer("$MeshFormat: the data size", 1, 16);
  r.end("MeshFormat");
  v4 = version > 3;
  return true;
}

/// $Nodes: the node tags, each defined once.
std::set<long long> read_nodes(MshReader &r, bool v4, const std::string &prefix)
{
  std::set<long long> tags;
  auto add = [&](long long tag)
  {
    if (!tags.insert(tag).second)
      throw InputError(prefix + "the node " + std::to_string(tag) +
                       " is defined twice in $Nodes; expected each node tag once");
  };
  if (!r.seek("$Nodes"))
    r.fail("no $Nodes section");
  if (!v4)
  {
    const long long n = r.integer("$Nodes: the number of nodes");
    for (long long i = 0; i < n; ++i)
    {
      const std::string what = "$Nodes: entry " + std::to_string(i + 1);
      add(r.integer(what + ", the node tag", 1));
      for (int k = 0; k < 3; ++k)
        r.real(what + ", a coordinate");
    }
  }
  else
    r.each_block("Nodes", "the parametric flag", 1,
                 [&](const std::string &what, long long parametric, long long dim,
                     long long count)
                 {
                   for (long long i = 0; i < count; ++i)
                     add(r.integer(what + ", a node tag", 1));
                   for (long long i = 0; i < count; ++i)
                     for (long long k = 0; k < 3 + (parametric ? dim : 0); ++k)
                       r.real(what + ", a coordinate");
                 });
  r.end("Nodes");
  return tags;
}

/// $Elements: known types, each node one of `tags`.
void read_elements(MshReader &r, bool v4, const std::set<long long> &tags)
{
  if (!r.seek("$Elements"))
    r.fail("no $Elements section");
  auto element = [&](const std::string &what, long long type)
  {
    const unsigned int n_nodes = nodes_of_type(type);
    if (n_nodes == 0)
      r.fail(what + ": element type " + std::to_string(type) +
             " is none of Gmsh's point, line, triangle or quadrilateral types");
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      const long long node = r.integer(what + ", a node", 1, 1000000000000LL);
      if (!tags.count(node))
        r.fail(what + " refers to node " + std::to_string(node) +
               ", which $Nodes does not define");
    }
  };
  if (!v4)
  {
    const long long n = r.integer("$Elements: the number of elements");
    for (long long i = 0; i < n; ++i)
    {
      const std::string what = "$Elements: entry " + std::to_string(i + 1);
      r.integer(what + ", the element number", 1, 1000000000000LL);
      const long long type = r.integer(what + ", the type", 1, 200);
      const long long n_tags = r.integer(what + ", the number of tags", 0, 100);
      for (long long k = 0; k < n_tags; ++k)
        r.integer(what + ", a tag", -100000000);
      element(what, type);
    }
  }
  else
    r.each_block("Elements", "the type", 200,
                 [&](const std::string &what, long long type, long long, long long count)
                 {
                   for (long long i = 0; i < count; ++i)
                   {
                     r.integer(what + ", an element tag", 1, 1000000000000LL);
                     element(what, type);
                   }
                 });
  r.end("Elements");
}
} // namespace

void check_msh_file(std::istream &in, const std::string &prefix)
{
  MshReader r(in, prefix);
  bool v4 = false;
  if (!read_format(r, v4))
    return; // deal.II refuses binary files itself
  if (v4)
    skip_entities(r);
  const std::set<long long> tags = read_nodes(r, v4, prefix);
  read_elements(r, v4, tags);
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
