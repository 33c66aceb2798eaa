// Slab functions and slab functionals in W-local coefficients: evaluation, gathering
// from interleaved slab vectors, transformation and differences.
#include "adaptivity/cell_kernel.h"

#include "time/slab_vector.h"

namespace anisodwr
{
using namespace dealii;

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
    v = 0.;
  for (auto &v : dt)
    v = 0.;
  jump = 0.;
}

double apply(const SlabFunctional &F, const SlabFunction &v, bool jump_of_v)
{
  double s = 0;
  for (unsigned int m = 0; m < F.val.size(); ++m)
  {
    s += F.val[m] * v.val[m];
    if (v.dt.size())
      s += F.dt[m] * v.dt[m];
  }
  s += F.jump * v.plus;
  if (jump_of_v && v.minus.size())
    s -= F.jump * v.minus;
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
    v.reinit(n);
    d.reinit(n);
    for (unsigned int k = 0; k < V.size(); ++k)
    {
      v.add(kernel.values_at(m)[k], V[k]);
      d.add(kernel.derivatives_at(m)[k] / tau, V[k]);
    }
  }
  f.plus.reinit(n);
  for (unsigned int k = 0; k < V.size(); ++k)
    f.plus.add(basis.left_trace()[k], V[k]);
}

void transform(const FullMatrix<double> &R, SlabFunction &f)
{
  auto one = [&](Vector<double> &v)
  {
    if (!v.size())
      return;
    thread_local Vector<double> t;
    t.reinit(v.size(), true);
    R.vmult(t, v);
    v = t;
  };
  for (auto &v : f.val)
    one(v);
  for (auto &v : f.dt)
    one(v);
  one(f.plus);
  one(f.minus);
}

/// d = a - b (d's vectors are reused).
void difference(const SlabFunction &a, const SlabFunction &b, SlabFunction &d)
{
  d = a;
  for (unsigned int m = 0; m < d.val.size(); ++m)
  {
    d.val[m] -= b.val[m];
    if (d.dt.size())
      d.dt[m] -= b.dt[m];
  }
  d.plus -= b.plus;
  if (d.minus.size())
    d.minus -= b.minus;
}

template void slab_function<2>(const CellKernel<2> &, const TemporalBasis &, double,
                               const std::vector<Vector<double>> &, SlabFunction &);
} // namespace anisodwr
