#pragma once
// Marking and refinement (doc/method.md §9): per-direction marking of the theta_h
// fraction of cells with the largest |eta_h,i^K| (a cell marked in every direction is
// refined isotropically), isotropic marking by |eta_h^K|, uniform refinement, optional
// coarsening, bisection of the theta_tau fraction of slabs with the largest
// |eta_tau^n|, and the aspect ratio of the mesh.
#include "adaptivity/estimator.h"
#include "scene/goal_spec.h"
#include "time/time_mesh.h"

#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <string>
#include <vector>

namespace anisodwr
{
template <int dim> class Scene;

/// What the marking did, counted on the active cells before refinement.
struct MarkingStats
{
  unsigned int marked = 0;   ///< cells flagged by the marking strategy
  unsigned int cut_x = 0;    ///< ... of them cut in x only
  unsigned int cut_y = 0;    ///< ... in y only
  unsigned int cut_both = 0; ///< ... in every direction (isotropic)
  unsigned int closure = 0;  ///< cells flagged or extended by the mesh closure
  unsigned int refined = 0;  ///< cells refined in the end (marked + closure)
};

/// Sets refinement (and coarsening) flags on the active cells; deal.II's
/// prepare_coarsening_and_refinement then keeps the mesh one-irregular. Build `tria`
/// with Triangulation::allow_anisotropic_smoothing (anisotropic_tria_smoothing()) so
/// that the closure is anisotropic: the coarser cell at the end of a hanging-node
/// chain is refined only in the direction the chain needs (without the flag deal.II
/// 9.4 refines it isotropically; both tested in test_refinement).
template <int dim>
MarkingStats mark_cells(dealii::Triangulation<dim> &tria, const Indicators<dim> &ind,
                        const MarkingOptions &options);

/// The mesh smoothing for the DWR meshes: anisotropic closure in anisotropic mode,
/// deal.II's default (none) otherwise, so isotropic and uniform runs stay isotropic.
template <int dim>
typename dealii::Triangulation<dim>::MeshSmoothing
tria_smoothing(const MarkingOptions &options)
{
  return options.mode == AdaptivityMode::anisotropic
             ? dealii::Triangulation<dim>::allow_anisotropic_smoothing
             : dealii::Triangulation<dim>::none;
}

/// Cells where the discrete solution leaves its bounds: for each active cell (by
/// active_cell_index) 1 + the local axis most parallel to b at its centre (the axis
/// whose halving shortens the cell along the flow), or 0 where every nodal value of
/// every vector in `u` lies within [u_min - threshold, u_max + threshold], or where the
/// cell's length along that axis is below min_aspect times its other lengths. Halving such
/// a cell along b resolves the change of the solution along the flow where a long
/// anisotropic cell lets SUPG oscillate (adaptivity.bound_refinement).
template <int dim>
std::vector<unsigned char>
cells_out_of_bounds(const dealii::DoFHandler<dim> &dofs,
                    const std::vector<dealii::Vector<double>> &u, double u_min,
                    double u_max, double threshold, double min_aspect,
                    const std::function<dealii::Tensor<1, dim>(const dealii::Point<dim> &)> &b);

/// Adds to the refinement flags of the active cells the cut of `cuts` (as returned by
/// cells_out_of_bounds; a cell flagged already gets the union of both cuts). Returns the
/// number of cells whose flag changed.
template <int dim>
unsigned int add_cuts(dealii::Triangulation<dim> &tria, const std::vector<unsigned char> &cuts);

/// What refine_wall_layer did.
struct WallLayer
{
  static constexpr unsigned int max_passes = 30;
  unsigned int passes = 0;
  unsigned int cells_before = 0, cells_after = 0;
  /// the smallest target thickness factor eps / (b.n) of a halved cell (0: none)
  double thinnest_target = 0.;
};

/// A priori layer mesh at the outflow Dirichlet boundary (discretization.wall_layer):
/// where Dirichlet data meets a flow that leaves the domain (b.n > 0 at a boundary
/// face's centre at t = 0, T/2 or T) the solution has an exponential layer of length
/// scale eps / (b.n). Halves the active cells at such faces across the face
/// (anisotropically, along the cell's local axis normal to it), pass after pass, until
/// each is at most factor eps / (b.n) thick there (the distance of the centres of the
/// wall face and the opposite face). Only the cells at the wall are halved, so the
/// thickness grows by 2 per cell away from it; deal.II adds the tangential cuts that
/// keep a curved wall's thin cells undistorted. Throws InputError (naming the key),
/// before refining, if a wall cell needs more than WallLayer::max_passes halvings.
/// factor <= 0: nothing.
WallLayer refine_wall_layer(dealii::Triangulation<2> &tria, const Scene<2> &scene,
                            double factor);

/// One line for the run's output: "wall layer: P halvings, cells A -> B, thinnest
/// target W" (or that no face is an outflow Dirichlet face).
std::string wall_layer_text(const WallLayer &w);

/// What refine_goal_streak did.
struct GoalStreak
{
  static constexpr unsigned int max_passes = 30;
  unsigned int goals = 0; ///< the point and mean goals traced
  unsigned int passes = 0;
  unsigned int cells_before = 0, cells_after = 0;
  /// the smallest target thickness w / factor of a halved cell (0: none)
  double thinnest_target = 0.;
};

/// A priori mesh along the goals' upstream characteristics (discretization.goal_streak).
/// Where eps is small against |b| times a goal's support width w, the goal's adjoint is
/// its support carried upstream along -b over [0, T]: a streak w wide across b, and a
/// same-mesh adjoint on cells much thicker than w cannot hold it (the goal's estimate is
/// then a fraction of its error, of either sign). Traces the centre of each point goal
/// (radius > 0; w = 2 r) and mean goal (w = the rectangle's width across b) back along
/// -b(x, t) from t = T to 0 (midpoint rule, 400 steps, until the path leaves the mesh),
/// and halves, pass after pass, the active cells whose centre lies within (w + the cell's
/// own width across b) / 2 of the path, along each local axis that lies at least 45
/// degrees across b and spans more than w / factor across it. Throws InputError (naming the key) if a
/// cell would need more than GoalStreak::max_passes halvings. factor <= 0: nothing.
GoalStreak refine_goal_streak(dealii::Triangulation<2> &tria, const Scene<2> &scene,
                              const std::vector<GoalSpec> &goals, double factor);

/// One line for the run's output: "goal streak: P halvings along G goals' upstream
/// paths, cells A -> B, thinnest target W".
std::string goal_streak_text(const GoalStreak &s);

/// Bisects the ceil(theta_tau N) slabs with the largest |eta_tau^n| (none if theta_tau =
/// 0).
TimeMesh refine_time(const TimeMesh &mesh, const std::vector<double> &eta_tau_slab,
                     double theta_tau);

/// Largest aspect ratio over cells and quadrature points: sigma_max / sigma_min of the
/// Jacobian of the cell map. `per_cell` (optional) receives each cell's value.
template <int dim>
double max_aspect_ratio(const dealii::Triangulation<dim> &tria,
                        const dealii::Mapping<dim> &mapping,
                        std::vector<double> *per_cell = nullptr);

/// The geometric mismatch at hanging nodes: for every face with a hanging vertex, the
/// distance of that vertex (placed by the manifold) from the coarse cell's straight face
/// (MappingQ1), divided by the smallest vertex distance of the fine cells on the face.
/// The largest ratio over the mesh; values near 1 or above mean that the fine cells
/// overlap the coarse one, or leave a gap, by their own thickness (curved boundaries
/// with thin cells).
template <int dim> double max_hanging_gap(const dealii::Triangulation<dim> &tria);
} // namespace anisodwr
