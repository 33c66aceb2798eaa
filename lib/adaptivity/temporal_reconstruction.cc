#include "adaptivity/temporal_reconstruction.h"

namespace anisodwr
{
double lagrange(const std::vector<double> &nodes, unsigned int j, double s,
                bool derivative)
{
  const unsigned int n = nodes.size();
  if (!derivative)
  {
    double v = 1;
    for (unsigned int m = 0; m < n; ++m)
      if (m != j)
        v *= (s - nodes[m]) / (nodes[j] - nodes[m]);
    return v;
  }
  double d = 0;
  for (unsigned int l = 0; l < n; ++l)
  {
    if (l == j)
      continue;
    double v = 1. / (nodes[j] - nodes[l]);
    for (unsigned int m = 0; m < n; ++m)
      if (m != j && m != l)
        v *= (s - nodes[m]) / (nodes[j] - nodes[m]);
    d += v;
  }
  return d;
}

TemporalReconstruction::TemporalReconstruction(const TemporalBasis &basis) : basis(basis)
{
  // primal nodes: 0, s_0, ..., s_r; adjoint nodes: 1 - s_r (= 0), ..., 1 - s_0, 1
  primal_nodes.push_back(0.);
  for (double s : basis.nodes())
    primal_nodes.push_back(s);
  for (auto it = basis.nodes().rbegin(); it != basis.nodes().rend(); ++it)
    adjoint_nodes.push_back(1. - *it);
  adjoint_nodes.push_back(1.);
}

TimeCombination TemporalReconstruction::primal(double s, bool derivative) const
{
  const unsigned int m = basis.n_dofs();
  TimeCombination c;
  c.outside = lagrange(primal_nodes, 0, s, derivative);
  c.slab.resize(m);
  for (unsigned int k = 0; k < m; ++k) // node s_k holds u(s_k) = U_k
    c.slab[k] = lagrange(primal_nodes, k + 1, s, derivative);
  return c;
}

TimeCombination TemporalReconstruction::adjoint(double s, bool derivative) const
{
  const unsigned int m = basis.n_dofs();
  TimeCombination c;
  c.outside = lagrange(adjoint_nodes, m, s, derivative);
  c.slab.assign(m, 0.);
  // node j (0..r) is 1 - s_{r-j}; z(1 - s_{r-j}) = sum_k l_k(1 - s_{r-j}) Z_k
  for (unsigned int j = 0; j < m; ++j)
  {
    const double L = lagrange(adjoint_nodes, j, s, derivative);
    const double sj = adjoint_nodes[j];
    for (unsigned int k = 0; k < m; ++k)
      c.slab[k] += L * basis.value(k, sj);
  }
  return c;
}
} // namespace anisodwr
