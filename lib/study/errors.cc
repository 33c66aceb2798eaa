#include "study/errors.h"

#include "time/slab_vector.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>

namespace anisodwr
{
using namespace dealii;

// One pass over the cells per slab evaluates u_h at all temporal points (the r+2 Gauss
// points and t_n^-) from the same shape values, instead of one integrate_difference
// per temporal point; spatial rule QGauss(p+3), as before.
template <int dim>
ErrorNorms compute_errors(const Space<dim> &space, const TimeMesh &mesh,
                          const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  ErrorNorms e;
  const ExactSolution<dim> &exact = *space.scene.exact();
  const unsigned int m = basis.n_dofs();
  std::vector<double> sq, wq;
  gauss_rule(m + 1, sq, wq);
  // temporal combinations: the Gauss points, then the right end t_n^-
  std::vector<std::vector<double>> at;
  for (const double s : sq)
    at.push_back(basis.values(s));
  at.push_back(basis.right_trace());
  const unsigned int n_times = at.size();

  const QGauss<dim> quad(space.degree() + 3);
  FEValues<dim> fv(space.mapping(), space.finite_element(), quad,
                   update_values | update_quadrature_points | update_JxW_values);
  const unsigned int n_local = space.finite_element().n_dofs_per_cell();
  std::vector<types::global_dof_index> idx(n_local);
  std::vector<double> coef(n_local * n_times), sq_err(n_times);
  double sum = 0;
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    std::fill(sq_err.begin(), sq_err.end(), 0.);
    std::vector<double> times(n_times);
    for (unsigned int p = 0; p < sq.size(); ++p)
      times[p] = mesh.start(n) + sq[p] * mesh.tau(n);
    times.back() = mesh.t[n + 1];
    for (const auto &cell : space.dof_handler().active_cell_iterators())
    {
      fv.reinit(cell);
      cell->get_dof_indices(idx);
      for (unsigned int i = 0; i < n_local; ++i)
        for (unsigned int p = 0; p < n_times; ++p)
        {
          double c = 0;
          for (unsigned int k = 0; k < m; ++k)
            c += at[p][k] * U[n](SlabLayout{m}.index(idx[i], k));
          coef[p * n_local + i] = c;
        }
      for (unsigned int q = 0; q < quad.size(); ++q)
      {
        const Point<dim> &x = fv.quadrature_point(q);
        for (unsigned int p = 0; p < n_times; ++p)
        {
          double uh = 0;
          for (unsigned int i = 0; i < n_local; ++i)
            uh += coef[p * n_local + i] * fv.shape_value(i, q);
          const double d = exact.value(x, times[p]) - uh;
          sq_err[p] += d * d * fv.JxW(q);
        }
      }
    }
    const double en = std::sqrt(sq_err.back());
    e.nodal = std::max(e.nodal, en);
    if (n + 1 == mesh.n_slabs())
      e.L2_T = en;
    for (unsigned int p = 0; p < sq.size(); ++p)
      sum += mesh.tau(n) * wq[p] * sq_err[p];
  }
  e.L2L2 = std::sqrt(sum);
  return e;
}

template ErrorNorms compute_errors<2>(const Space<2> &, const TimeMesh &, const TemporalBasis &,
                                      const std::vector<Vector<double>> &);
} // namespace anisodwr
