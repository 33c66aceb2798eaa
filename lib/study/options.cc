#include "study/options.h"

namespace anisodwr
{
SceneOptions scene_options(const Parameters &prm)
{
  SceneOptions o;
  o.name = prm.scene;
  o.variant = prm.variant;
  o.epsilon = prm.epsilon;
  o.end_time = prm.end_time;
  o.name_source = prm.source("scene.name");
  o.variant_source = prm.source("scene.variant");
  return o;
}

GoalInput goal_input(const Parameters &prm)
{
  GoalInput in;
  in.kind = prm.goal_kind;
  in.locations = prm.goal_locations;
  in.over_time = prm.goal_over_time;
  in.radius = prm.goal_radius;
  in.weights = prm.goal_weights;
  in.locations_source = prm.source("goal.locations");
  in.radius_source = prm.source("goal.radius");
  in.weights_source = prm.source("goal.weights");
  return in;
}

SlabSolverOptions slab_solver_options(const Parameters &prm)
{
  SlabSolverOptions o;
  o.type = prm.solver_type;
  o.reuse_factorization = prm.reuse_factorization;
  o.auto_threshold = prm.solver_auto_threshold;
  o.auto_memory_mb = prm.solver_auto_memory_mb;
  o.fallback = prm.fallback;
  o.iterative.krylov = prm.krylov;
  o.iterative.preconditioner = prm.preconditioner;
  o.iterative.tolerance = prm.solver_tolerance;
  o.iterative.restart = prm.restart;
  o.iterative.max_iterations = prm.max_iterations;
  o.iterative.ilu_fill = prm.ilu_fill;
  o.iterative.spatial_preconditioner = prm.spatial_preconditioner;
  o.iterative.amg_smoother = prm.amg_smoother;
  o.iterative.stagnation_window = prm.stagnation_window;
  o.iterative.stagnation_factor = prm.stagnation_factor;
  return o;
}
} // namespace anisodwr
