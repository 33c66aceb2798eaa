#pragma once
// Marking and refinement (SPEC §6): per-direction marking of the theta_h fraction of
// cells with the largest |eta_h,i^K| (a cell marked in every direction is refined
// isotropically), isotropic marking by |eta_h^K|, uniform refinement, optional
// coarsening, bisection of the theta_tau fraction of slabs with the largest
// |eta_tau^n|, and the aspect ratio of the mesh.
#include "adaptivity/estimator.h"
#include "time/time_mesh.h"

#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>

#include <string>

namespace anisodwr
{
struct MarkingOptions
{
  std::string mode = "anisotropic"; ///< anisotropic | isotropic | uniform
  /// anisotropic mode: "joint" ranks all (cell, direction) pairs by |eta_h,i^K| together
  /// and marks the theta_h fraction of them; "per_direction" marks the theta_h fraction
  /// of cells separately in each direction (SPEC §6 literally; a cell whose indicators
  /// are all large is then cut in every direction even if one dominates).
  std::string marking = "joint";
  double theta_h = 0.25, theta_coarsen = 0.;
};

/// Sets refinement (and coarsening) flags on the active cells; deal.II's
/// prepare_coarsening_and_refinement then keeps the mesh one-irregular, refining
/// coarser neighbours in the needed direction. Returns the number of cells flagged.
template <int dim>
unsigned int mark_cells(dealii::Triangulation<dim> &tria, const Indicators<dim> &ind,
                        const MarkingOptions &options);

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
} // namespace anisodwr
