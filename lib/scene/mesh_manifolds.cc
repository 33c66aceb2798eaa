#include "scene/mesh_manifolds.h"

#include "base/errors.h"
#include "base/parse_number.h"
#include "base/text.h"

#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <limits>
#include <set>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// Whether the item lists the (material or boundary) id.
bool lists(const ManifoldItem &m, unsigned int id)
{
  return std::find(m.ids.begin(), m.ids.end(), id) != m.ids.end();
}

/// Each line of the cells of a `cells ids: polar x, y` item (but for boundary lines a
/// boundary item claims) must be an arc about the centre (its ends equally far from it)
/// or radial (its ends in one direction from it): PolarManifold bends any other line
/// into a spiral, which turns a straight wall into a curve the mesh never had.
void check_polar_cells(const std::vector<ManifoldItem> &items,
                       const Triangulation<2, 2> &mesh, const std::string &where)
{
  for (const ManifoldItem &m : items)
  {
    if (!m.on_cells || !m.polar)
      continue;
    for (const auto &cell : mesh.active_cell_iterators())
    {
      if (!lists(m, cell->material_id()))
        continue;
      for (const auto &face : cell->face_iterators())
      {
        if (face->at_boundary() &&
            std::any_of(items.begin(), items.end(), [&](const ManifoldItem &b)
                        { return !b.on_cells && lists(b, face->boundary_id()); }))
          continue;
        const Tensor<1, 2> a = face->vertex(0) - m.center, b = face->vertex(1) - m.center;
        const double ra = a.norm(), rb = b.norm(), tol = 1e-8 * std::max(ra, rb);
        const bool arc = std::abs(ra - rb) <= tol;
        const bool radial = std::abs(a[0] * b[1] - a[1] * b[0]) <= tol * std::max(ra, rb) &&
                            a * b >= 0;
        if (!arc && !radial)
        {
          std::ostringstream d;
          const auto xy = [](const Point<2> &p)
          {
            std::ostringstream o;
            o << "(" << p[0] << ", " << p[1] << ")";
            return o.str();
          };
          d << "the line from " << xy(face->vertex(0)) << " to " << xy(face->vertex(1))
            << " of these cells is neither an arc about " << xy(m.center)
            << " (its ends lie at distances " << ra << " and " << rb
            << " from it) nor radial";
          throw InputError(where + ": invalid item '" + m.text +
                           "' in key 'scene.manifolds': " + d.str() +
                           "; expected cells whose lines are arcs about the centre or "
                           "radial (use 'cells ids: transfinite' for cells between a "
                           "circle and straight lines)");
        }
      }
    }
  }
}
} // namespace

namespace
{
/// InputError (prefixed by `bad`) unless the vertices of the boundary faces that the
/// polar item m lists lie on one circle about its centre (given as the texts xy).
void check_on_circle(const ManifoldItem &m, const Triangulation<2, 2> &mesh,
                     const std::string &bad, const std::vector<std::string> &xy)
{
  double r_min = std::numeric_limits<double>::max(), r_max = 0;
  for (const auto &face : mesh.active_face_iterators())
    if (face->at_boundary() && lists(m, face->boundary_id()))
      for (unsigned int v = 0; v < 2; ++v)
      {
        r_min = std::min(r_min, face->vertex(v).distance(m.center));
        r_max = std::max(r_max, face->vertex(v).distance(m.center));
      }
  if (r_max - r_min > 1e-8 * r_max)
  {
    std::ostringstream d;
    d << r_min << " to " << r_max;
    throw InputError(bad + " in key 'scene.manifolds': the vertices of these boundary "
                           "faces lie at distances " + d.str() + " from (" + xy[0] +
                     ", " + xy[1] + "); expected one circle about the centre");
  }
}
} // namespace

std::vector<ManifoldItem> parse_manifolds(const std::string &text,
                                          const Triangulation<2, 2> &mesh,
                                          const std::string &where,
                                          const std::string &domain)
{
  std::vector<ManifoldItem> items;
  if (trim_ws(text).empty())
    return items;
  std::set<unsigned int> boundary_ids, material_ids;
  for (const auto &cell : mesh.active_cell_iterators())
  {
    material_ids.insert(cell->material_id());
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
        boundary_ids.insert(face->boundary_id());
  }
  for (const auto &item : split_ws(text, ';'))
  {
    const std::string bad = where + ": invalid item '" + item +
                            "' in key 'scene.manifolds'; expected 'boundary ids: polar x, "
                            "y', 'cells ids: polar x, y' or 'cells ids: transfinite', "
                            "items separated by ';'";
    ManifoldItem m;
    const auto colon = item.find(':');
    const auto space = item.find_first_of(" \t");
    if (colon == std::string::npos || space == std::string::npos || space > colon)
      throw InputError(bad);
    const std::string what = item.substr(0, space);
    if (what != "boundary" && what != "cells")
      throw InputError(bad);
    m.on_cells = what == "cells";
    for (const auto &s : split_ws(item.substr(space, colon - space), ','))
    {
      if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
        throw InputError(bad + " ('" + s + "' is not an id)");
      m.ids.push_back(std::stoul(s));
      const auto &known = m.on_cells ? material_ids : boundary_ids;
      if (!known.count(m.ids.back()))
        throw InputError(where + ": " + (m.on_cells ? "material id " : "boundary id ") + s +
                         " in key 'scene.manifolds' is not one of the domain " + domain +
                         " (its " + (m.on_cells ? "material ids" : "boundary ids") +
                         ": " + ids_text(known, "none") + ")");
    }
    std::istringstream rest(item.substr(colon + 1));
    std::string kind;
    rest >> kind;
    std::string args;
    std::getline(rest, args);
    if (kind == "transfinite" && m.on_cells && trim_ws(args).empty())
      m.polar = false;
    else if (kind == "polar")
    {
      const auto xy = split_ws(args, ',');
      double c[2] = {0, 0};
      if (xy.size() != 2 || parse_double(xy[0], c[0]) != NumberStatus::ok ||
          parse_double(xy[1], c[1]) != NumberStatus::ok)
        throw InputError(bad + " (polar needs its centre, two numbers x, y)");
      m.center = Point<2>(c[0], c[1]);
      if (!m.on_cells)
        check_on_circle(m, mesh, where + ": invalid item '" + item + "'", xy);
    }
    else
      throw InputError(bad);
    m.text = item;
    items.push_back(m);
  }
  check_polar_cells(items, mesh, where);
  return items;
}

void attach_manifolds(const std::vector<ManifoldItem> &items, Triangulation<2, 2> &tria)
{
  for (const bool cells : {true, false})
    for (std::size_t k = 0; k < items.size(); ++k)
      if (items[k].on_cells == cells)
        for (const auto &cell : tria.active_cell_iterators())
        {
          if (cells && lists(items[k], cell->material_id()))
            cell->set_all_manifold_ids(k);
          if (!cells)
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary() && lists(items[k], face->boundary_id()))
                face->set_manifold_id(k);
        }
  for (std::size_t k = 0; k < items.size(); ++k)
    if (items[k].polar)
      tria.set_manifold(k, PolarManifold<2>(items[k].center));
  for (std::size_t k = 0; k < items.size(); ++k)
    if (!items[k].polar)
    {
      TransfiniteInterpolationManifold<2> transfinite;
      transfinite.initialize(tria);
      tria.set_manifold(k, transfinite);
    }
}
} // namespace anisodwr
