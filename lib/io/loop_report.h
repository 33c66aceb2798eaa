#pragma once
// The report of the adaptive DWR loop, one row per loop: the tables loops.csv and
// loops.tex, summary.json and the console table.
#include <array>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace anisodwr
{
/// One loop of the adaptive DWR loop: sizes, goal values, estimates, times, memory.
struct LoopRow
{
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();

  unsigned int loop = 0, n_t = 0;
  double n_space = 0, n_tot = 0;
  double J = 0, J_exact = nan, eta_h_total = 0, eta_tau = 0, ar = 1;
  std::array<double, 2> eta_h{};
  std::vector<double> J_goal, J_goal_exact;
  std::vector<double> weights;
  /// goal.weights = auto: J_i(I_2h u) - J_i(u_h) per goal, whose sign gave the weight
  /// (0 up to rounding: the lift does not see the goal; empty otherwise)
  std::vector<double> lift_difference;
  double t_primal = 0, t_adjoint = 0, t_estimate = 0, t_refine = 0, mem = 0;
  double eta_tau_rho = 0, eta_tau_rhostar = 0;
  /// the parts of eta_h summed over directions (1/2 rho(u)(z - R_i z), the adjoint half,
  /// S(u)(R_h z)) and the (cell, direction) pairs without a lift
  double eta_h_rho = 0, eta_h_rhostar = 0, eta_h_supg = 0, no_lift = 0;
  double eta_h_split_rest = 0; ///< Indicators::eta_h_split_rest
  double eta_h_data = 0;       ///< Indicators::eta_h_data
  double eta_h_quad = 0;       ///< Indicators::eta_h_quad
  /// max_hanging_gap of the loop's mesh (adaptivity/refinement.h)
  double hanging_gap = 0;
  /// adaptivity.measure_time_error: J_w(u_h) - J_w(u_tau h) on this spatial mesh,
  /// extrapolated from the time mesh bisected once and twice (NaN when not measured)
  double err_tau = nan, err_tau_order = nan;
  /// the same per goal, unweighted (NaN where it does not contract)
  std::vector<double> err_tau_goal;
  /// memory estimate of the loop (MB), made before it started (study/memory_estimate.h)
  double mem_estimate = nan;
  /// UMFPACK's factor size (MB) of the primal and the adjoint slab matrix (0: solved
  /// iteratively; the largest if several factorizations)
  double lu_primal_mb = 0, lu_adjoint_mb = 0;
  /// 1 if the primal and the adjoint marched concurrently (adaptivity.concurrent_marches)
  double concurrent = 0;
  /// adaptivity.per_goal_estimates: eta_tau h of each goal from its own adjoint
  std::vector<double> eta_goal;
  /// the same goals' parts eta_h,x, eta_h,y, eta_tau (signed), so that cancellation
  /// between them is visible per goal
  std::vector<std::array<double, 3>> eta_goal_parts;
  /// adaptivity.goal_estimate other than dwr: J_i of the primal marched in the
  /// adjoint's degree q (empty otherwise); eta_goal's spatial part is J_goal_hi - J_goal
  std::vector<double> J_goal_hi;
  /// The goal values of each u_q marched (goal_estimate = both: enriched's and
  /// consistent's; one otherwise; an entry empty where its march failed). pick_goal_hi
  /// forms J_goal_hi from them.
  std::vector<std::vector<double>> J_uq;
  /// the cells of the refinement that follows this loop (zeros on the last): marked,
  /// cut in x only, in y only, in both, flagged or extended by the closure
  std::array<unsigned int, 5> marking{};
  /// cells whose refinement flag adaptivity.bound_refinement set or extended
  unsigned int bound_cuts = 0;
  /// |sum_i w_i ((J_i + eta_i) - (J_i + eta_i) of the previous loop)|, the corrected goal
  /// values' change since the previous loop (corrected_drift; NaN on loop 1 and where
  /// the two loops' weighted goals differ)
  double eta_drift = nan;
  /// the probes by name (the columns of probes.csv) and the bounds they used
  std::vector<std::pair<std::string, double>> probes;
  std::string bounds; ///< where the probes' bounds come from (ProbeResult::bounds)
  double J_error() const { return std::abs(J_exact - J); }
  double I_eff() const { return std::abs((eta_h_total + eta_tau) / (J_exact - J)); }
  /// |eta_h,x| + |eta_h,y| + |eta_tau| without signs: per goal, weighted by |w_i|, when
  /// every goal has its own parts (eta_goal_parts), else of the weighted goal. Never
  /// below |eta_tau h| (eta_tau h = sum_i w_i eta_i); loops.csv column eta_abs.
  double eta_parts_abs() const;
  /// The spatial and the temporal share of eta_parts_abs(): |eta_h,x| + |eta_h,y| and
  /// |eta_tau|, per goal weighted by |w_i| when every goal has its own parts; with
  /// J_goal_hi (adaptivity.goal_estimate other than dwr) the spatial share is
  /// sum_i |w_i (J_goal_hi_i - J_goal_i)|.
  double eta_space_abs() const;
  /// max_i |w_i eta_i| over the goals' own estimates (eta_goal), or |eta_tau h| of the
  /// weighted goal where the goals have none; adaptivity.tolerance_measure = goals.
  double eta_goals_max() const;
  double eta_time_abs() const;
  /// J_goal_hi_i: of the u_q in J_uq with a value per goal, the one farthest from
  /// J_goal_i (goal_estimate = both: each goal's estimate the larger in size); empty if
  /// none has one.
  void pick_goal_hi();
  /// The first 18 columns of loop_columns.
  std::vector<double> values() const;
  /// values() followed by the columns loop_columns adds for the goals
  std::vector<double> all_values() const;
};

/// How far the corrected goal values J_i(u_h) + eta_i moved from `previous` to `row`:
/// sum_i |w_i| |(J_i + eta_i)(row) - (J_i + eta_i)(previous)| with row's weights where
/// both rows have an estimate per goal, else |(J + eta_tau h)(row) - (J + eta_tau
/// h)(previous)| of the weighted goal if the weights did not change; NaN otherwise (the
/// weighted goals of two loops are not the same quantity: the stop does not check it). Exact estimates give 0: the
/// drift is the change of the estimates' misses, e - eta, between the loops.
double corrected_drift(const LoopRow &previous, const LoopRow &row);

/// The columns of loops.csv (and of each loop in summary.json) for the goals named.
std::vector<std::string> loop_columns(const std::vector<std::string> &goal_names);

/// loops.tex: the main columns of all rows as a LaTeX tabular.
void write_loops_latex(const std::string &path, const std::vector<LoopRow> &rows);

/// What summary.json says besides the rows: the configuration (JSON), the goal names and
/// the solver totals (JSON members).
struct SummaryContext
{
  std::string config_json;
  std::vector<std::string> goal_names;
  std::string solver_json;
  /// where J_exact and the error columns come from: "exact", "goal.reference" or
  /// "none"; with "goal.reference" the uncertainty of each goal's reference value
  std::string error_reference = "none";
  std::vector<double> reference_uncertainty = {};
};

/// The text of summary.json.
std::string summary_json(const SummaryContext &context, const std::vector<LoopRow> &rows,
                         const std::string &status, const std::string &stop_reason,
                         double wall, const std::string &details);

/// Writes summary.json (path) atomically and prepares the one a SIGINT/SIGTERM leaves:
/// the same rows with status "interrupted".
void write_summary(const std::string &path, const SummaryContext &context,
                   const std::vector<LoopRow> &rows, const std::string &status,
                   const std::string &stop_reason, double wall,
                   const std::string &details = "");

/// The console table: its header, and one line per loop.
void print_loop_header(std::ostream &out);
void print_loop_row(std::ostream &out, const LoopRow &row);
} // namespace anisodwr
