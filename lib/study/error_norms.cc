#include "study/error_norms.h"

#include "time/slab_vector.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>

namespace anisodwr
{
using namespace dealii;

// One pass over the cells: the shape values of a cell serve every slab and every
// temporal point (the r+2 Gauss points and t_n^-); spatial rule QGauss(p+3). For a
// separable exact solution T(t) S(x), S is evaluated once per quadrature point.
template <int dim>
ErrorNorms compute_errors(const Space<dim> &space, const TimeMesh &mesh,
                          const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  ErrorNorms e;
  const ExactSolution<dim> &exact = *space.scene.exact();
  const bool separable = exact.separable();
  const unsigned int m = basis.n_dofs();
  const SlabLayout layout{m};
  std::vector<double> sq, wq;
  gauss_rule(m + 1, sq, wq);
  // temporal combinations: the Gauss points, then the right end t_n^-
  std::vector<std::vector<double>> at;
  for (const double s : sq)
    at.push_back(basis.values(s));
  at.push_back(basis.right_trace());
  const unsigned int n_times = at.size(), n_slabs = mesh.n_slabs();
  std::vector<double> times(n_slabs * n_times), T(n_slabs * n_times);
  for (unsigned int n = 0; n < n_slabs; ++n)
  {
    for (unsigned int p = 0; p < sq.size(); ++p)
      times[n * n_times + p] = mesh.start(n) + sq[p] * mesh.tau(n);
    times[n * n_times + n_times - 1] = mesh.t[n + 1];
  }
  if (separable)
    for (std::size_t j = 0; j < times.size(); ++j)
      T[j] = exact.time_factor(times[j], 0);

  const QGauss<dim> quad(space.degree() + 3);
  FEValues<dim> fv(space.mapping(), space.finite_element(), quad,
                   update_values | update_quadrature_points | update_JxW_values);
  const unsigned int n_local = space.finite_element().n_dofs_per_cell();
  std::vector<types::global_dof_index> idx(n_local);
  std::vector<double> coef(n_local * n_times), S(quad.size());
  std::vector<double> sq_err(n_slabs * n_times, 0.);
  for (const auto &cell : space.dof_handler().active_cell_iterators())
  {
    fv.reinit(cell);
    cell->get_dof_indices(idx);
    if (separable)
      for (unsigned int q = 0; q < quad.size(); ++q)
        S[q] = exact.space_value(fv.quadrature_point(q));
    for (unsigned int n = 0; n < n_slabs; ++n)
    {
      for (unsigned int i = 0; i < n_local; ++i)
        for (unsigned int p = 0; p < n_times; ++p)
        {
          double c = 0;
          for (unsigned int k = 0; k < m; ++k)
            c += at[p][k] * U[n](layout.index(idx[i], k));
          coef[p * n_local + i] = c;
        }
      double *err = &sq_err[n * n_times];
      for (unsigned int q = 0; q < quad.size(); ++q)
        for (unsigned int p = 0; p < n_times; ++p)
        {
          double uh = 0;
          for (unsigned int i = 0; i < n_local; ++i)
            uh += coef[p * n_local + i] * fv.shape_value(i, q);
          const double u = separable ? S[q] * T[n * n_times + p]
                                     : exact.value(fv.quadrature_point(q), times[n * n_times + p]);
          const double d = u - uh;
          err[p] += d * d * fv.JxW(q);
        }
    }
  }
  double sum = 0;
  for (unsigned int n = 0; n < n_slabs; ++n)
  {
    const double en = std::sqrt(sq_err[n * n_times + n_times - 1]);
    e.nodal = std::max(e.nodal, en);
    if (n + 1 == n_slabs)
      e.L2_T = en;
    for (unsigned int p = 0; p < sq.size(); ++p)
      sum += mesh.tau(n) * wq[p] * sq_err[n * n_times + p];
  }
  e.L2L2 = std::sqrt(sum);
  return e;
}

template ErrorNorms compute_errors<2>(const Space<2> &, const TimeMesh &, const TemporalBasis &,
                                      const std::vector<Vector<double>> &);
} // namespace anisodwr
