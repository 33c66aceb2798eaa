#pragma once
// The run parameters (config/parameters.h) as the options of the layers below study/:
// the scene section for scene/, the goal section for goal/, the solver section for
// slab/.
#include "config/parameters.h"
#include "goal/goal_input.h"
#include "scene/scene.h"
#include "slab/slab_solver_options.h"

#include <memory>

namespace anisodwr
{
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
} // namespace anisodwr
