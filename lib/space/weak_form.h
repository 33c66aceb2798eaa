#pragma once
// The convection-diffusion-reaction + SUPG weak form, pointwise (doc/method.md §2-3).
// Every integrand of the method is built from these terms: the spatial matrices and
// loads (space.cc), the estimator's residuals and adjoint forms
// (adaptivity/cell_functionals.cc, adaptivity/cell_matrices.cc). A stabilization term
// of the form (D_K grad u, grad v)_K (crosswind diffusion, isotropic shock capturing) is
// an entry of stabilization_terms.cc and reaches every integrand through
// cell_diffusion() below.
//
// With L u = -eps Lap u + b.grad u + alpha u the discrete scheme on a slab reads
//   (d_t u, v + delta_K b.grad v) + a(u)(v) + sum_K delta_K (L u, b.grad v)_K
//     + ([u], v + delta_K b.grad v) = (f, v + delta_K b.grad v),
//   a(u)(v) = (eps grad u, grad v) + (b.grad u + alpha u, v).
#include "scene/scene.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

namespace anisodwr::weak_form
{
/// eps, b and alpha at one point and time.
template <int dim> struct Coefficients
{
  double eps;
  dealii::Tensor<1, dim> b;
  double alpha;
};

/// The coefficients of `scene` at (x, t).
template <int dim>
Coefficients<dim> coefficients(const Scene<dim> &scene, const dealii::Point<dim> &x, double t)
{
  return {scene.epsilon, scene.convection(x, t), scene.reaction(x, t)};
}

/// The transport part b.grad u + alpha u.
template <int dim>
double transport(const Coefficients<dim> &c, double u, const dealii::Tensor<1, dim> &grad_u)
{
  return c.b * grad_u + c.alpha * u;
}

/// The integrand of a(u)(v) = (eps grad u, grad v) + (b.grad u + alpha u, v).
template <int dim>
double galerkin(const Coefficients<dim> &c, double u, const dealii::Tensor<1, dim> &grad_u,
                double v, const dealii::Tensor<1, dim> &grad_v)
{
  return c.eps * (grad_u * grad_v) + transport(c, u, grad_u) * v;
}

/// The strong operator L u = -eps Lap u + b.grad u + alpha u.
template <int dim>
double strong(const Coefficients<dim> &c, double u, const dealii::Tensor<1, dim> &grad_u,
              double laplacian_u)
{
  return -c.eps * laplacian_u + transport(c, u, grad_u);
}

/// The SUPG modification of a test function v: delta_K b.grad v (the test function of
/// the residual terms is v + supg_test).
template <int dim>
double supg_test(double delta, const dealii::Tensor<1, dim> &b,
                 const dealii::Tensor<1, dim> &grad_v)
{
  return delta * (b * grad_v);
}

/// The integrand (D grad u, grad v) of the stabilization terms beside SUPG
/// (stabilization_terms.h; D = D_K of Space::cell_diffusion, constant on the cell). Not
/// consistent: the scheme's error gains O(|D_K|) where a term acts; the estimator counts
/// it in S(u).
template <int dim>
double cell_diffusion(const dealii::Tensor<2, dim> &D, const dealii::Tensor<1, dim> &grad_u,
                      const dealii::Tensor<1, dim> &grad_v)
{
  return grad_v * (D * grad_u);
}

/// The strong residual f - d_t u - L u.
template <int dim>
double residual(const Coefficients<dim> &c, double f, double dt_u, double u,
                const dealii::Tensor<1, dim> &grad_u, double laplacian_u)
{
  return f - dt_u - strong(c, u, grad_u, laplacian_u);
}
} // namespace anisodwr::weak_form
