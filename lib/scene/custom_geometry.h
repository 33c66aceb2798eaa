#pragma once
// The custom scene's domain (scene/custom_scene.h): the coarse mesh from a generator or a
// Gmsh file, checked, and a refined copy of it for the geometric queries (contains,
// contains_box, the bounding box, the sample points). Private to lib/scene.
#include "scene/custom_scene.h"
#include "scene/mesh_manifolds.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/tria.h>

#include <array>
#include <set>
#include <string>
#include <vector>

namespace anisodwr
{
/// The coarse mesh, and the cells and boundary faces of a refined copy (curved
/// boundaries follow their manifolds) for contains(), the bounding box and the samples.
struct CustomScene::Geometry
{
  dealii::Triangulation<2> coarse, fine;
  std::vector<std::array<dealii::Point<2>, 4>> cells; ///< counter-clockwise vertices
  std::vector<std::array<dealii::Point<2>, 2>> cell_boxes;
  std::vector<std::array<dealii::Point<2>, 2>> segments; ///< boundary faces
  std::array<dealii::Point<2>, 2> box;
  double tol = 0;
  std::set<dealii::types::boundary_id> ids;
  /// a generator's name and arguments; empty for a mesh file
  std::string generator, arguments;
  /// a mesh file's manifolds (scene.manifolds)
  std::vector<ManifoldItem> manifolds;

  void build(const SceneOptions &o, std::string &domain);
  /// The coarse mesh into `tria`: a generator's is generated again (its manifolds, e.g.
  /// a TransfiniteInterpolationManifold, then belong to `tria`), a file's copied.
  void make(dealii::Triangulation<2> &tria) const;
  void read_mesh(const SceneOptions &o, std::string &domain);
};

} // namespace anisodwr
