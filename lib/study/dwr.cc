#include "study/dwr.h"
#include "study/memory_estimate.h"
#include "study/options.h"
#include "study/probes.h"

#include "adaptivity/estimator.h"
#include "adaptivity/refinement.h"
#include "adaptivity/spatial_operators.h"
#include "config/errors.h"
#include "goal/goal.h"
#include "io/table.h"
#include "io/vtu.h"
#include "slab/adjoint_march.h"
#include "slab/primal_march.h"

#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <tuple>

namespace anisodwr
{
using namespace dealii;

namespace
{
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> split(const std::string &s, char sep)
{
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep))
  {
    const auto a = item.find_first_not_of(" \t"), b = item.find_last_not_of(" \t");
    out.push_back(a == std::string::npos ? "" : item.substr(a, b - a + 1));
  }
  return out;
}

std::vector<double> numbers(const std::string &s, const std::string &key, unsigned int n,
                            const std::string &source)
{
  std::vector<double> v;
  for (const auto &x : split(s, ','))
    try
    {
      std::size_t used = 0;
      v.push_back(std::stod(x, &used));
      if (used != x.size() || !std::isfinite(v.back()))
        throw std::invalid_argument(x);
    }
    catch (const std::exception &)
    {
      throw InputError(source + ": invalid value '" + s + "' in key '" + key +
                       "'; expected " + std::to_string(n) +
                       " comma-separated finite numbers");
    }
  if (v.size() != n)
    throw InputError(source + ": invalid value '" + s + "' in key '" + key +
                     "'; expected " + std::to_string(n) +
                     " comma-separated numbers, got " + std::to_string(v.size()));
  return v;
}

std::string num(double v)
{
  return json_number(v, 12);
}

struct LoopRow
{
  unsigned int loop = 0, n_t = 0;
  double n_space = 0, n_tot = 0;
  double J = 0, J_exact = nan, eta_h_total = 0, eta_tau = 0, ar = 1;
  std::array<double, 2> eta_h{};
  std::vector<double> J_goal, J_goal_exact;
  std::vector<double> weights;
  double t_primal = 0, t_adjoint = 0, t_estimate = 0, t_refine = 0, mem = 0;
  double eta_tau_rho = 0, eta_tau_rhostar = 0;
  /// adaptivity.measure_time_error: J_w(u_h) - J_w(u_tau h) on this spatial mesh,
  /// extrapolated from the time mesh bisected once and twice (NaN when not measured)
  double err_tau = nan, err_tau_order = nan;
  /// memory estimate of the loop (MB), made before it started (study/memory_estimate.h)
  double mem_estimate = nan;
  /// adaptivity.per_goal_estimates: eta_tau h of each goal from its own adjoint
  std::vector<double> eta_goal;
  MarkingStats marking; ///< the refinement that follows this loop (zeros on the last)
  ProbeResult probes;
  double J_error() const { return std::abs(J_exact - J); }
  double I_eff() const { return std::abs((eta_h_total + eta_tau) / (J_exact - J)); }
  std::vector<double> values() const
  {
    return {double(loop),
            n_space,
            double(n_t),
            n_tot,
            J,
            J_error(),
            eta_h[0],
            eta_h[1],
            eta_h_total,
            eta_tau,
            eta_h_total + eta_tau,
            I_eff(),
            ar,
            t_primal,
            t_adjoint,
            t_estimate,
            t_refine,
            mem};
  }
  /// values() followed by the columns all_columns() adds
  std::vector<double> all_values() const
  {
    auto v = values();
    for (std::size_t g = 0; g < J_goal.size(); ++g)
      v.push_back(J_goal_exact[g] - J_goal[g]);
    for (std::size_t g = 0; g < J_goal.size(); ++g)
      v.push_back(g < eta_goal.size() ? eta_goal[g] : nan);
    for (std::size_t g = 0; g < J_goal.size(); ++g)
      v.push_back(g < eta_goal.size()
                      ? std::abs(eta_goal[g] / (J_goal_exact[g] - J_goal[g]))
                      : nan);
    v.insert(v.end(),
             {eta_tau_rho, eta_tau_rhostar, err_tau, err_tau_order,
              double(marking.marked), double(marking.cut_x), double(marking.cut_y),
              double(marking.cut_both), double(marking.closure), mem_estimate});
    return v;
  }
};

