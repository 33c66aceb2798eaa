// The spatial matrices of a slab operator whose coefficients depend on time, at a
// temporal quadrature point: interpolated in time from the Chebyshev points of [0, T]
// where that reproduces the assembly (SlabOperator::matrices_at), else assembled.
#include "slab/slab_operator.h"

#include <deal.II/lac/affine_constraints.h>

#include <array>
#include <cmath>
#include <utility>

namespace anisodwr
{
using namespace dealii;

namespace
{
constexpr unsigned int n_time_nodes = 4;
/// Slab lengths whose node matrices are kept (each holds n_time_nodes sets of M, A,
/// M_c, A_c).
constexpr std::size_t max_time_interpolations = 2;

/// The Chebyshev points of [0, T] (n_time_nodes of them).
double time_node(unsigned int k, double T)
{
  return 0.5 * T * (1. - std::cos((2. * k + 1.) * M_PI / (2. * n_time_nodes)));
}

/// m := sum_k l_k(t) at_nodes[k] (l_k the Lagrange polynomials of the time nodes).
void interpolate(const std::vector<SpatialMatrices> &at_nodes, double t, double T,
                 SpatialMatrices &m)
{
  std::vector<double> l(n_time_nodes, 1.);
  for (unsigned int k = 0; k < n_time_nodes; ++k)
    for (unsigned int j = 0; j < n_time_nodes; ++j)
      if (j != k)
        l[k] *= (t - time_node(j, T)) / (time_node(k, T) - time_node(j, T));
  const auto parts = [](SpatialMatrices &x)
  { return std::array<SparseMatrix<double> *, 4>{{&x.M, &x.A, &x.Mc, &x.Ac}}; };
  const auto from = [](const SpatialMatrices &x)
  { return std::array<const SparseMatrix<double> *, 4>{{&x.M, &x.A, &x.Mc, &x.Ac}}; };
  const auto out = parts(m);
  for (unsigned int p = 0; p < 4; ++p)
  {
    out[p]->reinit(from(at_nodes[0])[p]->get_sparsity_pattern());
    for (unsigned int k = 0; k < n_time_nodes; ++k)
      out[p]->add(l[k], *from(at_nodes[k])[p]);
  }
}

/// The rows of constrained DoFs in M_c and A_c hold only a diagonal entry, which the
/// assembly sets from the cell matrices' absolute values (not polynomial in t); it does
/// not couple to the other DoFs. Sets it to ref's, in both.
void constrained_diagonal(const AffineConstraints<double> &constraints,
                          const SpatialMatrices &ref, SpatialMatrices &m)
{
  for (types::global_dof_index i = 0; i < m.Mc.m(); ++i)
    if (constraints.is_constrained(i))
    {
      m.Mc.set(i, i, ref.Mc(i, i));
      m.Ac.set(i, i, ref.Ac(i, i));
    }
}

/// True if a and b agree to 1e-12 relative in each of M, A, M_c, A_c (Frobenius norm);
/// b is overwritten by b - a.
bool agree(const SpatialMatrices &a, SpatialMatrices &b)
{
  for (const auto &[x, y] : {std::pair{&a.M, &b.M}, std::pair{&a.A, &b.A},
                             std::pair{&a.Mc, &b.Mc}, std::pair{&a.Ac, &b.Ac}})
  {
    const double norm = x->frobenius_norm();
    y->add(-1., *x);
    if (!(y->frobenius_norm() <= 1e-12 * norm))
      return false;
  }
  return true;
}
} // namespace

template <int dim>
void SlabOperator<dim>::matrices_at(double t, double tau_n, SpatialMatrices &m)
{
  const double T = space.scene.end_time;
  // one set for all slab lengths unless delta_K depends on tau (keys rounded so that
  // equal lengths computed as differences share one)
  const double key = space.delta_depends_on_tau() ? std::round(tau_n / T * 1e12) : -1.;
  if (!opt.time_interpolation)
  {
    space.assemble_matrices(t, tau_n, m);
    ++time.n_spatial_assemblies;
    return;
  }
  auto it = interpolation.find(key);
  if (it == interpolation.end() && interpolation.size() >= max_time_interpolations)
  {
    // memory: at most two slab lengths keep their node matrices; others assemble
    space.assemble_matrices(t, tau_n, m);
    ++time.n_spatial_assemblies;
    return;
  }
  if (it == interpolation.end())
  {
    TimeInterpolation ti;
    ti.at_nodes.resize(n_time_nodes);
    for (unsigned int k = 0; k < n_time_nodes; ++k)
      space.assemble_matrices(time_node(k, T), tau_n, ti.at_nodes[k]);
    time.n_spatial_assemblies += n_time_nodes;
    bool exact = true;
    for (const double check : {0.3819660112501051 * T, 0.8541019662496845 * T})
    {
      SpatialMatrices assembled, interpolated;
      space.assemble_matrices(check, tau_n, assembled);
      ++time.n_spatial_assemblies;
      constrained_diagonal(space.constraints(), ti.at_nodes[0], assembled);
      interpolate(ti.at_nodes, check, T, interpolated);
      constrained_diagonal(space.constraints(), ti.at_nodes[0], interpolated);
      exact = exact && agree(assembled, interpolated);
    }
    if (!exact)
      ti.at_nodes.clear();
    it = interpolation.emplace(key, std::move(ti)).first;
  }
  if (!it->second.at_nodes.empty())
  {
    interpolate(it->second.at_nodes, t, T, m);
    constrained_diagonal(space.constraints(), it->second.at_nodes[0], m);
    ++time.n_interpolated;
  }
  else
  {
    space.assemble_matrices(t, tau_n, m);
    ++time.n_spatial_assemblies;
  }
}

template void SlabOperator<2>::matrices_at(double, double, SpatialMatrices &);
} // namespace anisodwr
