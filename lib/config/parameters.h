#pragma once
// Typed, validated run parameters, read from a JSON config: one struct per section of
// the config, one member per key (prm.<section>.<key>).
//
// Every key is declared once, in the entry table (parameter_table.cc), which binds its
// name, default, pattern and documentation to its member; reading, `anisodwr defaults`,
// to_json and the unknown-key errors all come from that table. Choice-valued keys are
// enums with one name table each (base/choice.h). The member initializers below
// equal the table's defaults (checked by test_parameters).
#include "adaptivity/adaptivity_keys.h"
#include "base/choice.h"
#include "scene/goal_spec.h"
#include "scene/scene_options.h"
#include "slab/slab_solver_options.h"
#include "space/stabilization.h"

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace anisodwr
{
/// study.mode
enum class StudyMode
{
  single,      ///< one primal run
  convergence, ///< uniform refinement over study.levels levels
  dwr          ///< the adaptive DWR loop
};

inline const std::vector<Named<StudyMode>> &names(StudyMode)
{
  static const std::vector<Named<StudyMode>> table{
      {StudyMode::single, "single"},
      {StudyMode::convergence, "convergence"},
      {StudyMode::dwr, "dwr"}};
  return table;
}

/// study.refine: what a convergence study refines per level.
enum class StudyRefine
{
  space,
  time,
  both
};

inline const std::vector<Named<StudyRefine>> &names(StudyRefine)
{
  static const std::vector<Named<StudyRefine>> table{{StudyRefine::space, "space"},
                                                     {StudyRefine::time, "time"},
                                                     {StudyRefine::both, "both"}};
  return table;
}

/// The scene section: the scenes' own options (scene/scene_options.h).
using SceneSection = SceneOptions;

/// The discretization section: the stabilization (space/stabilization.h) and the meshes.
struct DiscretizationSection : Stabilization
{
  unsigned int p = 1;
  unsigned int r = 0;
  double growth_limit = 1e4;
  unsigned int initial_refinements = 2;
  /// a priori layer mesh at the outflow Dirichlet boundary (adaptivity/refinement.h)
  double wall_layer = 0.;
  /// a priori mesh along the goals' upstream paths (adaptivity/refinement.h)
  double goal_streak = 0.;
  /// the first DWR loop's crosswind factor from a march without the term (dwr/dwr.cc)
  bool crosswind_first_solve = false;
  unsigned int n_slabs = 5;
  /// MappingQ degree of the cells; 0 = auto_mapping_degree (space/space.h)
  unsigned int mapping_degree = 0;
};

/// Spatial DoF order (solver.dof_numbering): automatic ("auto") = downstream unless
/// solver.type = direct.
enum class DofNumbering
{
  automatic,
  native,
  downstream
};
inline const std::vector<Named<DofNumbering>> &names(DofNumbering)
{
  static const std::vector<Named<DofNumbering>> table{{DofNumbering::automatic, "auto"},
                                                      {DofNumbering::native, "native"},
                                                      {DofNumbering::downstream, "downstream"}};
  return table;
}

/// The slab solver's options (slab/, solver/) and the DoF order of the spaces.
struct SolverSection : SlabSolverOptions
{
  SolverSection() { type = SolverType::automatic; }
  DofNumbering dof_numbering = DofNumbering::automatic;
};

struct StudySection
{
  StudyMode mode = StudyMode::single;
  StudyRefine refine = StudyRefine::both;
  unsigned int levels = 4;
};

/// The goal section: the goals' own input (scene/goal_spec.h).
using GoalSection = GoalInput;

/// The adaptivity section: the marking options (adaptivity/adaptivity_keys.h) and the loop's.
struct AdaptivitySection : MarkingOptions
{
  unsigned int loops = 6;
  double theta_tau = 1.;
  /// refine time where |eta_tau| >= time_balance |eta_h|, space where |eta_h| >=
  /// time_balance |eta_tau| (dwr/dwr.cc, balance)
  double time_balance = 0.5;
  double tolerance = 0.;
  ToleranceMeasure tolerance_measure = ToleranceMeasure::parts;
  /// the tolerance stop also needs a previous loop and LoopRow::eta_drift <=
  /// tolerance_drift * tolerance where eta_drift is defined (0: not checked)
  double tolerance_drift = 1.;
  double max_dofs = 0.;
  double max_memory_mb = 0.;
  double max_wall_time = 0.; ///< s; 0: no budget
  TimeIndicator time_indicator = TimeIndicator::higher_order;
  bool per_goal_estimates = false;
  GoalEstimate goal_estimate = GoalEstimate::dwr;
  bool measure_time_error = false;
  bool concurrent_marches = true;
  unsigned int adjoint_degree = 0;
  SpaceIndicator space_indicator = SpaceIndicator::primal_residual;
  AdjointStabilization adjoint_stabilization = AdjointStabilization::transposed;
  AdjointOutflow adjoint_outflow = AdjointOutflow::goals;
  double adjoint_delta0 = 0.1; ///< < 0: discretization.delta0
  /// the adjoint's delta_K <= h_min^2 / (eps q^4) (Stabilization::inverse_bound)
  bool adjoint_inverse_bound = true;
  /// the adjoint carries the primal's crosswind term (discretization.crosswind0)
  bool adjoint_crosswind = true;
  /// cells leaving the bounds by more than this fraction of their range are halved
  /// along b (cells_out_of_bounds); 0: off
  double bound_refinement = 0.;
  /// the estimator's rule for f and u_0: QGauss(deg W + 2) iterated this many times
  unsigned int data_rule_copies = 3;
  /// eta_h carries the primal's quadrature error in f and u_0
  bool data_quadrature_error = true;
  /// the spatial weights use the conforming interpolant at hanging nodes
  bool conforming_weights = true;
};

struct OutputSection
{
  std::string directory = "results/moving_hump";
  unsigned int vtu_every = 1;
  bool progress = true;
  unsigned int vtu_loops = 1;
  unsigned int dump_slab_loop = 0;
};

struct Parameters
{
  SceneSection scene;
  DiscretizationSection discretization;
  SolverSection solver;
  StudySection study;
  GoalSection goal;
  AdaptivitySection adaptivity;
  OutputSection output;

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
