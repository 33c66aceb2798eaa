// The spatial matrices of a slab operator whose coefficients depend on time, at a
// temporal quadrature point: interpolated in time from a few times of [0, T] by the
// polynomial of the lowest degree (<= 3) that reproduces the assembly
// (SlabOperator::matrices_at), else assembled.
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
constexpr unsigned int max_degree = 3;
/// The times of [0, T] (fractions of T) assembled in turn: the interpolant of degree d
/// takes the first d + 1 as its nodes and is checked at the next two, so that d = 1, 2,
/// 3 need 4, 5, 6 assemblies. The first four are the Chebyshev points of degree 3
/// (outer pair first), the checks of d = 3 two points away from them.
constexpr std::array<double, max_degree + 3> sample_times{
    {0.03806023374435663, 0.9619397662556434, 0.3086582838174551, 0.6913417161825449,
     0.3819660112501051, 0.8541019662496845}};
/// Slab lengths whose node matrices are kept (each holds up to max_degree + 1 sets of
/// M, A, M_c, A_c).
constexpr std::size_t max_time_interpolations = 2;

/// m := sum_k l_k(t) at_nodes[k] (l_k the Lagrange polynomials of the node times; the
/// first times.size() entries of at_nodes), for the parts M, A, M_c, A_c named in
/// `parts` (0..3).
void interpolate(const std::vector<SpatialMatrices> &at_nodes,
                 const std::vector<double> &times, double t, SpatialMatrices &m,
                 std::initializer_list<unsigned int> parts = {0, 1, 2, 3})
{
  const std::vector<double> l = lagrange_weights(times, t);
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
    for (unsigned int k = 0; k < times.size(); ++k)
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

/// True if the interpolant of `nodes` (at `times`) reproduces `assembled` at t to 1e-12
/// relative in each of M, A, M_c, A_c (Frobenius norm); one part at a time, so that
/// the check holds one matrix beside the nodes.
bool reproduces(const std::vector<SpatialMatrices> &nodes, const std::vector<double> &times,
                double t, const SpatialMatrices &assembled)
{
  for (const unsigned int p : {0u, 1u, 2u, 3u})
  {
    SpatialMatrices m;
    interpolate(nodes, times, t, m, {p});
    SparseMatrix<double> &y = *std::array<SparseMatrix<double> *, 4>{{&m.M, &m.A, &m.Mc, &m.Ac}}[p];
    const SparseMatrix<double> &x = *std::array<const SparseMatrix<double> *, 4>{
        {&assembled.M, &assembled.A, &assembled.Mc, &assembled.Ac}}[p];
    const double norm = x.frobenius_norm();
    y.add(-1., x);
    if (!(y.frobenius_norm() <= 1e-12 * norm))
      return false;
  }
  return true;
}
} // namespace

std::vector<double> lagrange_weights(const std::vector<double> &nodes, double t)
{
  std::vector<double> l(nodes.size(), 1.);
  for (unsigned int k = 0; k < nodes.size(); ++k)
    for (unsigned int j = 0; j < nodes.size(); ++j)
      if (j != k)
        l[k] *= (t - nodes[j]) / (nodes[k] - nodes[j]);
  return l;
}

template <int dim>
const typename SlabOperator<dim>::TimeInterpolation *
SlabOperator<dim>::time_nodes(double tau_n)
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
    // the matrices at sample_times[i] T, assembled as the checks ask for them
    std::vector<SpatialMatrices> at;
    std::vector<double> times;
    const auto sample = [&](unsigned int i) -> const SpatialMatrices &
    {
      while (at.size() <= i)
      {
        times.push_back(sample_times[at.size()] * T);
        at.emplace_back();
        space.assemble_matrices(times.back(), tau_n, at.back());
        ++time.n_spatial_assemblies;
        // all carry the first one's constrained diagonal: their combinations (weights
        // summing to 1) then carry it too
        constrained_diagonal(space.constraints(), at[0], at.back());
      }
      return at[i];
    };
    TimeInterpolation ti;
    for (unsigned int d = 1; d <= max_degree && ti.at_nodes.empty(); ++d)
    {
      sample(d);
      const std::vector<double> node_times(times.begin(), times.begin() + d + 1);
      bool exact = true;
      for (unsigned int c = d + 1; c < d + 3 && exact; ++c)
      {
        const SpatialMatrices &check = sample(c);
        exact = reproduces(at, node_times, times[c], check);
      }
      if (exact)
      {
        at.resize(d + 1);
        times.resize(d + 1);
        ti.at_nodes = std::move(at);
        ti.times = std::move(times);
      }
    }
    if (opt.transposed_only) // only the lift (solve, not transposed) reads A
      for (auto &node : ti.at_nodes)
        node.A.clear();
    it = interpolation.emplace(key, std::move(ti)).first;
  }
  return it->second.at_nodes.empty() ? nullptr : &it->second;
}

template <int dim>
void SlabOperator<dim>::matrices_at(double t, double tau_n, SpatialMatrices &m,
                                    bool mass_only)
{
  if (const auto *ti = time_nodes(tau_n))
  {
    if (mass_only)
      interpolate(ti->at_nodes, ti->times, t, m, {0});
    else
      interpolate(ti->at_nodes, ti->times, t, m);
    ++time.n_interpolated;
  }
  else
  {
    space.assemble_matrices(t, tau_n, m);
    ++time.n_spatial_assemblies;
  }
}

template const SlabOperator<2>::TimeInterpolation *SlabOperator<2>::time_nodes(double);
template void SlabOperator<2>::matrices_at(double, double, SpatialMatrices &, bool);
} // namespace anisodwr
