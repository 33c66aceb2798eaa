#include "study/options.h"

#include "adaptivity/refinement.h"
#include "slab/auto_solver.h"
#include "space/space.h"

#include <deal.II/base/bounding_box.h>

#include <algorithm>
#include <utility>

namespace anisodwr
{
SceneOptions scene_options(const Parameters &prm)
{
  SceneOptions o = prm.scene;
  o.variant_source = prm.source("scene.variant");
  for (const auto &[key, source] : prm.sources)
    if (key.rfind("scene.", 0) == 0)
      o.sources[key] = source;
  return o;
}

GoalInput goal_input(const Parameters &prm)
{
  GoalInput in = prm.goal;
  // a custom scene's own goals (goal.kind = scene) are placed by scene.goals
  in.locations_source = prm.scene.name == "custom" && in.kind == "scene"
                            ? prm.source("scene.goals")
                            : prm.source("goal.locations");
  in.radius_source = prm.source("goal.radius");
  in.weights_source = prm.source("goal.weights");
  in.reference_source = prm.source("goal.reference");
  return in;
}

SlabSolverOptions slab_solver_options(const Parameters &prm)
{
  return prm.solver; // the section is the solver's options plus the DoF order
}

MarkingOptions marking_options(const Parameters &prm)
{
  return prm.adaptivity; // the section is the marking options plus the loop's keys
}

unsigned int mapping_degree(const Parameters &prm, const dealii::Triangulation<2, 2> &tria)
{
  return prm.discretization.mapping_degree > 0
             ? prm.discretization.mapping_degree
             : auto_mapping_degree(tria, prm.discretization.p);
}

namespace
{
std::unique_ptr<Space<2>> make_space_with(const Parameters &prm, const Scene<2> &scene,
                                          const dealii::Triangulation<2, 2> &tria,
                                          unsigned int degree, double delta0,
                                          double tau_scale, bool inverse_bound = false,
                                          Space<2>::FaceRule natural_outflow = {})
{
  Stabilization stab = prm.discretization;
  stab.delta0 = delta0;
  stab.inverse_bound = inverse_bound;
  stab.supg_tau_factor *= tau_scale;
  auto space =
      std::make_unique<Space<2>>(scene, tria, degree, stab, mapping_degree(prm, tria));
  const DofNumbering numbering = prm.solver.dof_numbering;
  if (numbering != DofNumbering::automatic || prm.solver.type == SolverType::direct)
    space->set_downstream_numbering(numbering == DofNumbering::downstream);
  else
  {
    // auto: downstream for the Krylov solvers' ILU and Gauss-Seidel sweeps, native where
    // the slab systems go to the mode solver (UMFPACK orders them itself; native is
    // 4-6% faster in the marches and the estimator, doc/results.md)
    const SlabSolverOptions options = slab_solver_options(prm);
    const unsigned int m = prm.discretization.r + 1;
    const bool constant = !scene.coefficients_depend_on_time();
    space->set_downstream_numbering(
        [options, m, degree, constant](dealii::types::global_dof_index n)
        {
          return !solves_by_modes(options, double(n), m, degree, constant,
                                  options.reuse_factorization && constant);
        });
  }
  space->set_natural_outflow(std::move(natural_outflow));
  space->setup();
  return space;
}
} // namespace

std::unique_ptr<Space<2>> make_space(const Parameters &prm, const Scene<2> &scene,
                                     const dealii::Triangulation<2, 2> &tria,
                                     unsigned int degree, double tau_scale)
{
  return make_space_with(prm, scene, tria, degree, prm.discretization.delta0, tau_scale);
}

std::unique_ptr<Space<2>> make_enriched_space(const Parameters &prm, const Scene<2> &scene,
                                              const dealii::Triangulation<2, 2> &tria,
                                              unsigned int degree)
{
  return make_space_with(prm, scene, tria, degree, prm.discretization.delta0, 1.,
                         prm.adaptivity.adjoint_inverse_bound);
}

namespace
{
/// The distance from the segment [a, b] to the box (convex along the segment: a ternary
/// search).
double distance_to_box(const dealii::Point<2> &a, const dealii::Point<2> &b,
                       const dealii::BoundingBox<2> &box)
{
  const auto at = [&](double t)
  {
    const dealii::Point<2> p = a + t * (b - a);
    dealii::Point<2> q;
    for (unsigned int d = 0; d < 2; ++d)
      q[d] = std::clamp(p[d], box.lower_bound(d), box.upper_bound(d));
    return p.distance(q);
  };
  double lo = 0, hi = 1;
  for (int i = 0; i < 60; ++i)
  {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    const bool left = at(m1) <= at(m2);
    lo = left ? lo : m1;
    hi = left ? m2 : hi;
  }
  return std::min({at(0.), at(1.), at(0.5 * (lo + hi))});
}

/// adaptivity.adjoint_outflow = goals: a wall face is natural where a goal's support is
/// at the wall (within its own extent across the wall of the face), meets the face's
/// cell and is thinner across the face than the cell (a point goal's disk of radius r >
/// 0: extent 2r; a mean goal's rectangle: its extent along the face's normal). There
/// the exact adjoint rises from 0 at the wall to the goal's size within the support,
/// inside one cell, which the adjoint with z = 0 imposed at the wall cannot represent:
/// its test functions vanish where the goal sits. A larger support, or one away from
/// the wall, keeps z = 0: the free wall values would only add an O(delta_K) term
/// (boundary_layer's goal over half the domain: I_eff 1.57 instead of 0.96 at loop 1;
/// doc/results.md, "Goals inside an outflow layer").
Space<2>::FaceRule goal_wall_rule(const std::vector<GoalSpec> &goals)
{
  return [goals](const dealii::CellAccessor<2, 2> &cell, unsigned int f)
  {
    const auto face = cell.face(f);
    const dealii::Tensor<1, 2> n = outward_normal(cell, f);
    const double thickness = thickness_across(cell, f);
    const auto box = cell.bounding_box();
    for (const GoalSpec &g : goals)
    {
      std::array<double, 4> r;
      if (!support_rectangle(g, r))
        continue;
      const dealii::BoundingBox<2> support(
          std::make_pair(dealii::Point<2>(r[0], r[1]), dealii::Point<2>(r[2], r[3])));
      const double extent = support_extent(g, n[0], n[1]);
      if (extent < thickness &&
          box.get_neighbor_type(support) != dealii::NeighborType::not_neighbors &&
          distance_to_box(face->vertex(0), face->vertex(1), support) <= extent)
        return true;
    }
    return false;
  };
}
} // namespace

std::unique_ptr<Space<2>> make_adjoint_space(const Parameters &prm, const Scene<2> &scene,
                                             const dealii::Triangulation<2, 2> &tria,
                                             unsigned int degree,
                                             const std::vector<GoalSpec> &goals)
{
  const AdaptivitySection &a = prm.adaptivity;
  // never more SUPG than the primal's: a Galerkin primal gets a Galerkin adjoint (a
  // stabilized adjoint of an unstabilized primal overestimates a flux goal 5-6-fold,
  // doc/results.md, 'Error control without tuning')
  const double primal = prm.discretization.delta0;
  const double delta0 = a.adjoint_stabilization == AdjointStabilization::none ? 0.
                        : a.adjoint_delta0 >= 0 ? std::min(a.adjoint_delta0, primal)
                                                : primal;
  // the crosswind term is inconsistent: on an adjoint it spreads a goal's streak across b
  // by |b| h_perp / 2 (s_K = 1 on the first loop), and the estimate weights the residual
  // with that spread adjoint (doc/history.md, "Hemker: the goals' streaks and the
  // adjoint's crosswind term")
  Parameters without = prm;
  if (!a.adjoint_crosswind)
    without.discretization.crosswind0 = 0.;
  return make_space_with(without, scene, tria, degree, delta0, 1., a.adjoint_inverse_bound,
                         a.adjoint_outflow == AdjointOutflow::goals ? goal_wall_rule(goals)
                                                                    : Space<2>::FaceRule());
}

bool residual_crosswind(const Parameters &prm)
{
  return prm.discretization.crosswind0 > 0 &&
         prm.discretization.crosswind_form == CrosswindForm::residual;
}

bool first_loop_crosswind_switched(const Parameters &prm)
{
  return prm.discretization.crosswind_first_solve && residual_crosswind(prm);
}

bool marches_enriched_uq(const Parameters &prm)
{
  const GoalEstimate e = prm.adaptivity.goal_estimate;
  return e == GoalEstimate::enriched || e == GoalEstimate::both;
}

bool marches_consistent_uq(const Parameters &prm)
{
  const GoalEstimate e = prm.adaptivity.goal_estimate;
  return e == GoalEstimate::consistent || e == GoalEstimate::both;
}

bool consistent_uq_needs_own_operator(const Parameters &prm, bool switched)
{
  return prm.discretization.crosswind0 > 0. && prm.adaptivity.adjoint_crosswind && !switched;
}

std::vector<std::string> dwr_warnings(const Parameters &prm)
{
  std::vector<std::string> w;
  const auto &d = prm.discretization;
  // The dG(r+1) companion primal of this indicator marches the slabs with the primal's
  // delta_K; without the bound delta_K <= c tau_n it is unstable on short slabs while
  // dG(r) still looks fine (doc/results.md, "The higher-order eta_tau needs the SUPG
  // bound").
  if (prm.adaptivity.time_indicator == TimeIndicator::higher_order && d.delta0 > 0. &&
      d.supg_tau_factor == 0.)
    w.push_back("adaptivity.time_indicator = higher_order with discretization.delta0 > 0 "
                "and discretization.supg_tau_factor = 0: the dG(r+1) primal behind eta_tau "
                "is not stable on slabs shorter than delta_K, so eta_tau can be wrong by "
                "orders of magnitude (measured on the moving hump: 2.7e-4 instead of "
                "-4.5e-6); keep supg_tau_factor > 0 or use time_indicator = average");
  if (d.crosswind_form == CrosswindForm::residual && d.crosswind0 == 0.)
    w.push_back("discretization.crosswind_form = residual has no effect with "
                "discretization.crosswind0 = 0 (the crosswind term is off)");
  if (d.crosswind_first_solve && !residual_crosswind(prm))
    w.push_back("discretization.crosswind_first_solve has no effect unless "
                "discretization.crosswind_form = residual and discretization.crosswind0 > 0 "
                "(it sets the first loop's residual switch)");
  if (d.crosswind_exponent != 1. && !residual_crosswind(prm))
    w.push_back("discretization.crosswind_exponent has no effect unless "
                "discretization.crosswind_form = residual and discretization.crosswind0 > 0 "
                "(it is the power of the residual switch)");
  return w;
}
} // namespace anisodwr
