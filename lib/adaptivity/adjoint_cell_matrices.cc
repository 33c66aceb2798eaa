// For coefficients constant in time, the adjoint form A(.)(z) and the SUPG derivative
// S'(., z) on a cell are cell matrices applied to z (CellKernel::adj_matrices).
#include "adaptivity/cell_kernel.h"

#include "space/weak_form.h"

namespace anisodwr
{
using namespace dealii;

template <int dim> void CellKernel<dim>::build_adjoint_matrices()
{
  const unsigned int nw = fe_w.n_dofs_per_cell(), nq = quad.size();
  for (auto &M : adj_matrices)
    M.reinit(nw, nw);
  for (unsigned int q = 0; q < nq; ++q)
  {
    const auto c = coefficients(q, 0.);
    const double jx = fv_p.JxW(q);
    for (unsigned int l = 0; l < nw; ++l)
    {
      const double phi = fv_w.shape_value(l, q);
      const Tensor<1, dim> &gphi = fv_w.shape_grad(l, q);
      const double op = weak_form::strong(c, phi, gphi, trace(fv_w.shape_hessian(l, q)));
      for (unsigned int j = 0; j < nw; ++j)
      {
        const double zj = fv_w.shape_value(j, q);
        const Tensor<1, dim> &gz = fv_w.shape_grad(j, q);
        const double test_s = weak_form::supg_test(1., c.b, gz); // per unit delta_K
        adj_matrices[0](l, j) += jx * weak_form::galerkin(c, phi, gphi, zj, gz);
        adj_matrices[1](l, j) += jx * phi * zj;
        adj_matrices[2](l, j) += jx * op * test_s;
        adj_matrices[3](l, j) += jx * phi * test_s;
      }
    }
  }
}

template void CellKernel<2>::build_adjoint_matrices();
} // namespace anisodwr
