#include "study/dwr.h"
#include "study/memory_estimate.h"
#include "study/options.h"
#include "study/loop_outputs.h"
#include "study/probes.h"
#include "study/time_error.h"

#include "adaptivity/estimator.h"
#include "adaptivity/lifted_goal.h"
#include "adaptivity/refinement.h"
#include "base/blas_threads.h"
#include "base/errors.h"
#include "base/mpi.h"
#include "goal/goal.h"
#include "io/loop_report.h"
#include "io/table.h"
#include "slab/adjoint_march.h"
#include "slab/primal_march.h"

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/timer.h>
#include <deal.II/grid/tria.h>

#include <array>
#include <cmath>
#include <future>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
constexpr double dwr_nan = std::numeric_limits<double>::quiet_NaN();

/// The adjoint march of a loop: its slab operator, the adjoint slab solutions (one set
/// per goal with goal.weights = estimate or per_goal_estimates, else one for the
/// weighted goal) and its wall time.
struct AdjointMarch
{
  std::unique_ptr<SlabOperator<2>> op;
  std::vector<std::vector<Vector<double>>> Z;
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
  /// The loop's solves, goal values and indicators on the current meshes (ind), and its
  /// outputs (probes, cut lines, VTU). False if the DoF budget stops the run first.
  bool solve_and_estimate(LoopRow &row, Indicators<2> &ind);
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
  AdjointMarch march_adjoints(unsigned int loop, const Space<2> &adjoint,
                              const std::vector<GoalSpec> &goal_specs,
                              const MarchOptions &opt, bool concurrent,
                              std::shared_future<bool> weights = {}) const;
  /// J_i(u_tau h), the weights (auto: from the patch lift) and the weighted J (not yet
  /// for goal.weights = estimate).
  void evaluate_goals(LoopRow &row, const Space<2> &primal,
                      const std::vector<Vector<double>> &U);
  /// The weights of the goals into row, and the weighted J and J_exact.
  void weigh_goals(LoopRow &row) const;
  /// The indicators ind of the weighted goal from the adjoint march: one adjoint for
  /// J_w = sum_i w_i J_i, or (by_goal) one per goal and ind = sum_i w_i ind_i, with
  /// goal.weights = estimate w_i = sign(eta_i) / max(|J_i(u_h)|, 1e-12). Sets t_adjoint,
  /// t_estimate.
  void estimate_from(LoopRow &row, Indicators<2> &ind, const Space<2> &primal,
                     const Space<2> &adjoint, const std::vector<Vector<double>> &U,
                     const HigherOrderPrimal *hi, AdjointMarch adj);
  /// The indicators of one goal alone (weight 1) from its adjoint Z.
  Indicators<2> goal_estimate(const Space<2> &primal, const Space<2> &adjoint,
                              const std::vector<Vector<double>> &U,
                              const std::vector<Vector<double>> &Z, const GoalSpec &goal,
                              const HigherOrderPrimal *hi) const;
  /// by_goal: see estimate_from.
  void estimate_by_goal(LoopRow &row, Indicators<2> &ind, const Space<2> &primal,
                        const Space<2> &adjoint, std::vector<std::vector<Vector<double>>> Z,
                        const std::vector<Vector<double>> &U, const HigherOrderPrimal *hi);
  /// True if the run ends after this loop (stop_reason says why).
  bool stop_after(const LoopRow &row);
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
  /// "exact" (the scene's exact solution), "goal.reference" or "none": where J_exact,
  /// and with it the error columns and I_eff, come from
  const std::string error_reference;
  const bool has_exact; ///< error_reference != "none"
  std::vector<double> J_exact;
  MarkingOptions marking;
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

/// What a loop refines (adaptivity.time_balance): the slabs where the temporal share of
/// the estimate is not small against the spatial one, |eta_tau| >= b (|eta_h,x| +
/// |eta_h,y|), and the cells where the spatial share is not small against the temporal
/// one, |eta_h,x| + |eta_h,y| >= b |eta_tau| (or where no slab is bisected: theta_tau =
/// 0). The shares are those of eta_abs (per goal, weighted by |w_i|, where each goal has
/// its own estimate). b = 0: both in every loop; every loop refines one or both.
struct Balance
{
  bool space, time;
};

Balance balance(const LoopRow &row, const AdaptivitySection &a)
{
  const double space = row.eta_space_abs(), time = row.eta_time_abs();
  const bool time_refined = a.theta_tau > 0 && time >= a.time_balance * space;
  return {!time_refined || space >= a.time_balance * time, time_refined};
}

/// The scene of the run, with the output directory created first.
std::unique_ptr<Scene<2>> scene_in_directory(const Parameters &prm)
{
  make_directory(prm.output.directory);
  return create_scene<2>(prm);
}

AdaptiveLoop::AdaptiveLoop(const Parameters &prm)
    : prm(prm), scene(scene_in_directory(prm)),
      goals(make_goals(goal_input(prm), *scene)),
      auto_weights(prm.goal.weights == "auto"),
      estimate_weights(prm.goal.weights == "estimate"),
      by_goal(estimate_weights || prm.adaptivity.per_goal_estimates),
      error_reference(scene->exact()                      ? "exact"
                      : std::isnan(goals.front().reference) ? "none"
                                                            : "goal.reference"),
      has_exact(error_reference != "none"),
      J_exact(goals.size(), dwr_nan), marking(marking_options(prm)),
      tria(tria_smoothing<2>(marking)), basis(prm.discretization.r),
      q(prm.adaptivity.adjoint_degree ? prm.adaptivity.adjoint_degree
                                      : 2 * prm.discretization.p)
{
  scene->make_coarse_grid(tria);
  mesh = TimeMesh::uniform(scene->end_time, prm.discretization.n_slabs);
  table = std::make_unique<CsvTable>(prm.output.directory + "/loops.csv",
                                     loop_columns(goal_names(goals)));
  probe_table = std::make_unique<CsvTable>(prm.output.directory + "/probes.csv",
                                           probe_columns(goals));
  probe_spec = scene->probes();
  mem_limit = memory_limit(prm);
  wall.restart();
}

void AdaptiveLoop::run()
{
  summary("running", "", 0.);
  for (const std::string &w : dwr_warnings(prm))
    std::cerr << "anisodwr: warning: " << w << std::endl;
  try
  {
    // the initial mesh unless its predicted memory exceeds the limit (checked first:
    // the exact goal values take up to a second each)
    check_initial_mesh_memory(prm, *scene, tria.n_active_cells(), q, goals.size(),
                              mem_limit);
    for (std::size_t g = 0; g < goals.size(); ++g)
      J_exact[g] = scene->exact() ? exact_goal(*scene, goals[g]) : goals[g].reference;
    print_run_line(std::cout, prm, *scene, q, goals, J_exact, has_exact);
    print_loop_header(std::cout);
    tria.refine_global(prm.discretization.initial_refinements);
    base_mb = mpi_max(resident_memory_mb());
    for (unsigned int loop = 1; loop <= prm.adaptivity.loops; ++loop)
    {
      LoopRow row;
      row.loop = loop;
      Indicators<2> ind;
      if (!solve_and_estimate(row, ind))
        break;
      const bool stop = stop_after(row);
      if (!stop)
      {
        Timer t;
        const Balance refine = balance(row, prm.adaptivity);
        if (refine.space)
        {
          const MarkingStats m = mark_cells(tria, ind, marking);
          row.marking = {{m.marked, m.cut_x, m.cut_y, m.cut_both, m.closure}};
          tria.execute_coarsening_and_refinement();
        }
        if (refine.time)
          mesh = refine_time(mesh, ind.eta_tau_slab, prm.adaptivity.theta_tau);
        row.t_refine = t.wall_time();
      }
      row.mem = mpi_max(peak_memory_mb()); // the same decisions on every rank
      mem_ratio = std::max(1., row.mem / row.mem_estimate);
      record(row);
      if (stop)
        break;
    }
  }
  catch (const ResourceLimitError &e)
  {
    // not started: the finished loops stay, the reason is the message
    summary("stopped", e.what(), wall.wall_time());
    throw;
  }
  catch (const std::exception &e)
  {
    summary("failed: " + failure_message(e), "error", wall.wall_time(),
            failure_details(e));
    throw;
  }
  summary("ok", stop_reason, wall.wall_time());
  std::cout << "tables: " << table->path() << ", " << prm.output.directory << "/loops.tex"
            << " (stopped: " << stop_reason << ")\n";
}

bool AdaptiveLoop::solve_and_estimate(LoopRow &row, Indicators<2> &ind)
{
  // (freed pages go back to the system between the phases: the next phase's
  // factorizations map fresh memory and would sit beside them; memory_estimate.h)
  release_free_memory();
  const auto primal_space = make_space(prm, *scene, tria, prm.discretization.p);
  const auto adjoint_space = make_adjoint_space(prm, *scene, tria, q);
  const Space<2> &primal = *primal_space, &adjoint = *adjoint_space;
  if (row.loop == 1)
    check_goal_weights(primal, goals, goal_input(prm), *scene);
  row.n_space = primal.n_dofs();
  row.n_t = mesh.n_slabs();
  row.n_tot = row.n_space * row.n_t * basis.n_dofs();
  if (prm.adaptivity.max_dofs > 0 && row.n_tot > prm.adaptivity.max_dofs)
  {
    stop_reason = "DoF budget: loop " + std::to_string(row.loop) +
                  " would have N_tot = " + std::to_string(std::size_t(row.n_tot)) +
                  " > adaptivity.max_dofs";
    return false;
  }
  const bool concurrent = check_loop_memory(row, primal, adjoint);
  row.concurrent = concurrent;
  MarchOptions opt;
  opt.label = "loop " + std::to_string(row.loop);
  opt.progress = false;
  opt.growth_limit = prm.discretization.growth_limit;
  std::vector<Vector<double>> U, U_hi;
  const TemporalBasis basis_hi(prm.discretization.r + 1); // time_indicator = higher_order
  AdjointMarch adj;
  {
    // The adjoint does not depend on the primal unless goal.weights = auto: with
    // concurrent marches it runs in a second thread while the primal marches (the
    // future's destructor waits for it if the primal fails). With auto weights only its
    // operator is built and factorized then; the march waits for the weights (`gate`,
    // released with false before that destructor if the primal fails). OpenBLAS runs on
    // one thread: its own threads would compete with the other march.
    const ScopedBlasThreads blas(concurrent ? 1 : 0);
    std::future<AdjointMarch> adjoint_thread;
    struct Gate
    {
      std::promise<bool> promise;
      bool open = false;
      void release(bool ok)
      {
        if (!open)
          promise.set_value(ok);
        open = true;
      }
      ~Gate() { release(false); }
    } gate;
    const std::shared_future<bool> weights =
        auto_weights && !by_goal ? gate.promise.get_future().share() : std::shared_future<bool>();
    if (concurrent)
      adjoint_thread = std::async(
          std::launch::async, [this, &adjoint, &opt, specs = goals, loop = row.loop, weights]()
          { return march_adjoints(loop, adjoint, specs, opt, true, weights); });
    Timer t;
    {
      // (one after the other: the primal's factors are freed before the adjoint factorizes)
      SlabOperator<2> op(primal, basis, march_solver_options(row.loop, "primal", concurrent));
      U = march_primal(primal, mesh, basis, op, opt);
      report_auto_choice(row.loop, 0, op);
      row.lu_primal_mb = op.timings().factor_mb;
    }
    release_free_memory();
    if (prm.adaptivity.time_indicator == TimeIndicator::higher_order)
    {
      SlabOperator<2> op(primal, basis_hi, march_solver_options(0, "", concurrent));
      U_hi = march_primal(primal, mesh, basis_hi, op, opt);
    }
    release_free_memory();
    row.t_primal = t.wall_time();
    evaluate_goals(row, primal, U);
    gate.release(true);
    if (concurrent)
      adj = adjoint_thread.get();
  }
  const HigherOrderPrimal hi{basis_hi, U_hi};
  const HigherOrderPrimal *hi_ptr = U_hi.empty() ? nullptr : &hi;

  if (!concurrent)
    adj = march_adjoints(row.loop, adjoint, goals, opt, false);
  estimate_from(row, ind, primal, adjoint, U, hi_ptr, std::move(adj));
  for (double e : ind.eta_tau_slab)
    if (!std::isfinite(e))
      throw NumericalError(opt.label + ": the time indicator is NaN/Inf");
  if (prm.adaptivity.measure_time_error)
    measure_time_error(
        [&](double tau_scale)
        { return make_space(prm, *scene, tria, prm.discretization.p, tau_scale); },
        mesh, basis, slab_solver_options(prm), goals, opt, row);
  copy_indicators(ind, row);
  std::vector<double> ar_cell;
  row.ar = max_aspect_ratio(tria, primal.mapping(), &ar_cell);
  row.hanging_gap = max_hanging_gap(tria);

  Vector<double> uT;
  combine_blocks(U.back(), basis.right_trace(), uT);
  write_loop_outputs(prm, *scene, probe_spec, row, primal, uT, ind, ar_cell, vtu_records);
  return true;
}

SlabSolverOptions AdaptiveLoop::march_solver_options(unsigned int loop,
                                                     const std::string &problem,
                                                     bool concurrent) const
{
  SlabSolverOptions o = slab_solver_options(prm);
  if (concurrent)
  {
    // no Krylov solves in two threads: auto stays with a direct solver (modes or the
    // coupled UMFPACK)
    o.direct_only = true;
    if (o.type == SolverType::iterative)
      o.type = SolverType::direct;
  }
  if (loop > 0 && loop == prm.output.dump_slab_loop)
  {
    std::ostringstream name;
    name << prm.output.directory << "/slab-" << problem << "-loop-" << std::setw(4)
         << std::setfill('0') << loop << ".mtx";
    o.dump_matrix = name.str();
  }
  return o;
}

AdjointMarch AdaptiveLoop::march_adjoints(unsigned int loop, const Space<2> &adjoint,
                                          const std::vector<GoalSpec> &goal_specs,
                                          const MarchOptions &opt, bool concurrent,
                                          std::shared_future<bool> weights) const
{
  // One adjoint per goal: all adjoints first (one factorization serves them), then the
  // estimates without the adjoint's factors in memory
  Timer t;
  AdjointMarch a;
  a.op = std::make_unique<SlabOperator<2>>(adjoint, basis,
                                           march_solver_options(loop, "adjoint", concurrent));
  double waited = 0;
  if (weights.valid())
  {
    const unsigned int last = mesh.n_slabs() - 1;
    guarded_slab_solve(
        opt, "adjoint", last, mesh, [&]() { a.op->prepare(mesh.start(last), mesh.tau(last)); },
        Vector<double>());
    Timer w;
    if (!weights.get())
      return a;
    waited = w.wall_time();
  }
  // (with weights: the goals' weights as evaluate_goals set them)
  const std::vector<GoalSpec> &specs = weights.valid() ? goals : goal_specs;
  if (by_goal)
  {
    // each goal alone (weight 1), their solves side by side
    std::vector<GoalVectors> unit;
    for (const auto &goal : specs)
      unit.push_back(assemble_goal_vectors(adjoint, {unweighted(goal)}));
    a.Z = anisodwr::march_adjoints(adjoint, mesh, basis, *a.op, unit, opt);
  }
  else
    a.Z.push_back(
        march_adjoint(adjoint, mesh, basis, *a.op, assemble_goal_vectors(adjoint, specs), opt));
  a.wall = t.wall_time() - waited;
  return a;
}

void AdaptiveLoop::estimate_from(LoopRow &row, Indicators<2> &ind, const Space<2> &primal,
                                 const Space<2> &adjoint,
                                 const std::vector<Vector<double>> &U,
                                 const HigherOrderPrimal *hi, AdjointMarch adj)
{
  row.t_adjoint = adj.wall;
  report_auto_choice(row.loop, 1, *adj.op);
  row.lu_adjoint_mb = adj.op->timings().factor_mb;
  // The estimator solves no slab system: the adjoint's factors and matrices go before
  // it runs.
  adj.op.reset();
  release_free_memory();
  if (by_goal)
  {
    estimate_by_goal(row, ind, primal, adjoint, std::move(adj.Z), U, hi);
    return;
  }
  Timer t;
  ind = estimate(primal, adjoint, mesh, basis, U, adj.Z[0], goals,
                 prm.adaptivity.time_indicator, hi, prm.adaptivity.space_indicator);
  row.t_estimate = t.wall_time();
}

void AdaptiveLoop::estimate_by_goal(LoopRow &row, Indicators<2> &ind,
                                    const Space<2> &primal, const Space<2> &adjoint,
                                    std::vector<std::vector<Vector<double>>> Z,
                                    const std::vector<Vector<double>> &U,
                                    const HigherOrderPrimal *hi)
{
  Timer t;
  ind = Indicators<2>();
  for (std::size_t i = 0; i < goals.size(); ++i)
  {
    const auto part = goal_estimate(primal, adjoint, U, Z[i], goals[i], hi);
    Z[i] = {};
    add_goal_estimate(row, part);
    if (estimate_weights)
      goals[i].weight = signed_goal_weight(row.eta_goal[i], row.J_goal[i]);
    add_scaled(ind, goals[i].weight, part);
  }
  if (estimate_weights)
    weigh_goals(row);
  row.t_estimate = t.wall_time();
}

Indicators<2> AdaptiveLoop::goal_estimate(const Space<2> &primal, const Space<2> &adjoint,
                                          const std::vector<Vector<double>> &U,
                                          const std::vector<Vector<double>> &Z,
                                          const GoalSpec &goal,
                                          const HigherOrderPrimal *hi) const
{
  return estimate(primal, adjoint, mesh, basis, U, Z, {unweighted(goal)},
                  prm.adaptivity.time_indicator, hi, prm.adaptivity.space_indicator);
}

void AdaptiveLoop::report_auto_choice(unsigned int loop, unsigned int problem,
                                      const SlabOperator<2> &op)
{
  // printed when the solver changes, so that the table stays readable
  const int kind = op.iterative() ? 1 : op.modes() ? 2 : 0;
  if (op.auto_choice().empty() || kind == solver_kind_before[problem])
    return;
  solver_kind_before[problem] = kind;
  std::cout << "  loop " << loop << (problem ? " adjoint" : " primal")
            << ", solver.type = auto: " << op.auto_choice() << "\n";
}

bool AdaptiveLoop::check_loop_memory(LoopRow &row, const Space<2> &primal,
                                     const Space<2> &adjoint)
{
  MemoryModel model = memory_model(prm, primal, &adjoint, row.n_t, base_mb,
                                   static_cast<unsigned int>(goals.size()));
  const SlabSolverOptions options = slab_solver_options(prm);
  const bool higher_order = prm.adaptivity.time_indicator == TimeIndicator::higher_order;
  model.concurrent =
      prm.adaptivity.concurrent_marches &&
      mpi_ranks() == 1 &&
      MultithreadInfo::n_threads() > 1 && options.direct_solver == DirectEngine::umfpack &&
      !model.primal.iterative && !model.adjoint.iterative &&
      !(higher_order && solves_iteratively(options, primal.n_dofs(), prm.discretization.r + 2,
                                           primal.degree(),
                                           options.reuse_factorization &&
                                               !model.time_dependent));
  row.mem_estimate = estimate_memory(model).total_mb;
  if (model.concurrent && row.mem_estimate * mem_ratio > mem_limit.mb)
  {
    // both factorizations at once do not fit: one after the other
    model.concurrent = false;
    row.mem_estimate = estimate_memory(model).total_mb;
  }
  check_memory(
      "loop " + std::to_string(row.loop), row.mem_estimate * mem_ratio, mem_limit, model,
      mem_ratio > 1. ? " (the model's " + json_number(std::round(row.mem_estimate), 10) +
                           " MB times " + json_number(mem_ratio, 3) + ", loop " +
                           std::to_string(row.loop - 1) + "'s measured/estimated peak)"
                     : "");
  return model.concurrent;
}

void AdaptiveLoop::evaluate_goals(LoopRow &row, const Space<2> &primal,
                                  const std::vector<Vector<double>> &U)
{
  for (std::size_t g = 0; g < goals.size(); ++g)
  {
    row.J_goal.push_back(goal_value(primal, goals[g], mesh, basis, U));
    row.J_goal_exact.push_back(J_exact[g]);
    if (auto_weights)
    {
      const double d = lift_difference(primal, goals[g], mesh, basis, U);
      row.lift_difference.push_back(d);
      goals[g].weight = signed_goal_weight(d, row.J_goal[g], auto_weight_unseen);
    }
  }
  if (!estimate_weights)
    weigh_goals(row);
}

void AdaptiveLoop::weigh_goals(LoopRow &row) const
{
  row.weights.clear();
  row.J = 0;
  for (std::size_t g = 0; g < goals.size(); ++g)
  {
    row.weights.push_back(goals[g].weight);
    row.J += goals[g].weight * row.J_goal[g];
    if (has_exact)
      row.J_exact = (g ? row.J_exact : 0.) + goals[g].weight * J_exact[g];
  }
}

bool AdaptiveLoop::stop_after(const LoopRow &row)
{
  if (row.loop == prm.adaptivity.loops)
    return true;
  const double estimate = prm.adaptivity.tolerance_measure == ToleranceMeasure::parts
                             ? row.eta_parts_abs()
                             : std::abs(row.eta_h_total + row.eta_tau);
  if (prm.adaptivity.tolerance > 0 && estimate < prm.adaptivity.tolerance)
  {
    stop_reason = "tolerance";
    return true;
  }
  if (prm.adaptivity.max_wall_time > 0 &&
      mpi_max(wall.wall_time() + 2. * (row.t_primal + row.t_adjoint + row.t_estimate)) >
          prm.adaptivity.max_wall_time)
  {
    stop_reason = "wall-time budget";
    return true;
  }
  return false;
}

void AdaptiveLoop::record(const LoopRow &row)
{
  rows.push_back(row);
  table->add_row(row.all_values());
  {
    std::vector<double> v{double(row.loop), row.n_space, row.n_tot};
    v.insert(v.end(), row.J_goal.begin(), row.J_goal.end());
    for (const auto &field : row.probes)
      v.push_back(field.second);
    probe_table->add_row(v);
  }
  write_loops_latex(prm.output.directory + "/loops.tex", rows);
  summary("running", "", wall.wall_time());
  print_loop_row(std::cout, row);
}

void AdaptiveLoop::summary(const std::string &status, const std::string &reason,
                           double wall_time, const std::string &details)
{
  write_summary(prm.output.directory + "/summary.json",
                {prm.to_json(2), goal_names(goals), solver_totals_json(), error_reference,
                 reference_uncertainties(goals)},
                rows, status, reason, wall_time, details);
}
} // namespace

void run_dwr(const Parameters &prm)
{
  AdaptiveLoop(prm).run();
}
} // namespace anisodwr
