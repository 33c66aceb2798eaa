// Slab functions and slab functionals in W-local coefficients: evaluation, gathering
// from interleaved slab vectors, transformation and differences.
#include "adaptivity/cell_kernel.h"
#include "adaptivity/short_vectors.h"

#include "time/slab_vector.h"

namespace anisodwr
{
using namespace dealii;
namespace sv = short_vectors;

void SlabFunctional::reset(unsigned int n_points, unsigned int n)
{
  if (val.size() != n_points || jump.size() != n)
  {
    val.assign(n_points, Vector<double>(n));
    dt.assign(n_points, Vector<double>(n));
    jump.reinit(n);
    return;
  }
  for (auto &v : val)
    sv::zero(v);
  for (auto &v : dt)
    sv::zero(v);
  sv::zero(jump);
}

double apply(const SlabFunctional &F, const SlabFunction &v, bool jump_of_v)
{
  double s = 0;
  for (unsigned int m = 0; m < F.val.size(); ++m)
  {
    s += sv::dot(F.val[m], v.val[m]);
    if (v.dt.size())
      s += sv::dot(F.dt[m], v.dt[m]);
  }
  s += sv::dot(F.jump, v.plus);
  if (jump_of_v && v.minus.size())
    s -= sv::dot(F.jump, v.minus);
  return s;
}

/// W-local coefficients of temporal node k of an interleaved slab vector.
void gather(const Vector<double> &U, const std::vector<types::global_dof_index> &dofs,
            unsigned int m1, unsigned int k, const FullMatrix<double> &to_w,
            Vector<double> &out)
{
  const SlabLayout slab{m1};
  thread_local Vector<double> loc;
  loc.reinit(dofs.size(), true);
  for (unsigned int l = 0; l < dofs.size(); ++l)
    loc(l) = U(slab.index(dofs[l], k));
  out.reinit(to_w.m(), true);
  to_w.vmult(out, loc);
}

/// f = the slab function sum_k l_k(s) V_k from W-local nodal vectors V_k (f.minus is
/// left as it is; f's vectors are reused).
template <int dim>
void slab_function(const CellKernel<dim> &kernel, const TemporalBasis &basis, double tau,
                   const std::vector<Vector<double>> &V, SlabFunction &f)
{
  const unsigned int n = V[0].size(), n_points = kernel.n_points();
  f.val.resize(n_points);
  f.dt.resize(n_points);
  for (unsigned int m = 0; m < n_points; ++m)
  {
    Vector<double> &v = f.val[m], &d = f.dt[m];
    sv::zero(v, n);
    sv::zero(d, n);
    for (unsigned int k = 0; k < V.size(); ++k)
    {
      sv::add(v, kernel.values_at(m)[k], V[k]);
      sv::add(d, kernel.derivatives_at(m)[k] / tau, V[k]);
    }
  }
  sv::zero(f.plus, n);
  for (unsigned int k = 0; k < V.size(); ++k)
    sv::add(f.plus, basis.left_trace()[k], V[k]);
}

/// d = a (d's vectors are reused).
void assign(const SlabFunction &a, SlabFunction &d)
{
  const auto all =
      [](const std::vector<Vector<double>> &from, std::vector<Vector<double>> &to)
  {
    to.resize(from.size());
    for (std::size_t m = 0; m < from.size(); ++m)
      sv::copy(to[m], from[m]);
  };
  all(a.val, d.val);
  all(a.dt, d.dt);
  sv::copy(d.plus, a.plus);
  sv::copy(d.minus, a.minus);
}

/// d = a - b (d's vectors are reused).
void difference(const SlabFunction &a, const SlabFunction &b, SlabFunction &d)
{
  assign(a, d);
  for (unsigned int m = 0; m < d.val.size(); ++m)
  {
    sv::subtract(d.val[m], b.val[m]);
    if (d.dt.size())
      sv::subtract(d.dt[m], b.dt[m]);
  }
  sv::subtract(d.plus, b.plus);
  if (d.minus.size())
    sv::subtract(d.minus, b.minus);
}

template void slab_function<2>(const CellKernel<2> &, const TemporalBasis &, double,
                               const std::vector<Vector<double>> &, SlabFunction &);
} // namespace anisodwr
