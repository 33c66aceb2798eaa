#include "space/crosswind_scale.h"
#include "space/weak_form.h"

#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>

namespace anisodwr
{
using namespace dealii;

template <int dim>
std::vector<double>
crosswind_scale(const Space<dim> &space, const std::vector<double> &times,
                const std::vector<Vector<double>> &ends, double exponent)
{
  const Scene<dim> &scene = space.scene;
  const DoFHandler<dim> &dofs = space.dof_handler();
  const QGauss<dim> quad(space.degree() + 1);
  const unsigned int nq = quad.size();
  const std::size_t n_cells = dofs.get_triangulation().n_active_cells();
  std::vector<double> residual(n_cells, 0.), transport(n_cells, 0.), scale(n_cells, 0.),
      b_cell(n_cells, 0.);
  // |b| |grad u_h| below 1e-10 |b|_max max|u_h| / (the domain's size) is round-off (u_h
  // constant)
  double u_max = 0.;
  for (const auto &v : ends)
    u_max = std::max(u_max, v.linfty_norm());
  std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
  for (const auto &cell : dofs.active_cell_iterators())
    cells.push_back(cell);
  // Each cell's sums are its own, and the cells are cut into fixed chunks of 256 that
  // the threads (MultithreadInfo::n_threads()) take in any order. Each chunk starts its
  // own FEValues: FEValues reuses the mapping's data between similar consecutive cells,
  // which changes the sums in the last digits, so a chunk must not depend on which cell
  // a thread visited before it. The factors are then the same on every run (one thread
  // gives them up to round-off, 4e-15: test CrosswindScale.SameInAnyThreadOrder).
  const std::size_t chunk = 256, n_chunks = (cells.size() + chunk - 1) / chunk;
  const auto chunk_range = [&](const std::size_t first, const std::size_t last)
  {
    std::vector<double> u(nq), u_prev(nq), lap(nq);
    std::vector<Tensor<1, dim>> grad(nq);
    for (std::size_t piece = first; piece < last; ++piece)
    {
      FEValues<dim> fv(space.mapping(), space.finite_element(), quad,
                       update_values | update_gradients | update_hessians |
                           update_quadrature_points | update_JxW_values);
      const std::size_t begin = piece * chunk, end = std::min(cells.size(), begin + chunk);
      for (std::size_t i = begin; i < end; ++i)
      {
        fv.reinit(cells[i]);
        for (unsigned int q = 0; q < nq; ++q)
          u_prev[q] = scene.initial_value(fv.quadrature_point(q));
        const unsigned int k = cells[i]->active_cell_index();
        for (std::size_t n = 0; n < ends.size(); ++n)
        {
          const double t = times[n + 1], tau = times[n + 1] - times[n];
          fv.get_function_values(ends[n], u);
          fv.get_function_gradients(ends[n], grad);
          fv.get_function_laplacians(ends[n], lap);
          for (unsigned int q = 0; q < nq; ++q)
          {
            const Point<dim> &x = fv.quadrature_point(q);
            const auto c = weak_form::coefficients(scene, x, t);
            const double r = weak_form::residual(
                c, scene.rhs(x, t), (u[q] - u_prev[q]) / tau, u[q], grad[q], lap[q]);
            residual[k] += tau * std::abs(r) * fv.JxW(q);
            b_cell[k] = std::max(b_cell[k], c.b.norm());
            transport[k] += tau * c.b.norm() * grad[q].norm() * fv.JxW(q);
          }
          std::swap(u, u_prev);
        }
      }
    }
  };
  parallel::apply_to_subranges(std::size_t(0), n_chunks, chunk_range, 1);
  const double b_max = *std::max_element(b_cell.begin(), b_cell.end());
  // (the bounding box's diagonal as the domain's size: GridTools::diameter compares all
  // pairs of boundary vertices, 0.5 s at 4e4 cells along Hemker's refined walls)
  const auto box = GridTools::compute_bounding_box(dofs.get_triangulation());
  const double floor =
      1e-10 * b_max * u_max * (times.back() - times.front()) /
      box.get_boundary_points().first.distance(box.get_boundary_points().second);
  for (const auto &cell : dofs.active_cell_iterators())
  {
    const unsigned int k = cell->active_cell_index();
    if (transport[k] > floor * cell->measure())
      scale[k] = std::pow(std::min(1., residual[k] / transport[k]), exponent);
  }
  return scale;
}

template std::vector<double> crosswind_scale<2>(const Space<2> &,
                                                const std::vector<double> &,
                                                const std::vector<Vector<double>> &,
                                                double);
} // namespace anisodwr