const std::vector<std::string> columns{
    "loop",   "N_space",  "N_t",       "N_tot",      "J",        "J_error",
    "eta_hx", "eta_hy",   "eta_h",     "eta_tau",    "eta_tauh", "I_eff",
    "ar_max", "t_primal", "t_adjoint", "t_estimate", "t_refine", "mem_peak"};

/// Columns after `columns` in loops.csv: the signed error J_i(u) - J_i(u_tau h) of each
/// goal (unweighted; empty without an exact solution), each goal's own eta_tau h and
/// I_eff (adaptivity.per_goal_estimates; else empty), the two halves of eta_tau, the
/// measured temporal error (adaptivity.measure_time_error; else empty), and
/// the cells of the refinement after the loop: marked, cut in x only, in y only, in
/// both, and flagged or extended by the closure; last the loop's memory estimate.
std::vector<std::string> all_columns(const std::vector<GoalSpec> &goals)
{
  auto c = columns;
  for (const std::string prefix : {"err_", "eta_", "I_eff_"})
    for (const auto &g : goals)
      c.push_back(prefix + g.name);
  c.insert(c.end(), {"eta_tau_rho", "eta_tau_rhostar", "err_tau", "err_tau_order",
                     "marked", "marked_x", "marked_y", "marked_xy", "closure",
                     "memory_estimate_mb"});
  return c;
}

void write_latex(const std::string &path, const std::vector<LoopRow> &rows)
{
  std::ofstream f(path);
  f << "% written by anisodwr; one row per DWR loop\n"
    << "\\begin{tabular}{rrrrcccccccr}\n\\hline\n"
    << "$\\ell$ & $N_{\\mathrm{space}}$ & $N_t$ & $N_{\\mathrm{tot}}$ & "
    << "$|J(u)-J(u_{\\tau h})|$ & $\\eta_{h,x}$ & $\\eta_{h,y}$ & $\\eta_h$ & "
       "$\\eta_\\tau$ & "
    << "$\\eta_{\\tau h}$ & $I_{\\mathrm{eff}}$ & $\\mathrm{ar}_{\\max}$ \\\\\n\\hline\n";
  auto sci = [](double v)
  {
    if (!std::isfinite(v))
      return std::string("--");
    std::ostringstream s;
    s << std::scientific << std::setprecision(2) << v;
    return "$" + s.str() + "$";
  };
  for (const auto &r : rows)
  {
    std::ostringstream ie, ar;
    ie << std::fixed << std::setprecision(2) << r.I_eff();
    ar << std::fixed << std::setprecision(1) << r.ar;
    f << r.loop << " & " << std::size_t(r.n_space) << " & " << r.n_t << " & "
      << std::size_t(r.n_tot) << " & " << sci(r.J_error()) << " & " << sci(r.eta_h[0])
      << " & " << sci(r.eta_h[1]) << " & " << sci(r.eta_h_total) << " & "
      << sci(r.eta_tau) << " & " << sci(r.eta_h_total + r.eta_tau) << " & "
      << (std::isfinite(r.I_eff()) ? ie.str() : "--") << " & " << ar.str() << " \\\\\n";
  }
  f << "\\hline\n\\end{tabular}\n";
}

std::string summary_text(const Parameters &prm, const std::vector<GoalSpec> &goals,
                         const std::vector<LoopRow> &rows, const std::string &status,
                         const std::string &stop_reason, double wall,
                         const std::string &details)
{
  std::ostringstream f;
  f << "{\n  \"status\": \"" << json_escape(status) << "\",\n  \"stop_reason\": \""
    << json_escape(stop_reason) << "\",\n";
  if (!details.empty())
    f << "  \"details\": \"" << json_escape(details) << "\",\n";
  f << "  \"config\": " << prm.to_json(2) << ",\n  \"goals\": [";
  for (std::size_t g = 0; g < goals.size(); ++g)
    f << (g ? ", " : "") << "\"" << goals[g].name << "\"";
  f << "],\n  \"loops\": [";
  const auto names = all_columns(goals);
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const auto &r = rows[i];
    f << (i ? ",\n    " : "\n    ") << "{";
    const auto v = r.all_values();
    for (std::size_t c = 0; c < names.size(); ++c)
      f << (c ? ", " : "") << "\"" << names[c] << "\": " << num(v[c]);
    f << ", \"goals\": {";
    for (std::size_t g = 0; g < goals.size(); ++g)
      f << (g ? ", " : "") << "\"" << goals[g].name
        << "\": {\"J_h\": " << num(r.J_goal[g])
        << ", \"J_exact\": " << num(r.J_goal_exact[g])
        << ", \"weight\": " << num(r.weights[g]) << "}";
    f << "}, \"probes\": {";
    for (const auto &[name, value] : r.probes.named())
      f << "\"" << name << "\": " << num(value) << ", ";
    f << "\"u_min\": " << num(r.probes.u_min) << ", \"u_max\": " << num(r.probes.u_max)
      << "}}";
  }
  f << "\n  ],\n  \"wall_time\": " << num(wall)
    << ",\n  \"peak_memory_mb\": " << num(peak_memory_mb()) << ",\n  "
    << solver_totals_json() << "\n}\n";
  return f.str();
}

