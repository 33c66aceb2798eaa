#include "dwr/adaptive_loop.h"
#include "dwr/loop_outputs.h"
#include "study/options.h"
#include "dwr/time_error.h"

#include "adaptivity/lifted_goal.h"
#include "base/errors.h"
#include "base/mpi.h"
#include "slab/adjoint_march.h"

#include <deal.II/base/multithread_info.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace anisodwr::dwr_loop
{
namespace
{
DataQuadrature data_quadrature(const AdaptivitySection &a)
{
  return {a.data_rule_copies, a.data_quadrature_error};
}
} // namespace

SlabSolverOptions AdaptiveLoop::march_solver_options(unsigned int loop,
                                                     const std::string &problem,
                                                     bool concurrent) const
{
  SlabSolverOptions o = slab_solver_options(prm);
  if (concurrent)
  {
    // no Trilinos in two threads: auto picks a direct solver (modes or the coupled
    // UMFPACK) or the frozen operator's modes with deal.II's GMRES
    o.no_trilinos = true;
    if (o.type == SolverType::iterative &&
        !IterativeSlabSolver::runs_without_trilinos(o.iterative))
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
                                          std::shared_future<bool> weights,
                                          std::promise<SharedOperator> *share) const
{
  // `share` always gets a value (null unless the operator serves every slab), also when
  // this thread fails: the other thread waits for it
  struct Share
  {
    std::promise<SharedOperator> *promise;
    void operator()(SharedOperator op)
    {
      if (promise)
        promise->set_value(std::move(op));
      promise = nullptr;
    }
    ~Share() { (*this)(nullptr); }
  } share_op{share};
  // One adjoint per goal: all adjoints first (one factorization serves them), then the
  // estimates without the adjoint's factors in memory
  Timer t;
  AdjointMarch a;
  SlabSolverOptions options = march_solver_options(loop, "adjoint", concurrent);
  // (consistent: u_q solves it untransposed, unless it has an operator of its own)
  const bool by_factors = uq_by_adjoint_factors();
  options.transposed_only = !by_factors;
  a.op = std::make_shared<SlabOperator<2>>(adjoint, basis, options);
  // (prepared here, the march's first prepare() keeps the factors)
  const bool may_share = share && options.reuse_factorization &&
                         !adjoint.scene.coefficients_depend_on_time();
  double waited = 0;
  if (weights.valid() || may_share)
  {
    const unsigned int last = mesh.n_slabs() - 1;
    guarded_slab_solve(
        opt, "adjoint", last, mesh, [&]() { a.op->prepare(mesh.start(last), mesh.tau(last)); },
        Vector<double>());
  }
  const bool shared = may_share && a.op->prepared_for(mesh);
  share_op(shared ? a.op : nullptr);
  if (weights.valid())
  {
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
  if (by_factors && !shared) // u_q by the adjoint's factors (specs: this thread's goals)
    a.J_hi = degree_q_goal_values(
        adjoint, [&](const MarchOptions &o) { return march_primal(adjoint, mesh, basis, *a.op, o); },
        specs, opt);
  a.wall = t.wall_time() - waited;
  return a;
}

void AdaptiveLoop::estimate_from(LoopRow &row, Indicators<2> &ind, const Space<2> &primal,
                                 const Space<2> &adjoint,
                                 const std::vector<Vector<double>> &U,
                                 const HigherOrderPrimal *hi, AdjointMarch adj)
{
  // The estimator solves no slab system: the adjoint's factors and matrices go before
  // it runs.
  release_adjoint(row, adj);
  if (by_goal)
  {
    estimate_by_goal(row, ind, primal, adjoint, std::move(adj.Z), U, hi);
    return;
  }
  Timer t;
  ind = estimate(primal, adjoint, mesh, basis, U, adj.Z[0], goals,
                 prm.adaptivity.time_indicator, hi, prm.adaptivity.space_indicator,
                 data_quadrature(prm.adaptivity), prm.adaptivity.conforming_weights);
  row.t_estimate = t.wall_time();
}

void AdaptiveLoop::release_adjoint(LoopRow &row, AdjointMarch &adj)
{
  if (!adj.op)
    return;
  row.t_adjoint = adj.wall;
  report_auto_choice(row.loop, 1, *adj.op);
  row.lu_adjoint_mb = adj.op->timings().factor_mb;
  adj.op.reset();
  release_free_memory();
}

bool AdaptiveLoop::consistent_by_own_operator() const
{
  return consistent && consistent_uq_needs_own_operator(prm, !crosswind_by_cell.empty());
}

bool AdaptiveLoop::own_uq_operator() const
{
  return enriched || consistent_by_own_operator();
}

bool AdaptiveLoop::uq_by_adjoint_factors() const
{
  return consistent && !consistent_by_own_operator();
}

std::vector<std::unique_ptr<Space<2>>>
AdaptiveLoop::make_uq_spaces(const std::vector<double> &cw_scale) const
{
  std::vector<std::unique_ptr<Space<2>>> spaces;
  if (enriched)
    spaces.push_back(make_enriched_space(prm, *scene, tria, q));
  if (consistent_by_own_operator())
    spaces.push_back(make_adjoint_space(prm, *scene, tria, q, goals));
  // (an empty factor is s_K = 1 on every cell: no solution switches the term)
  for (auto &space : spaces)
    space->set_crosswind_scale(
        cw_scale.empty() ? std::vector<double>(tria.n_active_cells(), 0.) : cw_scale);
  return spaces;
}

double AdaptiveLoop::march_own_uq(LoopRow &row,
                                  const std::vector<std::unique_ptr<Space<2>>> &spaces,
                                  const MarchOptions &opt, bool concurrent) const
{
  Timer t;
  for (const auto &space : spaces)
  {
    row.J_uq.push_back(degree_q_goal_values(
        *space,
        [&](const MarchOptions &o)
        {
          SlabOperator<2> op(*space, basis, march_solver_options(0, "", concurrent));
          return march_primal(*space, mesh, basis, op, o);
        },
        goals, opt));
    release_free_memory();
  }
  return t.wall_time();
}

std::vector<double> AdaptiveLoop::degree_q_goal_values(const Space<2> &space,
                                                       const DegreeQMarch &march,
                                                       const std::vector<GoalSpec> &specs,
                                                       const MarchOptions &opt) const
{
  MarchOptions o = opt;
  o.label += " (primal of degree " + std::to_string(q) + ", adaptivity.goal_estimate)";
  std::vector<double> J;
  try
  {
    const std::vector<Vector<double>> Uq = march(o);
    for (const GoalSpec &goal : specs)
      J.push_back(goal_value(space, goal, mesh, basis, Uq));
    for (const double j : J)
      if (!std::isfinite(j))
        throw NumericalError(o.label + ": a goal value J(u_q) is NaN/Inf");
  }
  catch (const NumericalError &e)
  {
    // a diagnostic solve: the loop goes on with the DWR's goal estimates (J_hi_<goal>
    // empty in loops.csv)
    J.clear();
    if (writes_output())
      std::cout << "warning: " << e.what()
                << "; this loop's goal estimates are the DWR's" << std::endl;
  }
  return J;
}

void AdaptiveLoop::estimate_by_goal(LoopRow &row, Indicators<2> &ind,
                                    const Space<2> &primal, const Space<2> &adjoint,
                                    std::vector<std::vector<Vector<double>>> Z,
                                    const std::vector<Vector<double>> &U,
                                    const HigherOrderPrimal *hi)
{
  Timer t;
  ind = Indicators<2>();
  // goal.weights = estimate: relative to max(|J_i(u_h)|, 1e-2 |J_i(1)| max|u_h|), so a
  // goal whose value is near 0 against the solution's size is not weighted without bound
  double u_max = 0;
  for (const auto &u : U)
    u_max = std::max(u_max, u.linfty_norm());
  // each goal with its own adjoint, in one pass over the cells (the work on u_h shared)
  std::vector<AdjointOf> each;
  for (std::size_t i = 0; i < goals.size(); ++i)
    each.push_back({&Z[i], {unweighted(goals[i])}});
  const std::vector<Indicators<2>> parts =
      estimate_each(primal, adjoint, mesh, basis, U, each, prm.adaptivity.time_indicator,
                    hi, prm.adaptivity.space_indicator, data_quadrature(prm.adaptivity),
                    prm.adaptivity.conforming_weights);
  Z.clear();
  row.pick_goal_hi();
  for (std::size_t i = 0; i < goals.size(); ++i)
  {
    const Indicators<2> &part = parts[i];
    add_goal_estimate(row, part);
    if (!row.J_goal_hi.empty()) // goal_estimate: the spatial part from a primal of degree q
      row.eta_goal[i] = row.J_goal_hi[i] - row.J_goal[i] + row.eta_goal_parts[i][2];
    if (estimate_weights)
    {
      const double one = goal_of_one(primal, unweighted(goals[i])) *
                         (goals[i].over_time ? scene->end_time : 1.);
      goals[i].weight = signed_goal_weight(
          row.eta_goal[i],
          std::max(std::abs(row.J_goal[i]), estimate_weight_floor * std::abs(one) * u_max));
    }
    add_scaled(ind, goals[i].weight, part);
  }
  if (estimate_weights)
    weigh_goals(row);
  row.t_estimate += t.wall_time(); // (after march_own_uq's time)
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
  // (u_q by an operator of its own: a second degree-q factorization, as enriched's)
  count_uq_marches(model, prm, !crosswind_by_cell.empty());
  const SlabSolverOptions options = slab_solver_options(prm);
  const bool higher_order = prm.adaptivity.time_indicator == TimeIndicator::higher_order;
  model.concurrent =
      prm.adaptivity.concurrent_marches &&
      mpi_ranks() == 1 &&
      MultithreadInfo::n_threads() > 1 && options.direct_solver == DirectEngine::umfpack &&
      solves_without_trilinos(options, primal.n_dofs(), prm.discretization.r + 1,
                              primal.degree(), !model.time_dependent) &&
      solves_without_trilinos(options, adjoint.n_dofs(), prm.discretization.r + 1,
                              adjoint.degree(), !model.time_dependent) &&
      (!higher_order ||
       solves_without_trilinos(options, primal.n_dofs(), prm.discretization.r + 2,
                               primal.degree(), !model.time_dependent));
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
} // namespace anisodwr::dwr_loop
