// The localized forms of the estimator summed over all cells, for given global functions
// (LocalizedForms in estimator.h): what the localization tests compare with the global
// forms.
#include "adaptivity/cell_kernel.h"
#include "adaptivity/estimator.h"
#include "adaptivity/spatial_operators.h"

namespace anisodwr
{
using namespace dealii;

namespace
{
/// Runs `body(kernel, cell, to_w, other_dofs)` on every cell.
template <int dim, typename Body>
void for_cells(const Space<dim> &primal, const Space<dim> &other,
               const TemporalBasis &basis, Body body)
{
  const SpatialOperators<dim> ops(primal.dof_handler(), weight_degree(primal, other));
  const FullMatrix<double> to_w = ops.interpolation_from(other.finite_element());
  CellKernel<dim> kernel(primal, ops.weight_element(), basis, DataQuadrature{});
  std::vector<types::global_dof_index> idx(other.finite_element().n_dofs_per_cell());
  for (const auto &cell : primal.dof_handler().active_cell_iterators())
  {
    kernel.reinit(cell);
    typename DoFHandler<dim>::active_cell_iterator co(
        &primal.dof_handler().get_triangulation(), cell->level(), cell->index(),
        &other.dof_handler());
    co->get_dof_indices(idx);
    body(kernel, to_w, idx);
  }
}

/// The slab function of V on the cell; its W-local nodal vectors go to vk.
template <int dim>
SlabFunction
other_function(const CellKernel<dim> &kernel, const TemporalBasis &basis, double tau,
               const Vector<double> &V, const std::vector<types::global_dof_index> &idx,
               const FullMatrix<double> &to_w, std::vector<Vector<double>> &vk)
{
  vk.resize(basis.n_dofs());
  for (unsigned int k = 0; k < basis.n_dofs(); ++k)
    gather(V, idx, basis.n_dofs(), k, to_w, vk[k]);
  SlabFunction f;
  slab_function(kernel, basis, tau, vk, f);
  return f;
}
/// sum over cells of rho(u)(w) (supg == false) or S(u)(w), one value per slab.
template <int dim>
std::vector<double> primal_form(const Space<dim> &primal, const Space<dim> &other,
                                const TimeMesh &mesh, const TemporalBasis &basis,
                                const std::vector<Vector<double>> &U,
                                const std::vector<Vector<double>> &W, bool supg)
{
  std::vector<double> out(mesh.n_slabs(), 0.);
  for_cells(primal, other, basis,
            [&](const CellKernel<dim> &k, const FullMatrix<double> &to_w,
                const std::vector<types::global_dof_index> &idx)
            {
              SlabFunctional rho, S;
              for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
              {
                k.primal_functionals(mesh.start(n), mesh.tau(n), U[n],
                                     n ? &U[n - 1] : nullptr, rho, S);
                std::vector<Vector<double>> wk;
                out[n] += apply(
                    supg ? S : rho,
                    other_function(k, basis, mesh.tau(n), W[n], idx, to_w, wk), false);
              }
            });
  return out;
}
} // namespace

template <int dim>
std::vector<double>
LocalizedForms<dim>::primal_residual(const Space<dim> &primal, const Space<dim> &other,
                                     const TimeMesh &mesh, const TemporalBasis &basis,
                                     const std::vector<Vector<double>> &U,
                                     const std::vector<Vector<double>> &W)
{
  return primal_form(primal, other, mesh, basis, U, W, false);
}

template <int dim>
std::vector<double>
LocalizedForms<dim>::supg(const Space<dim> &primal, const Space<dim> &other,
                          const TimeMesh &mesh, const TemporalBasis &basis,
                          const std::vector<Vector<double>> &U,
                          const std::vector<Vector<double>> &Y)
{
  return primal_form(primal, other, mesh, basis, U, Y, true);
}

template <int dim>
std::vector<double> LocalizedForms<dim>::adjoint_form(
    const Space<dim> &primal, const Space<dim> &other, const TimeMesh &mesh,
    const TemporalBasis &basis, const std::vector<Vector<double>> &V,
    const std::vector<Vector<double>> &Zt, bool supg_derivative)
{
  std::vector<double> out(mesh.n_slabs(), 0.);
  const unsigned int m1 = basis.n_dofs();
  for_cells(primal, other, basis,
            [&](const CellKernel<dim> &k, const FullMatrix<double> &to_w,
                const std::vector<types::global_dof_index> &idx)
            {
              SlabFunctional A;
              for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
              {
                const double tau = mesh.tau(n);
                std::vector<Vector<double>> zk, vk;
                const SlabFunction z =
                    other_function(k, basis, tau, Zt[n], idx, to_w, zk);
                k.adjoint_functional(mesh.start(n), tau, zk, z, supg_derivative, A);
                SlabFunction v = other_function(k, basis, tau, V[n], idx, to_w, vk);
                if (n > 0)
                  gather(V[n - 1], idx, m1, m1 - 1, to_w, v.minus);
                out[n] += apply(A, v, true);
              }
            });
  return out;
}

template struct LocalizedForms<2>;
} // namespace anisodwr
