#include "io/loop_report.h"

#include "base/mpi.h"
#include "io/table.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace anisodwr
{
namespace
{
std::string num(double v)
{
  return json_number(v, 12);
}

const std::vector<std::string> columns{
    "loop",   "N_space",  "N_t",       "N_tot",      "J",        "J_error",
    "eta_hx", "eta_hy",   "eta_h",     "eta_tau",    "eta_tauh", "I_eff",
    "ar_max", "t_primal", "t_adjoint", "t_estimate", "t_refine", "mem_peak"};
} // namespace

std::vector<double> LoopRow::values() const
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

std::vector<double> LoopRow::all_values() const
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
  for (unsigned int part = 0; part < 3; ++part)
    for (std::size_t g = 0; g < J_goal.size(); ++g)
      v.push_back(g < eta_goal_parts.size() ? eta_goal_parts[g][part] : nan);
  for (std::size_t g = 0; g < J_goal.size(); ++g)
    v.push_back(g < err_tau_goal.size() ? err_tau_goal[g] : nan);
  v.insert(v.end(),
           {eta_tau_rho, eta_tau_rhostar, err_tau, err_tau_order, double(marking[0]),
            double(marking[1]), double(marking[2]), double(marking[3]),
            double(marking[4]), mem_estimate, eta_h_rho, eta_h_rhostar, eta_h_supg,
            no_lift, lu_primal_mb, lu_adjoint_mb, concurrent, eta_h_split_rest,
            eta_parts_abs(), hanging_gap, eta_h_data, double(bound_cuts), eta_drift,
            eta_h_quad});
  for (std::size_t g = 0; g < J_goal.size(); ++g)
    v.push_back(g < J_goal_hi.size() ? J_goal_hi[g] : nan);
  return v;
}

double LoopRow::eta_goals_max() const
{
  if (eta_goal.empty() || eta_goal.size() != weights.size())
    return std::abs(eta_h_total + eta_tau);
  double m = 0;
  for (std::size_t g = 0; g < eta_goal.size(); ++g)
    m = std::max(m, std::abs(weights[g] * eta_goal[g]));
  return m;
}

double corrected_drift(const LoopRow &previous, const LoopRow &row)
{
  const std::size_t n = row.J_goal.size();
  const auto per_goal = [n](const LoopRow &r)
  { return r.eta_goal.size() == n && r.weights.size() == n && r.J_goal.size() == n; };
  if (n > 0 && per_goal(row) && per_goal(previous))
  {
    double drift = 0;
    for (std::size_t g = 0; g < n; ++g)
      drift += std::abs(row.weights[g]) * std::abs((row.J_goal[g] + row.eta_goal[g]) -
                                                   (previous.J_goal[g] + previous.eta_goal[g]));
    return drift;
  }
  if (row.weights != previous.weights)
    return LoopRow::nan;
  return std::abs((row.J + row.eta_h_total + row.eta_tau) -
                  (previous.J + previous.eta_h_total + previous.eta_tau));
}

double LoopRow::eta_parts_abs() const
{
  return eta_space_abs() + eta_time_abs();
}

namespace
{
/// sum of |w_i part| over the goals' parts [first, last) (or the weighted goal's)
double abs_parts(const LoopRow &row, unsigned int first, unsigned int last)
{
  const std::array<double, 3> own{{row.eta_h[0], row.eta_h[1], row.eta_tau}};
  const bool per_goal =
      !row.eta_goal_parts.empty() && row.eta_goal_parts.size() == row.weights.size();
  double sum = 0;
  for (std::size_t g = 0; g < (per_goal ? row.weights.size() : 1); ++g)
    for (unsigned int part = first; part < last; ++part)
      sum += per_goal ? std::abs(row.weights[g] * row.eta_goal_parts[g][part])
                      : std::abs(own[part]);
  return sum;
}
} // namespace