/// Writes summary.json atomically and prepares the one a SIGINT/SIGTERM leaves: the
/// same rows with status "interrupted".
void write_summary(const Parameters &prm, const std::vector<GoalSpec> &goals,
                   const std::vector<LoopRow> &rows, const std::string &status,
                   const std::string &stop_reason, double wall,
                   const std::string &details = "")
{
  const std::string path = prm.output_directory + "/summary.json";
  write_file_atomically(
      path, summary_text(prm, goals, rows, status, stop_reason, wall, details));
  set_interrupt_summary(path, summary_text(prm, goals, rows, "interrupted",
                                           "interrupted (SIGINT/SIGTERM)", wall, ""));
}

/// The goal with weight 1 (the per-goal values and estimates are unweighted).
GoalSpec unweighted(const GoalSpec &goal)
{
  GoalSpec g = goal;
  g.weight = 1;
  return g;
}

/// J_i(u~) with u~ the patch lift I_2h u_h (the reconstruction behind `auto` weights).
double lifted_goal(const Space<2> &primal, const GoalSpec &goal, const TimeMesh &mesh,
                   const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  const SpatialOperators<2> ops(primal.dof_handler(), 2 * primal.degree());
  const GoalSpec g = unweighted(goal);
  const LocalGoal<2> local(primal.mapping(), ops.weight_element(),
                           primal.dof_handler().get_triangulation(), {g}, g.over_time);
  const FullMatrix<double> P = ops.interpolation_from(primal.finite_element());
  const unsigned int m1 = basis.n_dofs(), N = mesh.n_slabs();
  std::vector<double> gp, gw;
  gauss_rule(m1 + 1, gp, gw);
  std::vector<types::global_dof_index> idx(primal.finite_element().n_dofs_per_cell());
  double J = 0;
  Vector<double> j, v;
  for (const auto &cell : primal.dof_handler().active_cell_iterators())
  {
    if (!local.cell_vector(cell, j))
      continue;
    LocalMap lift = ops.patch_lift(cell);
    if (!lift.exists) // no patch: the lift is u itself
    {
      cell->get_dof_indices(idx);
      lift.exists = true;
      lift.dofs = idx;
      lift.matrix = P;
    }
    auto node_value = [&](unsigned int n, unsigned int k)
    {
      lift.apply(U[n], v, m1, k);
      return j * v;
    };
    if (!g.over_time)
      J += node_value(N - 1, m1 - 1);
    else
      for (unsigned int n = 0; n < N; ++n)
        for (unsigned int k = 0; k < m1; ++k)
        {
          double w = 0;
          for (unsigned int m = 0; m < gp.size(); ++m)
            w += gw[m] * basis.value(k, gp[m]);
          J += mesh.tau(n) * w * node_value(n, k);
        }
  }
  return J;
}

double goal_value(const Space<2> &space, const GoalSpec &goal, const TimeMesh &mesh,
                  const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  return evaluate_goal(assemble_goal_vectors(space, {unweighted(goal)}), mesh, basis, U);
}

TimeIndicator time_indicator(const Parameters &prm)
{
  if (prm.time_indicator == "average")
    return TimeIndicator::average;
  return prm.time_indicator == "adjoint_residual" ? TimeIndicator::adjoint_residual
                                                  : TimeIndicator::higher_order;
}

