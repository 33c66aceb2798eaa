#include "adaptivity/lifted_goal.h"

#include "adaptivity/spatial_operators.h"
#include "goal/goal.h"

namespace anisodwr
{
using namespace dealii;

double lift_difference(const Space<2> &primal, const GoalSpec &goal, const TimeMesh &mesh,
                       const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  const SpatialOperators<2> ops(primal.dof_handler(), 2 * primal.degree());
  const GoalSpec g = unweighted(goal);
  const auto &tria = primal.dof_handler().get_triangulation();
  const LocalGoal<2> local_t(primal.scene, primal.mapping(), ops.weight_element(), tria,
                             {g}, true),
      local_T(primal.scene, primal.mapping(), ops.weight_element(), tria, {g}, false);
  const FullMatrix<double> P = ops.interpolation_from(primal.finite_element());
  const unsigned int m1 = basis.n_dofs(), N = mesh.n_slabs();
  std::vector<double> gp, gw;
  gauss_rule(m1 + 1, gp, gw);
  double d = 0;
  Vector<double> j, v, u;
  LocalMap own; // u_h on the cell, interpolated into the weight element
  own.exists = true;
  own.dofs.resize(primal.finite_element().n_dofs_per_cell());
  own.matrix = P;
  Vector<double> jT;
  for (const auto &cell : primal.dof_handler().active_cell_iterators())
  {
    const bool at_end = !local_T.empty() && local_T.cell_vector(cell, jT),
               over_time = !local_t.empty() && local_t.cell_vector(cell, j);
    if (!at_end && !over_time)
      continue;
    const LocalMap lift = ops.patch_lift(cell);
    if (!lift.exists) // no patch: the lift is u_h itself
      continue;
    cell->get_dof_indices(own.dofs);
    auto node_value = [&](unsigned int n, unsigned int k, const Vector<double> &jn)
    {
      lift.apply(U[n], v, m1, k);
      own.apply(U[n], u, m1, k);
      v -= u;
      return jn * v;
    };
    if (at_end)
      d += node_value(N - 1, m1 - 1, jT);
    if (over_time)
      for (unsigned int n = 0; n < N; ++n)
        for (unsigned int k = 0; k < m1; ++k)
        {
          double w = 0;
          for (unsigned int m = 0; m < gp.size(); ++m)
            w += gw[m] * basis.value(k, gp[m]);
          d += mesh.tau(n) * w * node_value(n, k, j);
        }
  }
  return d;
}
} // namespace anisodwr
