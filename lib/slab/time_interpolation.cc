// The spatial matrices of a slab operator whose coefficients depend on time, at a
// temporal quadrature point: interpolated in time from the Chebyshev points of [0, T]
// where that reproduces the assembly (SlabOperator::matrices_at), else assembled.
#include "slab/slab_operator.h"

#include <deal.II/lac/affine_constraints.h>

#include <array>
#include <initializer_list>
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

/// The Lagrange polynomials of the time nodes at t.
std::vector<double> time_node_weights(double t, double T)
{
  std::vector<double> l(n_time_nodes, 1.);
  for (unsigned int k = 0; k < n_time_nodes; ++k)
    for (unsigned int j = 0; j < n_time_nodes; ++j)
      if (j != k)
        l[k] *= (t - time_node(j, T)) / (time_node(k, T) - time_node(j, T));
  return l;
}

/// m := sum_k l_k(t) at_nodes[k] (l_k the Lagrange polynomials of the time nodes),
/// for the parts M, A, M_c, A_c named in `parts` (0..3).
void interpolate(const std::vector<SpatialMatrices> &at_nodes, double t, double T,
                 SpatialMatrices &m, std::initializer_list<unsigned int> parts = {0, 1, 2, 3})
{
  const std::vector<double> l = time_node_weights(t, T);
  const auto out = [&m](unsigned int p)
  { return std::array<SparseMatrix<double> *, 4>{{&m.M, &m.A, &m.Mc, &m.Ac}}[p]; };
  const auto in = [](const SpatialMatrices &x, unsigned int p)
  { return std::array<const SparseMatrix<double> *, 4>{{&x.M, &x.A, &x.Mc, &x.Ac}}[p]; };
  for (const unsigned int p : parts)
  {
    if (in(at_nodes[0], p)->empty()) // not kept at the nodes (transposed_only: A)
    {
      out(p)->clear();
      continue;
    }
    out(p)->reinit(in(at_nodes[0], p)->get_sparsity_pattern());
    for (unsigned int k = 0; k < n_time_nodes; ++k)
      out(p)->add(l[k], *in(at_nodes[k], p));
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
const std::vector<SpatialMatrices> *SlabOperator<dim>::time_nodes(double tau_n)
{
  if (!opt.time_interpolation)
    return nullptr;
  const double T = space.scene.end_time;
  // one set for all slab lengths unless delta_K depends on tau (keys rounded so that
  // equal lengths computed as differences share one)
  const double key = space.delta_depends_on_tau() ? std::round(tau_n / T * 1e12) : -1.;
  auto it = interpolation.find(key);
  if (it == interpolation.end() && interpolation.size() >= max_time_interpolations)
    return nullptr; // memory: at most two slab lengths keep their node matrices
  if (it == interpolation.end())
  {
    TimeInterpolation ti;
    ti.at_nodes.resize(n_time_nodes);
    for (unsigned int k = 0; k < n_time_nodes; ++k)
    {
      space.assemble_matrices(time_node(k, T), tau_n, ti.at_nodes[k]);
      // all nodes carry the first one's constrained diagonal: their combinations
      // (weights summing to 1) then carry it too
      constrained_diagonal(space.constraints(), ti.at_nodes[0], ti.at_nodes[k]);
    }
    time.n_spatial_assemblies += n_time_nodes;
    bool exact = true;
    for (const double check : {0.3819660112501051 * T, 0.8541019662496845 * T})
    {
      SpatialMatrices assembled, interpolated;
      space.assemble_matrices(check, tau_n, assembled);
      ++time.n_spatial_assemblies;
      constrained_diagonal(space.constraints(), ti.at_nodes[0], assembled);
      interpolate(ti.at_nodes, check, T, interpolated);
      exact = exact && agree(assembled, interpolated);
    }
    if (!exact)
      ti.at_nodes.clear();
    else if (opt.transposed_only) // only the lift (solve, not transposed) reads A
      for (auto &node : ti.at_nodes)
        node.A.clear();
    it = interpolation.emplace(key, std::move(ti)).first;
  }
  return it->second.at_nodes.empty() ? nullptr : &it->second.at_nodes;
}

template <int dim>
std::vector<double> SlabOperator<dim>::time_node_weights(double t) const
{
  return anisodwr::time_node_weights(t, space.scene.end_time);
}

template <int dim>
void SlabOperator<dim>::matrices_at(double t, double tau_n, SpatialMatrices &m,
                                    bool mass_only)
{
  if (const auto *nodes = time_nodes(tau_n))
  {
    if (mass_only)
      interpolate(*nodes, t, space.scene.end_time, m, {0});
    else
      interpolate(*nodes, t, space.scene.end_time, m);
    ++time.n_interpolated;
  }
  else
  {
    space.assemble_matrices(t, tau_n, m);
    ++time.n_spatial_assemblies;
  }
}

template const std::vector<SpatialMatrices> *SlabOperator<2>::time_nodes(double);
template std::vector<double> SlabOperator<2>::time_node_weights(double) const;
template void SlabOperator<2>::matrices_at(double, double, SpatialMatrices &, bool);
} // namespace anisodwr