/// The temporal part of the goal error on the current spatial mesh, measured: the
/// primal is solved again on the time mesh bisected once and twice; with
/// d1 = J(2N) - J(N), d2 = J(4N) - J(2N) and the observed order k = log2(d1 / d2),
/// J(inf) - J(N) = d1 + d2 / (2^k - 1) (Richardson). Returns {error, k}, both NaN when
/// the differences do not contract (k <= 1/2).
std::pair<double, double> measure_time_error(const Space<2> &primal, const TimeMesh &mesh,
                                             const TemporalBasis &basis,
                                             const SlabSolverOptions &solver,
                                             const std::vector<GoalSpec> &goals,
                                             double J_N, const MarchOptions &opt)
{
  auto bisect = [](const TimeMesh &m)
  { return refine_time(m, std::vector<double>(m.n_slabs(), 1.), 1.); };
  const GoalVectors gv = assemble_goal_vectors(primal, goals);
  std::vector<double> J{J_N};
  TimeMesh m = mesh;
  for (unsigned int level = 1; level <= 2; ++level)
  {
    m = bisect(m);
    SlabOperator<2> op(primal, basis, solver);
    const auto U = march_primal(primal, m, basis, op, opt);
    J.push_back(evaluate_goal(gv, m, basis, U));
  }
  std::cout << "  " << opt.label << ": temporal error check, J_w with " << mesh.n_slabs()
            << ", " << 2 * mesh.n_slabs() << ", " << 4 * mesh.n_slabs()
            << " slabs: " << num(J[0]) << ", " << num(J[1]) << ", " << num(J[2])
            << std::endl;
  const double d1 = J[1] - J[0], d2 = J[2] - J[1];
  const double k = std::log2(d1 / d2);
  if (!(k > 0.5) || !std::isfinite(k))
  {
    // not contracting: on strongly anisotropic meshes the SUPG-weighted mass with
    // cell-wise delta_K is indefinite and small slabs can be unstable (doc/results.md)
    std::cout << "  " << opt.label
              << ": temporal error check does not contract; err_tau not reported"
              << std::endl;
    return {nan, nan};
  }
  return {d1 + d2 / (std::pow(2., k) - 1.), k};
}
} // namespace

std::vector<GoalSpec> make_goals(const Parameters &prm, const Scene<2> &scene)
{
  const std::string where = prm.source("goal.locations");
  std::vector<GoalSpec> goals;
  if (prm.goal_kind == "scene")
    goals = scene.default_goals(prm.goal_radius);
  else
  {
    const auto items = split(prm.goal_locations, ';');
    if (prm.goal_locations.empty() || items.empty())
      throw InputError(where + ": key 'goal.locations' is empty; goal.kind = " +
                       prm.goal_kind + " needs at least one location");
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      GoalSpec g;
      g.kind = prm.goal_kind;
      g.over_time = prm.goal_over_time;
      g.name = prm.goal_kind + "_" + std::to_string(i + 1);
      if (g.kind == "point")
      {
        g.center = numbers(items[i], "goal.locations", 2, where);
        g.radius = prm.goal_radius;
        if (!scene.contains(Point<2>(g.center[0], g.center[1])))
          throw InputError(where + ": invalid point '" + items[i] +
                           "' in key 'goal.locations'; it lies outside the domain " +
                           scene.domain_text() + " of scene '" + scene.name() + "'");
      }
      else
      {
        const auto v = numbers(items[i], "goal.locations", 4, where);
        g.lower = {v[0], v[1]};
        g.upper = {v[2], v[3]};
        if (!(v[2] > v[0] && v[3] > v[1]))
          throw InputError(
              where + ": invalid rectangle '" + items[i] +
              "' in key 'goal.locations'; expected x0,y0,x1,y1 with x1 > x0, "
              "y1 > y0");
        if (!scene.contains_box(Point<2>(v[0], v[1]), Point<2>(v[2], v[3])))
          throw InputError(where + ": invalid rectangle '" + items[i] +
                           "' in key 'goal.locations'; it is not inside the domain " +
                           scene.domain_text() + " of scene '" + scene.name() + "'");
      }
      goals.push_back(g);
    }
  }
  // a mollifier wider than the domain is no point goal (and makes J a domain mean)
  const auto box = scene.bounding_box();
  const double diameter = box[0].distance(box[1]);
  for (const auto &g : goals)
    if (g.kind == "point" && !(g.radius <= diameter))
      throw InputError(prm.source("goal.radius") + ": invalid value '" +
                       json_number(g.radius, 6) +
                       "' for key 'goal.radius'; expected a number >= 0 and at most the "
                       "diameter " +
                       json_number(diameter, 6) + " of the domain " +
                       scene.domain_text() + " of scene '" + scene.name() + "'");
  if (prm.goal_weights != "auto")
  {
    const auto w = split(prm.goal_weights, ',');
    if (w.size() != 1 && w.size() != goals.size())
      throw InputError(
          prm.source("goal.weights") + ": invalid value '" + prm.goal_weights +
          "' for key 'goal.weights'; "
          "expected auto, one number or " +
          std::to_string(goals.size()) + " comma-separated numbers (one per goal)");
    const auto v =
        numbers(prm.goal_weights, "goal.weights", w.size(), prm.source("goal.weights"));
    for (std::size_t g = 0; g < goals.size(); ++g)
      goals[g].weight = v[w.size() == 1 ? 0 : g];
  }
  return goals;
}

