#include "dwr/time_error.h"

#include "adaptivity/refinement.h"
#include "goal/goal.h"
#include "io/table.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <tuple>

namespace anisodwr
{
using namespace dealii;

namespace
{
std::string fmt12(double v)
{
  return json_number(v, 12);
}
} // namespace

double goal_value(const Space<2> &space, const GoalSpec &goal, const TimeMesh &mesh,
                  const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  return evaluate_goal(assemble_goal_vectors(space, {unweighted(goal)}), mesh, basis, U);
}

std::pair<double, double> richardson(const std::array<double, 3> &J)
{
  const double d1 = J[1] - J[0], d2 = J[2] - J[1];
  const double k = std::log2(d1 / d2);
  if (!(k > 0.5) || !std::isfinite(k))
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  // d1, d2, d2 / 2^k, d2 / 4^k, ...: J(inf) - J(N) = d1 + d2 + d2 / (2^k - 1)
  return {d1 + d2 * std::pow(2., k) / (std::pow(2., k) - 1.), k};
}

void measure_time_error(const std::function<std::unique_ptr<Space<2>>(double)> &space,
                        const TimeMesh &mesh, const TemporalBasis &basis,
                        const SlabSolverOptions &solver, const std::vector<GoalSpec> &goals,
                        const MarchOptions &opt, LoopRow &row)
{
  auto bisect = [](const TimeMesh &m)
  { return refine_time(m, std::vector<double>(m.n_slabs(), 1.), 1.); };
  // J[0]: the weighted goal, J[1 + i]: goal i unweighted; per level
  std::vector<std::array<double, 3>> J(goals.size() + 1);
  TimeMesh m = mesh;
  for (unsigned int level = 0; level <= 2; ++level)
  {
    if (level > 0)
      m = bisect(m);
    const auto primal = space(std::pow(2., level) / 4.);
    SlabOperator<2> op(*primal, basis, solver);
    const auto U = march_primal(*primal, m, basis, op, opt);
    J[0][level] = 0; // J_w = sum_i w_i J_i, as weigh_goals forms row.J
    for (std::size_t i = 0; i < goals.size(); ++i)
    {
      J[1 + i][level] = goal_value(*primal, goals[i], m, basis, U);
      J[0][level] += goals[i].weight * J[1 + i][level];
    }
  }
  std::cout << "  " << opt.label << ": temporal error check, J_w with " << mesh.n_slabs()
            << ", " << 2 * mesh.n_slabs() << ", " << 4 * mesh.n_slabs()
            << " slabs: " << fmt12(J[0][0]) << ", " << fmt12(J[0][1]) << ", "
            << fmt12(J[0][2]) << std::endl;
  std::tie(row.err_tau, row.err_tau_order) = richardson(J[0]);
  if (std::isnan(row.err_tau))
    std::cout << "  " << opt.label
              << ": temporal error check does not contract; err_tau not reported"
              << std::endl;
  row.err_tau_goal.clear();
  for (std::size_t i = 0; i < goals.size(); ++i)
    row.err_tau_goal.push_back(richardson(J[1 + i]).first);
}

} // namespace anisodwr