double LoopRow::eta_space_abs() const
{
  // adaptivity.goal_estimate other than dwr: each goal's spatial estimate is one number
  if (!J_goal_hi.empty() && J_goal_hi.size() == weights.size())
  {
    double sum = 0;
    for (std::size_t g = 0; g < weights.size(); ++g)
      sum += std::abs(weights[g] * (J_goal_hi[g] - J_goal[g]));
    return sum;
  }
  return abs_parts(*this, 0, 2);
}

double LoopRow::eta_time_abs() const
{
  return abs_parts(*this, 2, 3);
}

void LoopRow::pick_goal_hi()
{
  J_goal_hi.clear();
  for (const std::vector<double> &J : J_uq)
  {
    if (J.size() != J_goal.size())
      continue; // (a failed march)
    if (J_goal_hi.empty())
      J_goal_hi = J;
    else
      for (std::size_t g = 0; g < J.size(); ++g)
        if (std::abs(J[g] - J_goal[g]) > std::abs(J_goal_hi[g] - J_goal[g]))
          J_goal_hi[g] = J[g];
  }
}

/// Columns after `columns` in loops.csv: the signed error J_i(u) - J_i(u_tau h) of each
/// goal (unweighted; empty without an exact solution), each goal's own eta_tau h and
/// I_eff (adaptivity.per_goal_estimates; else empty) and its parts eta_h,x, eta_h,y,
/// eta_tau (columns eta_hx_<goal>, eta_hy_<goal>, eta_tau_<goal>), each goal's measured
/// temporal error (err_time_<goal>, unweighted; adaptivity.measure_time_error, else
/// empty), the two halves of eta_tau, the measured temporal error of the weighted goal
/// and its observed order (the same key), and
/// the cells of the refinement after the loop: marked, cut in x only, in y only, in
/// both, and flagged or extended by the closure; the loop's memory estimate; last the
/// parts of eta_h (1/2 rho(u)(z - R_i z), the adjoint half, S(u)(R_h z), summed over
/// directions), the number of (cell, direction) pairs without a lift and the UMFPACK
/// factor sizes of the primal and adjoint slab matrices (MB), whether the primal and
/// the adjoint marched concurrently (1/0), the remainder of the directional split and
/// LoopRow::eta_parts_abs(), the mesh's hanging-node mismatch (max_hanging_gap) and the
/// Dirichlet data's share of eta_h (Indicators::eta_h_data), the cells that
/// adaptivity.bound_refinement cut, the corrected goal values' drift (eta_drift) and
/// the primal's data quadrature error in eta_h (Indicators::eta_h_quad), and each goal's
/// value from the primal of the adjoint's degree (J_hi_<goal>; adaptivity.goal_estimate
/// = enriched, else empty).
std::vector<std::string> loop_columns(const std::vector<std::string> &goal_names)
{
  auto c = columns;
  for (const std::string prefix :
       {"err_", "eta_", "I_eff_", "eta_hx_", "eta_hy_", "eta_tau_", "err_time_"})
    for (const auto &name : goal_names)
      c.push_back(prefix + name);
  c.insert(c.end(),
           {"eta_tau_rho", "eta_tau_rhostar", "err_tau", "err_tau_order", "marked",
            "marked_x", "marked_y", "marked_xy", "closure", "memory_estimate_mb",
            "eta_h_rho", "eta_h_rhostar", "eta_h_supg", "no_lift", "lu_primal_mb",
            "lu_adjoint_mb", "concurrent", "eta_h_split_rest", "eta_abs",
            "hanging_gap", "eta_h_data", "bound_cuts", "eta_drift",
            "eta_h_quad"});
  for (const auto &name : goal_names)
    c.push_back("J_hi_" + name);
  return c;
}

void write_loops_latex(const std::string &path, const std::vector<LoopRow> &rows)
{
  if (!writes_output())
    return;
  std::ostringstream f;
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
  write_file_atomically_here(path, f.str());
}

