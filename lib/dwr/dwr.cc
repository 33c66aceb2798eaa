#include "dwr/dwr.h"
#include "dwr/adaptive_loop.h"
#include "dwr/loop_outputs.h"
#include "study/options.h"
#include "dwr/time_error.h"

#include "space/crosswind_scale.h"

#include "base/blas_threads.h"
#include "base/errors.h"
#include "base/mpi.h"

#include <array>
#include <cmath>
#include <iostream>

namespace anisodwr
{
namespace dwr_loop
{
namespace
{
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

/// adaptivity.bound_refinement halves cells along b that are this many times longer
/// along b than across
constexpr double bound_cut_aspect = 10.;

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
} // namespace

AdaptiveLoop::AdaptiveLoop(const Parameters &prm)
    : prm(prm), scene(scene_in_directory(prm)),
      goals(make_goals(goal_input(prm), *scene)),
      auto_weights(prm.goal.weights == "auto"),
      estimate_weights(prm.goal.weights == "estimate"),
      by_goal(estimate_weights || prm.adaptivity.per_goal_estimates ||
              prm.adaptivity.tolerance_measure == ToleranceMeasure::goals ||
              prm.adaptivity.goal_estimate != GoalEstimate::dwr),
      enriched(marches_enriched_uq(prm)), consistent(marches_consistent_uq(prm)),
      error_reference(scene->exact()                      ? "exact"
                      : std::isnan(goals.front().reference) ? "none"
                                                            : "goal.reference"),
      has_exact(error_reference != "none"),
      J_exact(goals.size(), dwr_nan), marking(marking_options(prm)),
      tria(tria_smoothing<2>(marking)), basis(prm.discretization.r),
      q(prm.adaptivity.adjoint_degree ? prm.adaptivity.adjoint_degree
                                      : prm.discretization.p + 1)
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
      try
      {
        J_exact[g] = scene->exact() ? exact_goal(*scene, goals[g]) : goals[g].reference;
      }
      catch (const InputError &e)
      {
        const std::string key = prm.scene.name == "custom" ? "scene.goals" : "goal.kind";
        throw InputError(prm.source(key) + ": key '" + key + "': " + e.what());
      }
    print_run_line(std::cout, prm, *scene, q, goals, J_exact, has_exact,
                   mapping_degree(prm, tria));
    tria.refine_global(prm.discretization.initial_refinements);
    if (prm.discretization.goal_streak > 0.)
      std::cout << goal_streak_text(refine_goal_streak(tria, *scene, goals,
                                                       prm.discretization.goal_streak))
                << "\n";
    if (prm.discretization.wall_layer > 0.)
      std::cout << wall_layer_text(refine_wall_layer(tria, *scene,
                                                     prm.discretization.wall_layer))
                << "\n";
    print_loop_header(std::cout);
    base_mb = mpi_max(resident_memory_mb());
    if (first_loop_crosswind_switched(prm))
      first_crosswind_from_a_plain_solve();
    for (unsigned int loop = 1; loop <= prm.adaptivity.loops; ++loop)
    {
      LoopRow row;
      row.loop = loop;
      Indicators<2> ind;
      bool stop = false;
      if (!solve_and_estimate(row, ind, stop))
        break;
      if (!stop)
      {
        Timer t;
        const Balance refine = balance(row, prm.adaptivity);
        if (refine.space)
        {
          const MarkingStats m = mark_cells(tria, ind, marking);
          row.marking = {{m.marked, m.cut_x, m.cut_y, m.cut_both, m.closure}};
          if (!bound_cuts.empty())
            row.bound_cuts = add_cuts(tria, bound_cuts);
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

bool AdaptiveLoop::solve_and_estimate(LoopRow &row, Indicators<2> &ind, bool &stop)
{
  // (freed pages go back to the system between the phases: the next phase's
  // factorizations map fresh memory and would sit beside them; memory_estimate.h)
  release_free_memory();
  const auto primal_space = make_space(prm, *scene, tria, prm.discretization.p);
  const auto adjoint_space = make_adjoint_space(prm, *scene, tria, q, goals);
  const std::vector<double> cw_scale = crosswind_scale_of_mesh();
  primal_space->set_crosswind_scale(cw_scale);
  adjoint_space->set_crosswind_scale(cw_scale);
  const Space<2> &primal = *primal_space, &adjoint = *adjoint_space;
  if (row.loop == 1)
    check_goal_weights(primal, goals, goal_input(prm), *scene);
  if (!within_dof_budget(row, primal))
    return false;
  const bool own_uq = own_uq_operator();
  row.concurrent = check_loop_memory(row, primal, adjoint);
  MarchOptions opt;
  opt.label = "loop " + std::to_string(row.loop);
  opt.progress = false;
  opt.growth_limit = prm.discretization.growth_limit;
  std::vector<Vector<double>> U, U_hi;
  const TemporalBasis basis_hi(prm.discretization.r + 1); // time_indicator = higher_order
  // u_q by its own operator with concurrent marches: its space made now, its march
  // beside the adjoints
  std::vector<std::unique_ptr<Space<2>>> uq_spaces;
  if (own_uq && row.concurrent)
    uq_spaces = make_uq_spaces(cw_scale);
  AdjointMarch adj = march_both(row, primal, adjoint, opt, U, basis_hi, U_hi, uq_spaces);
  uq_spaces.clear();
  const HigherOrderPrimal hi{basis_hi, U_hi};
  const HigherOrderPrimal *hi_ptr = U_hi.empty() ? nullptr : &hi;
  if (!row.concurrent)
    adj = march_adjoints(row.loop, adjoint, goals, opt, false);
  if (own_uq && !row.concurrent)
  {
    // (after the adjoint's factors: the two degree-q factorizations are not held at once)
    release_adjoint(row, adj);
    row.t_estimate += march_own_uq(row, make_uq_spaces(cw_scale), opt, false);
  }
  if (uq_by_adjoint_factors())
    row.J_uq.push_back(std::move(adj.J_hi));
  estimate_from(row, ind, primal, adjoint, U, hi_ptr, std::move(adj));
  check_finite(row, ind, opt.label);
  if (prm.adaptivity.measure_time_error)
    measure_time_error(
        [&](double tau_scale)
        {
          auto space = make_space(prm, *scene, tria, prm.discretization.p, tau_scale);
          space->set_crosswind_scale(cw_scale);
          return space;
        },
        mesh, basis, slab_solver_options(prm), goals, opt, row);
  copy_indicators(ind, row);
  std::vector<double> ar_cell;
  row.ar = max_aspect_ratio(tria, primal.mapping(), &ar_cell);
  row.hanging_gap = max_hanging_gap(tria);

  Vector<double> uT;
  combine_blocks(U.back(), basis.right_trace(), uT);
  stop = stop_after(row);
  write_loop_outputs(prm, *scene, probe_spec, row, primal, uT, ind, ar_cell, stop,
                     vtu_records);
  prepare_refinement(row, primal, U);
  return true;
}

bool AdaptiveLoop::within_dof_budget(LoopRow &row, const Space<2> &primal)
{
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
  return true;
}

AdjointMarch AdaptiveLoop::march_both(LoopRow &row, const Space<2> &primal,
                                      const Space<2> &adjoint, const MarchOptions &opt,
                                      std::vector<Vector<double>> &U,
                                      const TemporalBasis &basis_hi,
                                      std::vector<Vector<double>> &U_hi,
                                      const std::vector<std::unique_ptr<Space<2>>> &uq_spaces)
{
  // The adjoint does not depend on the primal unless goal.weights = auto: with
  // concurrent marches it runs in a second thread while the primal marches (the
  // future's destructor waits for it if the primal fails). With auto weights only its
  // operator is built and factorized then; the march waits for the weights (`gate`,
  // released with false before that destructor if the primal fails). OpenBLAS runs on
  // one thread: its own threads would compete with the other march.
  const bool concurrent = row.concurrent;
  const ScopedBlasThreads blas(concurrent ? 1 : 0);
  // consistent: the adjoint's operator, once factorized, for u_q's march in this thread
  // (declared before the thread's future: it outlives the thread if the primal fails)
  std::promise<SharedOperator> share;
  std::future<SharedOperator> shared = share.get_future();
  const bool by_adjoint_factors = uq_by_adjoint_factors();
  std::promise<SharedOperator> *share_ptr = by_adjoint_factors ? &share : nullptr;
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
        std::launch::async,
        [this, &adjoint, &opt, specs = goals, loop = row.loop, weights, share_ptr]()
        { return march_adjoints(loop, adjoint, specs, opt, true, weights, share_ptr); });
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
  evaluate_goals(row, primal, U);
  gate.release(true);
  if (concurrent && !uq_spaces.empty())
    march_own_uq(row, uq_spaces, opt, true); // (beside the adjoints)
  std::vector<double> J_hi;
  SharedOperator adjoint_op = concurrent && by_adjoint_factors ? shared.get() : nullptr;
  if (adjoint_op) // (beside the adjoints' solves, which only read the factors too)
    J_hi = degree_q_goal_values(
        adjoint,
        [&](const MarchOptions &o)
        { return march_primal_prepared(adjoint, mesh, basis, *adjoint_op, o); },
        goals, opt);
  row.t_primal = t.wall_time();
  if (!concurrent)
    return AdjointMarch();
  AdjointMarch adj = adjoint_thread.get();
  if (adjoint_op)
    adj.J_hi = std::move(J_hi);
  return adj;
}

void AdaptiveLoop::check_finite(const LoopRow &row, const Indicators<2> &ind,
                                const std::string &label) const
{
  for (double e : ind.eta_tau_slab)
    if (!std::isfinite(e))
      throw NumericalError(label + ": the time indicator is NaN/Inf");
  // (an overflow in the data, e.g. f = 1e308 x, leaves u_h finite and eta_h not)
  for (const auto &e : ind.eta_h_cell)
    if (!std::isfinite(e[0]) || !std::isfinite(e[1]))
      throw NumericalError(label + ": the space indicator eta_h is NaN/Inf (an "
                                   "overflow in the data or the solution?)");
  for (const double J : row.J_goal)
    if (!std::isfinite(J))
      throw NumericalError(label + ": a goal value J(u_h) is NaN/Inf");
}

void AdaptiveLoop::prepare_refinement(const LoopRow &row, const Space<2> &primal,
                                      const std::vector<Vector<double>> &U)
{
  // u_h at the slab ends, formed once for the crosswind factor and the bound refinement
  std::vector<Vector<double>> ends;
  const auto slab_ends = [&]() -> const std::vector<Vector<double>> &
  {
    if (ends.empty())
      ends = right_traces(U);
    return ends;
  };
  if (residual_crosswind(prm))
    keep_crosswind_factor(primal, slab_ends());
  bound_cuts.clear();
  const double bound_fraction = prm.adaptivity.bound_refinement;
  if (bound_fraction <= 0)
    return;
  double u_min = dwr_nan, u_max = dwr_nan;
  for (const auto &p : row.probes)
  {
    if (p.first == "u_min")
      u_min = p.second;
    if (p.first == "u_max")
      u_max = p.second;
  }
  if (std::isfinite(u_min) && std::isfinite(u_max))
    bound_cuts = cells_out_of_bounds<2>(
        primal.dof_handler(), slab_ends(), u_min, u_max, bound_fraction * (u_max - u_min),
        bound_cut_aspect, [this](const Point<2> &x) { return scene->convection(x, 0.); });
}

void AdaptiveLoop::first_crosswind_from_a_plain_solve()
{
  // s_K = 1 on the first loop smears u_h, and the factor of that smooth solution is small
  // where the next loop then oscillates (doc/history.md, "Hemker: the goals' streaks and
  // the adjoint's crosswind term"); SUPG alone shows where the term is needed
  const auto space = make_space(prm, *scene, tria, prm.discretization.p);
  space->set_crosswind_scale(std::vector<double>(tria.n_active_cells(), 0.));
  MarchOptions opt;
  opt.label = "loop 1 (the crosswind factor's march without the term)";
  opt.progress = false;
  opt.growth_limit = prm.discretization.growth_limit;
  std::vector<Vector<double>> U;
  {
    SlabOperator<2> op(*space, basis, march_solver_options(1, "primal", false));
    U = march_primal(*space, mesh, basis, op, opt);
  }
  keep_crosswind_factor(*space, right_traces(U));
  release_free_memory();
}

std::vector<Vector<double>> AdaptiveLoop::right_traces(const std::vector<Vector<double>> &U) const
{
  std::vector<Vector<double>> ends(U.size());
  for (std::size_t n = 0; n < U.size(); ++n)
    combine_blocks(U[n], basis.right_trace(), ends[n]);
  return ends;
}

void AdaptiveLoop::keep_crosswind_factor(const Space<2> &primal,
                                         const std::vector<Vector<double>> &ends)
{
  const std::vector<double> s =
      crosswind_scale(primal, mesh.t, ends, prm.discretization.crosswind_exponent);
  crosswind_by_cell.clear();
  for (const auto &cell : tria.active_cell_iterators())
    crosswind_by_cell[cell->id()] = s[cell->active_cell_index()];
}

std::vector<double> AdaptiveLoop::crosswind_scale_of_mesh() const
{
  if (crosswind_by_cell.empty())
    return {};
  std::vector<double> scale(tria.n_active_cells(), 1.);
  for (const auto &cell : tria.active_cell_iterators())
    for (auto c = Triangulation<2>::cell_iterator(cell);; c = c->parent())
    {
      const auto it = crosswind_by_cell.find(c->id());
      if (it != crosswind_by_cell.end())
      {
        scale[cell->active_cell_index()] = it->second;
        break;
      }
      if (c->level() == 0)
        break;
    }
  return scale;
}

bool AdaptiveLoop::stop_after(LoopRow &row)
{
  if (!rows.empty())
    row.eta_drift = corrected_drift(rows.back(), row);
  if (row.loop == prm.adaptivity.loops)
    return true;
  const auto &a = prm.adaptivity;
  const double estimate = a.tolerance_measure == ToleranceMeasure::parts ? row.eta_parts_abs()
                          : a.tolerance_measure == ToleranceMeasure::goals
                              ? row.eta_goals_max()
                              : std::abs(row.eta_h_total + row.eta_tau);
  if (a.tolerance > 0 && estimate < a.tolerance)
  {
    // loop 1 has nothing to compare with; a NaN drift after it (weights that changed
    // without estimates per goal: the weighted goals differ) is not checked
    const bool settled = a.tolerance_drift <= 0 ||
                         (!rows.empty() && !(row.eta_drift > a.tolerance_drift * a.tolerance));
    if (settled)
    {
      stop_reason = "tolerance";
      return true;
    }
    if (writes_output())
    {
      std::cout << "loop " << row.loop << ": estimate " << estimate
                << " is below adaptivity.tolerance " << a.tolerance << ", but ";
      if (rows.empty())
        std::cout << "the stop compares the corrected goal values with a previous loop";
      else
        std::cout << "the corrected goal values moved by " << row.eta_drift;
      std::cout << " (adaptivity.tolerance_drift): refining on" << std::endl;
    }
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
} // namespace dwr_loop

void run_dwr(const Parameters &prm)
{
  dwr_loop::AdaptiveLoop(prm).run();
}
} // namespace anisodwr
