#include "dwr/loop_outputs.h"

#include "io/table.h"
#include "io/vtu.h"

#include <deal.II/base/utilities.h>

#include <cmath>

namespace anisodwr
{
using namespace dealii;

void write_loop_outputs(const Parameters &prm, const Scene<2> &scene,
                        const ProbeSpec<2> &probe_spec, LoopRow &row, const Space<2> &primal,
                        const Vector<double> &uT, const Indicators<2> &ind,
                        const std::vector<double> &ar_cell, bool last,
                        std::vector<std::pair<double, std::string>> &vtu_records)
{
  const ProbeResult probes = evaluate_probes(primal.dof_handler(), primal.mapping(), uT,
                                             probe_spec, scene, scene.end_time);
  row.probes = probes.named();
  row.bounds = probes.bounds;
  const unsigned int loop = row.loop;
  for (const auto &l : probe_spec.cut_lines)
    write_line_csv(
        prm.output.directory + "/cut_" + l.name + "_loop-" +
            Utilities::int_to_string(loop, 4) + ".csv",
        LineEvaluator<2>(primal.dof_handler(), primal.mapping(), uT, l.start, l.end),
        2 * prm.discretization.p);
  if (!(prm.output.vtu_loops > 0 && (loop % prm.output.vtu_loops == 0 || last)))
    return;
  Vector<double> ex(ar_cell.size()), ey(ar_cell.size()), et(ar_cell.size()),
      ar(ar_cell.begin(), ar_cell.end());
  for (unsigned int c = 0; c < ar_cell.size(); ++c)
  {
    ex[c] = ind.eta_h_cell[c][0];
    ey[c] = ind.eta_h_cell[c][1];
    et[c] = ind.eta_tau_cell[c];
  }
  vtu_records.emplace_back(
      loop,
      write_vtu(primal, uT, scene.end_time, prm.output.directory, "loop", loop,
                {{"eta_hx", ex}, {"eta_hy", ey}, {"eta_tau", et}, {"aspect_ratio", ar}}));
  write_pvd(prm.output.directory, "loops", vtu_records);
}


void print_run_line(std::ostream &out, const Parameters &prm, const Scene<2> &scene,
                    unsigned int q, const std::vector<GoalSpec> &goals,
                    const std::vector<double> &J_exact, bool has_exact,
                    unsigned int mapping_degree)
{
  out << "anisodwr dwr: scene " << scene.name() << ", cG(" << prm.discretization.p
      << ")-dG(" << prm.discretization.r << "), adjoint cG(" << q << "), ";
  if (mapping_degree > 1)
    out << "MappingQ(" << mapping_degree << ")"
        << (prm.discretization.mapping_degree == 0 ? " (auto: curved manifold)" : "")
        << ", ";
  out << name(prm.adaptivity.mode) << ", goals:";
  for (std::size_t g = 0; g < goals.size(); ++g)
    out << " " << goals[g].name << (has_exact ? " = " + json_number(J_exact[g], 12) : "")
        << (std::isnan(goals[g].reference)
                ? ""
                : " +- " + json_number(goals[g].reference_uncertainty, 12) + " (reference)");
  out << "\n";
}

/// The loop table's copy of the estimator's sums.
void copy_indicators(const Indicators<2> &ind, LoopRow &row)
{
  row.eta_h = ind.eta_h;
  row.eta_h_total = ind.eta_h_total();
  row.eta_tau = ind.eta_tau;
  row.eta_tau_rho = ind.eta_tau_rho;
  row.eta_tau_rhostar = ind.eta_tau_rhostar;
  row.eta_h_rho = ind.eta_h_rho;
  row.eta_h_rhostar = ind.eta_h_rhostar;
  row.eta_h_supg = ind.eta_h_supg;
  row.eta_h_split_rest = ind.eta_h_split_rest;
  row.eta_h_data = ind.eta_h_data;
  row.eta_h_quad = ind.eta_h_quad;
  row.no_lift = ind.no_lift;
}

/// One goal's own estimate and its signed parts into row (eta_<goal>, eta_hx_<goal>, ...).
void add_goal_estimate(LoopRow &row, const Indicators<2> &goal_ind)
{
  row.eta_goal.push_back(goal_ind.eta_h_total() + goal_ind.eta_tau);
  row.eta_goal_parts.push_back({{goal_ind.eta_h[0], goal_ind.eta_h[1], goal_ind.eta_tau}});
}

/// The uncertainties of goal.reference, one per goal (empty without references).
std::vector<double> reference_uncertainties(const std::vector<GoalSpec> &goals)
{
  std::vector<double> u;
  for (const auto &g : goals)
    if (!std::isnan(g.reference))
      u.push_back(g.reference_uncertainty);
  return u;
}

std::vector<std::string> goal_names(const std::vector<GoalSpec> &goals)
{
  std::vector<std::string> names;
  for (const auto &g : goals)
    names.push_back(g.name);
  return names;
}

std::vector<std::string> probe_columns(const std::vector<GoalSpec> &goals)
{
  std::vector<std::string> columns{"loop", "N_space", "N_tot"};
  for (const auto &g : goals)
    columns.push_back("J_" + g.name);
  for (const auto &field : ProbeResult().named())
    columns.push_back(field.first);
  return columns;
}
} // namespace anisodwr
