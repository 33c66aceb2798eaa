#include "study/loop_outputs.h"

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
                        const std::vector<double> &ar_cell,
                        std::vector<std::pair<double, std::string>> &vtu_records)
{
  const ProbeResult probes = evaluate_probes(primal.dof_handler(), primal.mapping(), uT,
                                             probe_spec, scene, scene.end_time);
  row.probes = probes.named();
  row.u_min = probes.u_min;
  row.u_max = probes.u_max;
  const unsigned int loop = row.loop;
  for (const auto &l : probe_spec.cut_lines)
    write_line_csv(
        prm.output.directory + "/cut_" + l.name + "_loop-" +
            Utilities::int_to_string(loop, 4) + ".csv",
        LineEvaluator<2>(primal.dof_handler(), primal.mapping(), uT, l.start, l.end),
        2 * prm.discretization.p);
  if (!(prm.output.vtu_loops > 0 &&
        (loop % prm.output.vtu_loops == 0 || loop == prm.adaptivity.loops)))
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
                    const std::vector<double> &J_exact, bool has_exact)
{
  out << "anisodwr dwr: scene " << scene.name() << ", cG(" << prm.discretization.p
      << ")-dG(" << prm.discretization.r << "), adjoint cG(" << q << "), "
      << name(prm.adaptivity.mode) << ", goals:";
  for (std::size_t g = 0; g < goals.size(); ++g)
    out << " " << goals[g].name << (has_exact ? " = " + json_number(J_exact[g], 12) : "")
        << (std::isnan(goals[g].reference)
                ? ""
                : " +- " + json_number(goals[g].reference_uncertainty, 12) + " (reference)");
  out << "\n";
}
} // namespace anisodwr