void run_dwr(const Parameters &prm)
{
  make_directory(prm.output_directory);
  const auto scene = create_scene<2>(prm);
  auto goals = make_goals(prm, *scene);
  const bool auto_weights = prm.goal_weights == "auto";
  const bool has_exact = scene->exact() != nullptr;
  std::vector<double> J_exact(goals.size(), nan);
  if (has_exact)
    for (std::size_t g = 0; g < goals.size(); ++g)
      J_exact[g] = exact_goal(*scene, goals[g]);

  MarkingOptions marking;
  marking.mode = prm.adaptivity_mode;
  marking.theta_h = prm.theta_h;
  marking.marking = prm.marking;
  marking.theta_coarsen = prm.theta_coarsen;
  marking.kappa = prm.kappa;
  Triangulation<2> tria(tria_smoothing<2>(marking));
  scene->make_coarse_grid(tria);
  tria.refine_global(prm.initial_refinements);
  TimeMesh mesh = TimeMesh::uniform(scene->end_time, prm.n_slabs);
  const TemporalBasis basis(prm.r);
  const unsigned int q = prm.adjoint_degree ? prm.adjoint_degree : 2 * prm.p;

  CsvTable table(prm.output_directory + "/loops.csv", all_columns(goals));
  std::vector<std::string> probe_columns{"loop", "N_space", "N_tot"};
  for (const auto &g : goals)
    probe_columns.push_back("J_" + g.name);
  for (const auto &field : ProbeResult().named())
    probe_columns.push_back(field.first);
  CsvTable probe_table(prm.output_directory + "/probes.csv", probe_columns);
  const ProbeSpec<2> probe_spec = scene->probes();
  std::vector<LoopRow> rows;
  std::vector<std::pair<double, std::string>> vtu_records;
  std::string stop_reason = "max loops";
  // the memory estimate: the process before the loops' data, the limit, and the last
  // loop's measured/estimated peak (>= 1) that scales the next estimate
  const double base_mb = resident_memory_mb();
  const MemoryLimit mem_limit = memory_limit(prm);
  double mem_ratio = 1.;
  Timer wall;
  write_summary(prm, goals, rows, "running", "", 0.);
  std::cout << "anisodwr dwr: scene " << scene->name() << ", cG(" << prm.p << ")-dG("
            << prm.r << "), adjoint cG(" << q << "), " << prm.adaptivity_mode
            << ", goals:";
  for (std::size_t g = 0; g < goals.size(); ++g)
    std::cout << " " << goals[g].name << (has_exact ? " = " + num(J_exact[g]) : "");
  std::cout << "\n";
  std::cout << std::setw(4) << "loop" << std::setw(9) << "N_space" << std::setw(6)
            << "N_t" << std::setw(10) << "N_tot" << std::setw(12) << "J_error"
            << std::setw(11) << "eta_hx" << std::setw(11) << "eta_hy" << std::setw(11)
            << "eta_tau" << std::setw(7) << "I_eff" << std::setw(9) << "ar"
            << std::setw(8) << "t[s]" << std::endl;
  try
  {
    for (unsigned int loop = 1; loop <= prm.loops; ++loop)
    {
      LoopRow row;
      row.loop = loop;
      Indicators<2> ind;
      {
        Space<2> primal(*scene, tria, prm.p, prm.delta0, prm.supg_length == "streamline",
                         prm.supg_tau_factor);
        primal.setup();
        Space<2> adjoint(*scene, tria, q,
                         prm.adjoint_stabilization == "none" ? 0. : prm.delta0,
                         prm.supg_length == "streamline",
                         prm.supg_tau_factor);
        adjoint.setup();
        row.n_space = primal.n_dofs();
        row.n_t = mesh.n_slabs();
        row.n_tot = row.n_space * row.n_t * basis.n_dofs();
        if (prm.max_dofs > 0 && row.n_tot > prm.max_dofs)
        {
          stop_reason = "DoF budget: loop " + std::to_string(loop) +
                        " would have N_tot = " + std::to_string(std::size_t(row.n_tot)) +
                        " > adaptivity.max_dofs";
          break;
        }
        const MemoryModel model = memory_model(prm, primal, &adjoint, row.n_t, base_mb);
        row.mem_estimate = estimate_memory(model).total_mb;
        check_memory("loop " + std::to_string(loop), row.mem_estimate * mem_ratio,
                     mem_limit, model,
                     mem_ratio > 1. ? " (the model's " +
                                          json_number(std::round(row.mem_estimate), 10) +
                                          " MB times " + json_number(mem_ratio, 3) +
                                          ", loop " + std::to_string(loop - 1) +
                                          "'s measured/estimated peak)"
                                    : "");
        MarchOptions opt;
        opt.label = "loop " + std::to_string(loop);
        opt.progress = false;
        Timer t;
        std::vector<Vector<double>> U;
        {
          // (the primal's factors are freed before the adjoint factorizes)
          SlabOperator<2> op(primal, basis, slab_solver_options(prm));
          U = march_primal(primal, mesh, basis, op, opt);
        }
        // the dG(r+1) primal of time_indicator = higher_order
        const TemporalBasis basis_hi(prm.r + 1);
        std::vector<Vector<double>> U_hi;
        if (time_indicator(prm) == TimeIndicator::higher_order)
        {
          SlabOperator<2> op(primal, basis_hi, slab_solver_options(prm));
          U_hi = march_primal(primal, mesh, basis_hi, op, opt);
        }
        const HigherOrderPrimal hi{basis_hi, U_hi};
        const HigherOrderPrimal *hi_ptr = U_hi.empty() ? nullptr : &hi;
        row.t_primal = t.wall_time();

        for (std::size_t g = 0; g < goals.size(); ++g)
        {
          row.J_goal.push_back(goal_value(primal, goals[g], mesh, basis, U));
          row.J_goal_exact.push_back(J_exact[g]);
          if (auto_weights)
          {
            const double d =
                lifted_goal(primal, goals[g], mesh, basis, U) - row.J_goal[g];
            goals[g].weight =
                (d >= 0 ? 1. : -1.) / std::max(std::abs(row.J_goal[g]), 1e-12);
          }
          row.weights.push_back(goals[g].weight);
          row.J += goals[g].weight * row.J_goal[g];
          if (has_exact)
            row.J_exact = (g ? row.J_exact : 0.) + goals[g].weight * J_exact[g];
        }

        if (prm.measure_time_error)
          std::tie(row.err_tau, row.err_tau_order) = measure_time_error(
              primal, mesh, basis, slab_solver_options(prm), goals, row.J, opt);

        t.restart();
        SlabOperator<2> opq(adjoint, basis, slab_solver_options(prm));
        const auto Z = march_adjoint(adjoint, mesh, basis, opq,
                                     assemble_goal_vectors(adjoint, goals), opt);
        row.t_adjoint = t.wall_time();

        t.restart();
        ind = estimate(primal, adjoint, mesh, basis, U, Z, goals, time_indicator(prm), hi_ptr);
        row.t_estimate = t.wall_time();
        for (double e : ind.eta_tau_slab)
          if (!std::isfinite(e))
            throw NumericalError(opt.label + ": the time indicator is NaN/Inf");
        if (prm.per_goal_estimates)
          for (const auto &goal : goals)
          {
            const GoalSpec g = unweighted(goal);
            const auto Zg = march_adjoint(adjoint, mesh, basis, opq,
                                          assemble_goal_vectors(adjoint, {g}), opt);
            const auto ig =
                estimate(primal, adjoint, mesh, basis, U, Zg, {g}, time_indicator(prm), hi_ptr);
            row.eta_goal.push_back(ig.eta_h_total() + ig.eta_tau);
          }
        row.eta_h = ind.eta_h;
        row.eta_h_total = ind.eta_h_total();
        row.eta_tau = ind.eta_tau;
        row.eta_tau_rho = ind.eta_tau_rho;
        row.eta_tau_rhostar = ind.eta_tau_rhostar;
        std::vector<double> ar_cell;
        row.ar = max_aspect_ratio(tria, primal.mapping(), &ar_cell);

        Vector<double> uT;
        combine_blocks(U.back(), basis.right_trace(), uT);
        row.probes = evaluate_probes(primal.dof_handler(), primal.mapping(), uT,
                                     probe_spec, *scene, scene->end_time);
        for (const auto &l : probe_spec.cut_lines)
          write_line_csv(prm.output_directory + "/cut_" + l.name + "_loop-" +
                             Utilities::int_to_string(loop, 4) + ".csv",
                         LineEvaluator<2>(primal.dof_handler(), primal.mapping(), uT,
                                          l.start, l.end),
                         2 * prm.p);

        if (prm.vtu_loops > 0 && (loop % prm.vtu_loops == 0 || loop == prm.loops))
        {
          Vector<double> ex(ar_cell.size()), ey(ar_cell.size()), et(ar_cell.size()),
              ar(ar_cell.begin(), ar_cell.end());
          for (unsigned int c = 0; c < ar_cell.size(); ++c)
          {
            ex[c] = ind.eta_h_cell[c][0];
            ey[c] = ind.eta_h_cell[c][1];
            et[c] = ind.eta_tau_cell[c];
          }
          vtu_records.emplace_back(loop, write_vtu(primal, uT, scene->end_time,
                                                   prm.output_directory, "loop", loop,
                                                   {{"eta_hx", ex},
                                                    {"eta_hy", ey},
                                                    {"eta_tau", et},
                                                    {"aspect_ratio", ar}}));
          write_pvd(prm.output_directory, "loops", vtu_records);
        }
      }

      bool stop = false;
      if (loop == prm.loops)
        stop = true;
      else if (prm.tolerance > 0 &&
               std::abs(row.eta_h_total + row.eta_tau) < prm.tolerance)
      {
        stop = true;
        stop_reason = "tolerance";
      }
      else if (prm.max_wall_time > 0 &&
               wall.wall_time() + 2. * (row.t_primal + row.t_adjoint + row.t_estimate) >
                   prm.max_wall_time)
      {
        stop = true;
        stop_reason = "wall-time budget";
      }
      if (!stop)
      {
        Timer t;
        row.marking = mark_cells(tria, ind, marking);
        tria.execute_coarsening_and_refinement();
        mesh = refine_time(mesh, ind.eta_tau_slab, prm.theta_tau);
        row.t_refine = t.wall_time();
      }
      row.mem = peak_memory_mb();
      mem_ratio = std::max(1., row.mem / row.mem_estimate);
      rows.push_back(row);
      table.add_row(row.all_values());
      {
        std::vector<double> v{double(row.loop), row.n_space, row.n_tot};
        v.insert(v.end(), row.J_goal.begin(), row.J_goal.end());
        for (const auto &field : row.probes.named())
          v.push_back(field.second);
        probe_table.add_row(v);
      }
      write_latex(prm.output_directory + "/loops.tex", rows);
      write_summary(prm, goals, rows, "running", "", wall.wall_time());
      std::cout << std::setw(4) << loop << std::setw(9) << std::size_t(row.n_space)
                << std::setw(6) << row.n_t << std::setw(10) << std::size_t(row.n_tot)
                << std::setw(12) << std::setprecision(3) << row.J_error() << std::setw(11)
                << row.eta_h[0] << std::setw(11) << row.eta_h[1] << std::setw(11)
                << row.eta_tau << std::setw(7) << std::setprecision(3) << row.I_eff()
                << std::setw(9) << std::setprecision(4) << row.ar << std::setw(8)
                << std::setprecision(3)
                << row.t_primal + row.t_adjoint + row.t_estimate + row.t_refine
                << std::endl;
      if (stop)
        break;
    }
  }
  catch (const ResourceLimitError &e)
  {
    // not started: the finished loops stay, the reason is the message
    write_summary(prm, goals, rows, "stopped", e.what(), wall.wall_time());
    throw;
  }
  catch (const std::exception &e)
  {
    write_summary(prm, goals, rows, "failed: " + failure_message(e), "error",
                  wall.wall_time(), failure_details(e));
    throw;
  }
  write_summary(prm, goals, rows, "ok", stop_reason, wall.wall_time());
  std::cout << "tables: " << table.path() << ", " << prm.output_directory << "/loops.tex"
            << " (stopped: " << stop_reason << ")\n";
}
} // namespace anisodwr
