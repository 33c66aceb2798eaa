#pragma once
// The keys of the scene section that define a scene in the config (scene.name = custom):
// the domain, the coefficients and data as expressions, the boundary conditions by
// boundary id, an optional exact solution and default goals (lib/scene/custom_scene.h).
#include <string>

namespace anisodwr
{
struct CustomSceneOptions
{
  std::string constants = "";
  std::string grid = "hyper_cube";
  std::string grid_arguments = "0 : 1 : true";
  std::string mesh_file = "";
  std::string manifolds = "";
  std::string convection = "0; 0";
  std::string reaction = "0";
  std::string rhs = "0";
  std::string initial_value = "0";
  std::string dirichlet = "0, 1, 2, 3: 0";
  std::string neumann = "";
  std::string exact_solution = "";
  std::string goals = "";
  bool goals_over_time = false;
  double check_tolerance = 1e-6;
};
} // namespace anisodwr
