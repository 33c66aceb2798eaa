#pragma once
// The adaptive DWR loop of run_dwr (dwr/dwr.h), internal to lib/dwr/: the class that
// sequences the loops. Its parts by job:
//   dwr.cc          the loop: solves, estimate, refinement (time and space balanced),
//                   stop, tables
//   dwr_adjoint.cc  goals, weights, the adjoint march(es), the estimate from them, the
//                   slab solver options and the loop's memory check
#include "adaptivity/estimator.h"
#include "adaptivity/refinement.h"
#include "config/parameters.h"
#include "goal/goal.h"
#include "io/loop_report.h"
#include "io/table.h"
#include "slab/primal_march.h"
#include "slab/slab_operator.h"
#include "study/memory_estimate.h"
#include "dwr/probes.h"

#include <deal.II/base/timer.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria.h>

#include <functional>
#include <future>
#include <map>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace anisodwr::dwr_loop
{
using namespace dealii;

constexpr double dwr_nan = std::numeric_limits<double>::quiet_NaN();

/// An adjoint operator that two threads may hold (goal_estimate = consistent: the
/// primal thread marches u_q by its factors while the adjoint thread marches).
using SharedOperator = std::shared_ptr<const SlabOperator<2>>;

/// The adjoint march of a loop: its slab operator, the adjoint slab solutions (one set
/// per goal with goal.weights = estimate or per_goal_estimates, else one for the
/// weighted goal) and its wall time.
struct AdjointMarch
{
  std::shared_ptr<SlabOperator<2>> op;
  std::vector<std::vector<Vector<double>>> Z;
  /// goal_estimate = consistent or both: each goal's value of u_q (the adjoint's operator
  /// solved untransposed); empty otherwise and where that march failed
  std::vector<double> J_hi;
  double wall = 0;
};

/// The adaptive loop of run_dwr: the scene, goals and meshes, the tables, and per loop
/// the solves, the estimate, the outputs and the refinement.
class AdaptiveLoop
{
public:
  explicit AdaptiveLoop(const Parameters &prm);
  void run();

private:
  /// The loop's solves, goal values and indicators on the current meshes (ind), whether
  /// the run stops after it (stop, from stop_after), and its outputs (probes, cut lines,
  /// VTU; a stopping loop writes its VTU). False if the DoF budget stops the run first.
  bool solve_and_estimate(LoopRow &row, Indicators<2> &ind, bool &stop);
  /// N_space, N_t, N_tot of the loop into row; false (with stop_reason) if N_tot exceeds
  /// adaptivity.max_dofs.
  bool within_dof_budget(LoopRow &row, const Space<2> &primal);
  /// The primal march (U), the dG(r+1) primal of time_indicator = higher_order (U_hi)
  /// and the goal values; with row.concurrent the adjoint march(es) in a second thread,
  /// returned (else an empty AdjointMarch: the caller marches them after).
  /// With row.concurrent and `uq_spaces` (own_uq_operator), the primal thread then
  /// marches a u_q on each by its own operator (march_own_uq; its time is in t_primal);
  /// with row.concurrent and uq_by_adjoint_factors it marches consistent's u_q by the
  /// adjoint's factors beside the adjoints where that operator serves every slab
  /// (SlabOperator::prepared_for; time in t_primal, values returned in J_hi).
  AdjointMarch march_both(LoopRow &row, const Space<2> &primal, const Space<2> &adjoint,
                          const MarchOptions &opt, std::vector<Vector<double>> &U,
                          const TemporalBasis &basis_hi, std::vector<Vector<double>> &U_hi,
                          const std::vector<std::unique_ptr<Space<2>>> &uq_spaces);
  /// NumericalError naming the loop (label) if an indicator or a goal value is NaN/Inf.
  void check_finite(const LoopRow &row, const Indicators<2> &ind,
                    const std::string &label) const;
  /// What the next loop's refinement and mesh take from this loop's solution U: the
  /// crosswind factor by cell (crosswind_form = residual) and the bound cuts
  /// (adaptivity.bound_refinement).
  void prepare_refinement(const LoopRow &row, const Space<2> &primal,
                          const std::vector<Vector<double>> &U);
  /// The slab solver options, with the dump of the first slab matrix to
  /// slab-<problem>-loop-NNNN.mtx in loop output.dump_slab_loop; UMFPACK (no auto
  /// choice inside a march thread) when the marches are concurrent.
  SlabSolverOptions march_solver_options(unsigned int loop, const std::string &problem,
                                         bool concurrent) const;
  /// The loop's memory estimate, checked against the limit (ResourceLimitError).
  /// Returns whether the primal and the adjoint march concurrently
  /// (adaptivity.concurrent_marches: see its documentation for the conditions).
  bool check_loop_memory(LoopRow &row, const Space<2> &primal, const Space<2> &adjoint);
  /// The adjoint(s) of the loop: independent of the primal unless goal.weights = auto
  /// with one adjoint for the weighted goal. Then `weights` is valid: the last slab's
  /// operator is assembled and factorized first, and the march waits for weights (true
  /// once evaluate_goals has set the goals' weights, false if the primal failed).
  /// goal_estimate = consistent: u_q's goal values into J_hi, marched after the adjoints
  /// unless `share` is given: then the operator, once factorized, is passed through it
  /// if prepared_for(mesh) (another thread marches u_q; null otherwise, and on failure).
  AdjointMarch march_adjoints(unsigned int loop, const Space<2> &adjoint,
                              const std::vector<GoalSpec> &goal_specs,
                              const MarchOptions &opt, bool concurrent,
                              std::shared_future<bool> weights = {},
                              std::promise<SharedOperator> *share = nullptr) const;
  /// J_i(u_tau h), the weights (auto: from the patch lift) and the weighted J (not yet
  /// for goal.weights = estimate).
  void evaluate_goals(LoopRow &row, const Space<2> &primal,
                      const std::vector<Vector<double>> &U);
  /// The weights of the goals into row, and the weighted J and J_exact.
  void weigh_goals(LoopRow &row) const;
  /// The adjoint operator's figures into row (solver choice, factor size) and its
  /// factors and matrices freed; nothing if adj.op is already empty.
  void release_adjoint(LoopRow &row, AdjointMarch &adj);
  /// Whether consistent's u_q marches by an operator of its own: where the adjoint
  /// carries a crosswind term that no solution switches (crosswind_by_cell empty:
  /// crosswind_form = linear, or the first loop of residual), which u_q leaves out
  /// (make_uq_spaces).
  bool consistent_by_own_operator() const;
  /// Whether this loop marches a u_q by an operator of its own (march_own_uq): enriched's,
  /// or consistent's by consistent_by_own_operator.
  bool own_uq_operator() const;
  /// Whether consistent's u_q marches by the adjoint's factors, untransposed.
  bool uq_by_adjoint_factors() const;
  /// The spaces of the u_q that march by operators of their own (march_own_uq):
  /// enriched's, the primal's stabilization in degree q; consistent's, the adjoint's
  /// space. Either with the loop's crosswind factor, or without the term where no
  /// solution switches it: on every cell the term is an O(h) inconsistent diffusion
  /// across b, and u_q would share the error it causes in u_h (doc/results.md, "Goal
  /// estimates from the enriched primal"). Made before a second thread starts: the two
  /// threads do not build spaces on the triangulation at once.
  std::vector<std::unique_ptr<Space<2>>> make_uq_spaces(const std::vector<double> &cw_scale) const;
  /// A u_q marched on each of `spaces` by its own operator on the loop's meshes (one
  /// after the other), their goal values appended to row.J_uq (estimate_by_goal forms
  /// the goals' estimates from them). `concurrent`: in the primal thread while the
  /// adjoints march (no Trilinos, one BLAS thread). Returns its wall time.
  double march_own_uq(LoopRow &row, const std::vector<std::unique_ptr<Space<2>>> &spaces,
                      const MarchOptions &opt, bool concurrent) const;
  /// The forward march of a primal of degree q with the given options.
  using DegreeQMarch = std::function<std::vector<Vector<double>>(const MarchOptions &)>;
  /// The goals' values (specs) of the primal of degree q on `space` that `march` gives
  /// (march_own_uq: by its own operator; consistent: by the adjoint's, untransposed); empty,
  /// with a warning, where the march fails (NumericalError).
  std::vector<double> degree_q_goal_values(const Space<2> &space, const DegreeQMarch &march,
                                           const std::vector<GoalSpec> &specs,
                                           const MarchOptions &opt) const;
  /// The indicators ind of the weighted goal from the adjoint march: one adjoint for
  /// J_w = sum_i w_i J_i, or (by_goal) one per goal and ind = sum_i w_i ind_i, with
  /// goal.weights = estimate w_i = sign(eta_i) / max(|J_i(u_h)|, 1e-12). Sets t_adjoint,
  /// t_estimate.
  void estimate_from(LoopRow &row, Indicators<2> &ind, const Space<2> &primal,
                     const Space<2> &adjoint, const std::vector<Vector<double>> &U,
                     const HigherOrderPrimal *hi, AdjointMarch adj);
  /// by_goal: see estimate_from.
  void estimate_by_goal(LoopRow &row, Indicators<2> &ind, const Space<2> &primal,
                        const Space<2> &adjoint, std::vector<std::vector<Vector<double>>> Z,
                        const std::vector<Vector<double>> &U, const HigherOrderPrimal *hi);
  /// True if the run ends after this loop (stop_reason says why).
  bool stop_after(LoopRow &row);
  /// Tables, summary and console line of a finished loop.
  void record(const LoopRow &row);
  void summary(const std::string &status, const std::string &reason, double wall_time,
               const std::string &details = "");

  const Parameters &prm;
  const std::unique_ptr<Scene<2>> scene;
  std::vector<GoalSpec> goals;
  const bool auto_weights, estimate_weights;
  /// one adjoint and one estimate per goal, the combined indicators their weighted sum
  /// (goal.weights = estimate or adaptivity.per_goal_estimates)
  const bool by_goal;
  /// adaptivity.goal_estimate = enriched or both: enriched's u_q (implies by_goal)
  const bool enriched;
  /// adaptivity.goal_estimate = consistent or both: consistent's u_q (implies by_goal)
  const bool consistent;
  /// "exact" (the scene's exact solution), "goal.reference" or "none": where J_exact,
  /// and with it the error columns and I_eff, come from
  const std::string error_reference;
  const bool has_exact; ///< error_reference != "none"
  std::vector<double> J_exact;
  MarkingOptions marking;
  /// per active cell, the cut that adaptivity.bound_refinement adds (cells_out_of_bounds)
  std::vector<unsigned char> bound_cuts;
  /// discretization.crosswind_form = residual: the crosswind factor s_K of the last
  /// loop's solution (crosswind_scale) by cell; a cell of the next mesh takes its own or
  /// its nearest ancestor's (1 where neither is known, e.g. on the first loop)
  std::map<CellId, double> crosswind_by_cell;
  std::vector<double> crosswind_scale_of_mesh() const;
  /// discretization.crosswind_first_solve: the first loop's crosswind factor from a
  /// primal march on its mesh without the term (instead of 1 on every cell).
  void first_crosswind_from_a_plain_solve();
  /// u_h at the right end of each slab, from the slabs' coefficient vectors U.
  std::vector<Vector<double>> right_traces(const std::vector<Vector<double>> &U) const;
  /// crosswind_by_cell from the crosswind factor of u_h (slab-end values `ends`) on the
  /// current mesh.
  void keep_crosswind_factor(const Space<2> &primal, const std::vector<Vector<double>> &ends);
  Triangulation<2> tria;
  TimeMesh mesh;
  const TemporalBasis basis;
  const unsigned int q;
  std::unique_ptr<CsvTable> table, probe_table;
  ProbeSpec<2> probe_spec;
  std::vector<LoopRow> rows;
  std::vector<std::pair<double, std::string>> vtu_records;
  std::string stop_reason = "max loops";
  /// solver.type = auto: the last solver kind printed per problem (primal, adjoint)
  int solver_kind_before[2] = {-1, -1}; ///< 0 coupled direct, 1 iterative, 2 modes
  void report_auto_choice(unsigned int loop, unsigned int problem, const SlabOperator<2> &op);
  /// the memory estimate: the process before the loops' data, the limit, and the last
  /// loop's measured/estimated peak (>= 1) that scales the next estimate
  double base_mb = 0;
  MemoryLimit mem_limit;
  double mem_ratio = 1.;
  Timer wall;
};
} // namespace anisodwr::dwr_loop
