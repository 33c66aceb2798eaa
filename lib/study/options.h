#pragma once
// The run parameters (config/parameters.h) as the options of the layers below study/:
// the scene section for scene/, the goal section for goal/, the solver section for
// slab/, the adaptivity section for the marking, and the spaces of a run.
#include "config/parameters.h"
#include "goal/goal_input.h"
#include "scene/goal_spec.h"
#include "scene/scene.h"
#include "slab/slab_solver_options.h"

#include <memory>
#include <string>
#include <vector>

namespace anisodwr
{
template <int dim> class Space;
struct MarkingOptions;

/// The scene section of the run parameters.
SceneOptions scene_options(const Parameters &prm);

/// The scene named in the run parameters (create_scene of scene_options(prm)).
template <int dim> std::unique_ptr<Scene<dim>> create_scene(const Parameters &prm)
{
  return create_scene<dim>(scene_options(prm));
}

/// The goal section of the run parameters.
GoalInput goal_input(const Parameters &prm);

/// The solver section of the run parameters.
SlabSolverOptions slab_solver_options(const Parameters &prm);

/// The marking options of the adaptivity section.
MarkingOptions marking_options(const Parameters &prm);

/// The MappingQ degree of the run's spaces: discretization.mapping_degree, or for 0
/// (auto) auto_mapping_degree of `tria` (p on curved manifolds, else 1).
unsigned int mapping_degree(const Parameters &prm, const dealii::Triangulation<2, 2> &tria);

/// The FE_Q(degree) space of a run on `tria`, mapped by mapping_degree(prm, tria), set up: SUPG from the discretization
/// section, DoFs numbered as solver.dof_numbering says. tau_scale multiplies
/// supg_tau_factor (the bound delta_K <= supg_tau_factor * tau_n): the temporal error
/// check gives its three time meshes the bound of the finest with 1/4, 1/2, 1.
std::unique_ptr<Space<2>> make_space(const Parameters &prm, const Scene<2> &scene,
                                     const dealii::Triangulation<2, 2> &tria,
                                     unsigned int degree, double tau_scale = 1.);
/// The primal of adaptivity.goal_estimate = enriched: as make_space in the adjoint's
/// degree, with delta_K within the inverse bound h_min^2 / (eps q^4) where
/// adaptivity.adjoint_inverse_bound is on (SUPG's delta of degree p can make degree q
/// unstable on thin cells, as it would the adjoint).
std::unique_ptr<Space<2>> make_enriched_space(const Parameters &prm, const Scene<2> &scene,
                                              const dealii::Triangulation<2, 2> &tria,
                                              unsigned int degree);
/// The adjoint's space: as make_space, with the delta0 of the adaptivity section
/// (adjoint_stabilization, adjoint_delta0) and, with adjoint_outflow = goals, the outflow
/// Dirichlet faces natural where a goal's support lies within the wall cell.
std::unique_ptr<Space<2>> make_adjoint_space(const Parameters &prm, const Scene<2> &scene,
                                             const dealii::Triangulation<2, 2> &tria,
                                             unsigned int degree,
                                             const std::vector<GoalSpec> &goals = {});

/// Whether the loops switch the crosswind term by the last loop's residual
/// (discretization.crosswind_form = residual with crosswind0 > 0).
bool residual_crosswind(const Parameters &prm);
/// Whether the first DWR loop has a crosswind factor s_K from a solution
/// (crosswind_first_solve with residual_crosswind); else s_K = 1 on every cell there.
bool first_loop_crosswind_switched(const Parameters &prm);

/// adaptivity.goal_estimate: whether the loops march enriched's u_q (enriched, both)
/// and consistent's (consistent, both).
bool marches_enriched_uq(const Parameters &prm);
bool marches_consistent_uq(const Parameters &prm);

/// goal_estimate = consistent: whether u_q needs an operator of its own because the
/// adjoint carries a crosswind term that no solution switches (`switched`: the loop has
/// a factor s_K from a solution), which u_q leaves out (doc/method.md §8).
bool consistent_uq_needs_own_operator(const Parameters &prm, bool switched);

/// Warnings on combinations of DWR keys that run but are known to mislead (each one
/// line, naming the keys; empty if there are none). The loop prints them first.
std::vector<std::string> dwr_warnings(const Parameters &prm);
} // namespace anisodwr
