#pragma once
// Typed, validated run parameters, read from a JSON config.
//
// Every key is declared once (parameters.cc: the entry table) with its default,
// its pattern and its documentation. `anisodwr defaults` prints that table as a
// loadable JSON file in which "#key" entries hold the documentation.
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace anisodwr
{
struct Parameters
{
  // [scene]
  std::string scene = "moving_hump";
  std::string variant = "";
  double epsilon = 1e-6;
  double end_time = 0.5;

  // [discretization]
  unsigned int p = 1;
  unsigned int r = 0;
  double delta0 = 1.0;
  std::string supg_length = "volume";
  double supg_tau_factor = 1.;
  unsigned int initial_refinements = 2;
  unsigned int n_slabs = 5;

  // [solver]
  std::string solver_type = "auto";
  bool reuse_factorization = true;
  double solver_auto_threshold = 1e6;
  double solver_auto_memory_mb = 0.; ///< 0: half the physical memory
  std::string krylov = "gmres";
  std::string preconditioner = "kronecker_presb";
  double solver_tolerance = 1e-10;
  unsigned int restart = 30;
  unsigned int max_iterations = 500;
  double ilu_fill = 1.;
  std::string spatial_preconditioner = "ilu";
  std::string amg_smoother = "ilu";
  unsigned int stagnation_window = 50;
  double stagnation_factor = 10.;
  std::string fallback = "direct";

  // [study]
  std::string mode = "single";
  std::string refine = "both";
  unsigned int levels = 4;

  // [goal]
  std::string goal_kind = "scene";
  std::string goal_locations = "";
  bool goal_over_time = false;
  double goal_radius = 0.01;
  std::string goal_weights = "1";

  // [adaptivity]
  std::string adaptivity_mode = "anisotropic";
  std::string marking = "cell";
  double kappa = 0.75;
  unsigned int loops = 6;
  double theta_h = 0.25;
  double theta_tau = 0.2;
  double theta_coarsen = 0.;
  double tolerance = 0.;
  double max_dofs = 0.;
  double max_memory_mb = 0.;
  double max_wall_time = 0.; ///< s; 0: no budget
  unsigned int adjoint_degree = 0;
  std::string adjoint_stabilization = "transposed";
  std::string space_indicator = "average";
  std::string dof_numbering = "native";
  bool measure_time_error = false;
  std::string time_indicator = "average";
  bool per_goal_estimates = false;

  // [output]
  std::string output_directory = "results/moving_hump";
  unsigned int vtu_every = 1;
  bool progress = true;
  unsigned int vtu_loops = 1;

  /// Where each key's value came from: the config file's path, "--set" or "default".
  std::map<std::string, std::string> sources;
  /// sources[key] ("default" if unknown); messages start with it.
  std::string source(const std::string &key) const;

  /// Reads `file`, then applies the overrides "section.key=value" in order.
  /// Throws InputError naming the file, key and value on any problem.
  static Parameters read(const std::string &file,
                         const std::vector<std::string> &overrides);
  /// Defaults with overrides only (no file); used by tests.
  static Parameters from_overrides(const std::vector<std::string> &overrides);
  /// Prints the complete default configuration as documented JSON.
  static void print_defaults(std::ostream &out);
  /// The configuration as JSON (values only), for summary.json.
  std::string to_json(unsigned int indent) const;
};
} // namespace anisodwr
