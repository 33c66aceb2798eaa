#pragma once
// The manifolds of a mesh read from a Gmsh file (scene.manifolds), which the file cannot
// carry: curved boundaries (polar about a centre) and the transfinite interpolation of
// the cells next to them, so that refined vertices follow the curve.
#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace dealii
{
template <int dim, int spacedim> class Triangulation;
}

namespace anisodwr
{
/// One item of scene.manifolds: "boundary ids: polar x, y", "cells ids: polar x, y" or
/// "cells ids: transfinite" (ids: comma-separated boundary ids, or material ids, which
/// are the physical tags of a Gmsh file's quadrilaterals).
struct ManifoldItem
{
  bool on_cells = false; ///< cells by material id, else boundary faces by boundary id
  std::vector<unsigned int> ids;
  bool polar = true; ///< a PolarManifold about `center`, else transfinite (cells only)
  dealii::Point<2> center;
  std::string text; ///< the item as written, for messages
};

/// Reads scene.manifolds (items separated by ';') and checks its ids against `mesh`;
/// throws InputError "<where>: invalid item ... in key 'scene.manifolds'; ..." naming
/// the mesh's ids where an id is not in it, where a boundary item's faces are not on one
/// circle about its centre, and where a polar cells item's lines are neither arcs about
/// the centre nor radial.
std::vector<ManifoldItem> parse_manifolds(const std::string &text,
                                          const dealii::Triangulation<2, 2> &mesh,
                                          const std::string &where,
                                          const std::string &domain);

/// Gives item k the manifold id k (the cells' items first, on the cells and their faces,
/// then the boundary faces') and attaches its manifold to `tria` (a transfinite one
/// initialized on `tria`, after the polar ones).
void attach_manifolds(const std::vector<ManifoldItem> &items,
                      dealii::Triangulation<2, 2> &tria);
} // namespace anisodwr