std::string summary_json(const SummaryContext &context, const std::vector<LoopRow> &rows,
                         const std::string &status, const std::string &stop_reason,
                         double wall, const std::string &details)
{
  std::ostringstream f;
  f << "{\n  \"status\": \"" << json_escape(status) << "\",\n  \"mpi_ranks\": "
    << mpi_ranks() << ",\n  \"stop_reason\": \"" << json_escape(stop_reason) << "\",\n";
  if (!details.empty())
    f << "  \"details\": \"" << json_escape(details) << "\",\n";
  const auto &goals = context.goal_names;
  f << "  \"config\": " << context.config_json << ",\n  \"goals\": [";
  for (std::size_t g = 0; g < goals.size(); ++g)
    f << (g ? ", " : "") << "\"" << goals[g] << "\"";
  f << "],\n  \"error_reference\": \"" << json_escape(context.error_reference) << "\"";
  if (!context.reference_uncertainty.empty())
  {
    f << ",\n  \"reference_uncertainty\": [";
    for (std::size_t g = 0; g < context.reference_uncertainty.size(); ++g)
      f << (g ? ", " : "") << num(context.reference_uncertainty[g]);
    f << "]";
  }
  f << ",\n  \"loops\": [";
  const auto names = loop_columns(goals);
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const auto &r = rows[i];
    f << (i ? ",\n    " : "\n    ") << "{";
    const auto v = r.all_values();
    for (std::size_t c = 0; c < names.size(); ++c)
      f << (c ? ", " : "") << "\"" << names[c] << "\": " << num(v[c]);
    f << ", \"goals\": {";
    for (std::size_t g = 0; g < goals.size(); ++g)
      f << (g ? ", " : "") << "\"" << goals[g] << "\": {\"J_h\": " << num(r.J_goal[g])
        << ", \"J_exact\": " << num(r.J_goal_exact[g])
        << ", \"weight\": " << num(r.weights[g])
        << (r.lift_difference.size() > g
                ? ", \"lift_difference\": " + num(r.lift_difference[g])
                : std::string())
        << "}";
    f << "}, \"probes\": {";
    for (const auto &[name, value] : r.probes)
      f << "\"" << name << "\": " << num(value) << ", ";
    f << "\"bounds\": \"" << r.bounds << "\"}}";
  }
  f << "\n  ],\n  \"wall_time\": " << num(wall)
    << ",\n  \"peak_memory_mb\": " << num(peak_memory_mb()) << ",\n  "
    << context.solver_json << "\n}\n";
  return f.str();
}

void write_summary(const std::string &path, const SummaryContext &context,
                   const std::vector<LoopRow> &rows, const std::string &status,
                   const std::string &stop_reason, double wall,
                   const std::string &details)
{
  write_file_atomically(path,
                        summary_json(context, rows, status, stop_reason, wall, details));
  set_interrupt_summary(path, summary_json(context, rows, "interrupted",
                                           "interrupted (SIGINT/SIGTERM)", wall, ""));
}

void print_loop_header(std::ostream &out)
{
  out << std::setw(4) << "loop" << std::setw(9) << "N_space" << std::setw(6) << "N_t"
      << std::setw(10) << "N_tot" << std::setw(12) << "J_error" << std::setw(11)
      << "eta_hx" << std::setw(11) << "eta_hy" << std::setw(11) << "eta_tau"
      << std::setw(7) << "I_eff" << std::setw(11) << "ar" << std::setw(8) << "t[s]"
      << std::endl;
}

void print_loop_row(std::ostream &out, const LoopRow &row)
{
  out << std::setw(4) << row.loop << std::setw(9) << std::size_t(row.n_space)
      << std::setw(6) << row.n_t << std::setw(10) << std::size_t(row.n_tot)
      << std::setw(12) << std::setprecision(3) << row.J_error() << std::setw(11)
      << row.eta_h[0] << std::setw(11) << row.eta_h[1] << std::setw(11) << row.eta_tau
      << std::setw(7) << std::setprecision(3) << row.I_eff() << std::setw(11)
      << std::setprecision(4) << row.ar << std::setw(8) << std::setprecision(3)
      << row.t_primal + row.t_adjoint + row.t_estimate + row.t_refine << std::endl;
}
} // namespace anisodwr
