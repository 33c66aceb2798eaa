// For coefficients constant in time, the primal residual rho(u) and the SUPG form S(u),
// the adjoint form A(.)(z) and the SUPG derivative S'(., z) on a cell are cell matrices
// applied to cell coefficients (CellKernel::primal_matrices, adj_matrices); the face
// fluxes are matrices for every scene (CellKernel::own_flux, Piece::nb_flux).
#include "adaptivity/cell_kernel.h"
#include "adaptivity/short_vectors.h"

#include "space/weak_form.h"
#include "time/slab_vector.h"

#include <deal.II/base/tensor.h>

namespace anisodwr
{
using namespace dealii;
namespace sv = short_vectors;

template <int dim> void CellKernel<dim>::build_cell_matrices()
{
  // Every matrix is a sum over the quadrature points of products of two factors, one
  // per slot, formed once per point from weak_form's terms: X D Y^T with X, Y holding
  // the factors per shape function (rows) and point (columns), D = diag(JxW). The
  // products go to FullMatrix::mTmult (BLAS for the larger sizes).
  //   A:   galerkin(phi_l, z_j) = eps grad phi_l . grad z_j + transport(phi_l) z_j
  //   A_t: phi_l z_j;  S': strong(phi_l) s_j;  S'_t: phi_l s_j   (s = supg_test per
  //   unit delta_K)
  //   rho: -strong(u_k) phi_l, -u_k phi_l;  S: strong(u_k) s_l, u_k s_l
  //   the stabilization terms (Space::cell_diffusion): D_K grad phi_l . grad z_j and
  //   D_K grad phi_l . grad u_k (D_K symmetric)
  const unsigned int nw = fe_w.n_dofs_per_cell(), np = fe_p.n_dofs_per_cell(),
                     nq = quad.size();
  FullMatrix<double> phi(nw, nq), dphi(nw, nq), s(nw, nq), ds(nw, nq), dop(nw, nq),
      u(np, nq), lu(np, nq), grads(nw, (dim + 1) * nq), dgrads(nw, (dim + 1) * nq),
      pg(nw, dim * nq), dpg(nw, dim * nq), gu(np, dim * nq);
  for (unsigned int q = 0; q < nq; ++q)
  {
    const auto c = coefficients(q, 0.);
    const double jx = fv_p.JxW(q);
    for (unsigned int l = 0; l < nw; ++l)
    {
      const double p = fv_w.shape_value(l, q);
      const Tensor<1, dim> &gp = fv_w.shape_grad(l, q);
      phi(l, q) = p;
      dphi(l, q) = jx * p;
      s(l, q) = weak_form::supg_test(1., c.b, gp);
      ds(l, q) = jx * s(l, q);
      dop(l, q) = jx * weak_form::strong(c, p, gp, trace(fv_w.shape_hessian(l, q)));
      for (unsigned int d = 0; d < dim; ++d)
      {
        grads(l, d * nq + q) = gp[d];
        dgrads(l, d * nq + q) = jx * c.eps * gp[d];
      }
      grads(l, dim * nq + q) = p;
      dgrads(l, dim * nq + q) = jx * weak_form::transport(c, p, gp);
      // grad phi_l, and D_K grad phi_l with the weight
      const Tensor<1, dim> Dg = cw.D * gp;
      for (unsigned int d = 0; d < dim; ++d)
      {
        pg(l, d * nq + q) = gp[d];
        dpg(l, d * nq + q) = jx * Dg[d];
      }
    }
    for (unsigned int k = 0; k < np; ++k)
    {
      u(k, q) = fv_p.shape_value(k, q);
      lu(k, q) = weak_form::strong(c, u(k, q), fv_p.shape_grad(k, q),
                                   trace(fv_p.shape_hessian(k, q)));
      for (unsigned int d = 0; d < dim; ++d)
        gu(k, d * nq + q) = fv_p.shape_grad(k, q)[d];
    }
  }
  for (auto &M : adj_matrices)
    M.reinit(nw, nw);
  for (auto &M : primal_matrices)
    M.reinit(nw, np);
  dgrads.mTmult(adj_matrices[0], grads);
  dphi.mTmult(adj_matrices[1], phi);
  dop.mTmult(adj_matrices[2], s);
  dphi.mTmult(adj_matrices[3], s);
  dphi.mTmult(primal_matrices[0], lu);
  primal_matrices[0] *= -1.;
  dphi.mTmult(primal_matrices[1], u);
  primal_matrices[1] *= -1.;
  ds.mTmult(primal_matrices[2], lu);
  ds.mTmult(primal_matrices[3], u);
  if (cw.active)
  {
    dpg.mTmult(adj_matrices[4], pg);
    dpg.mTmult(primal_matrices[4], gu);
  }
  if (separable_load)
  {
    load_vectors_on(fv_load, load_rho, load_supg);
    if (data_error) // the same on the primal's rule (load_quadrature_error)
      load_vectors_on(fv_lo, lo_rho, lo_supg);
  }
}

template <int dim>
void CellKernel<dim>::load_vectors_on(const FEValues<dim> &fv,
                                      std::vector<Vector<double>> &rho,
                                      std::vector<Vector<double>> &supg) const
{
  const unsigned int nw = fe_w.n_dofs_per_cell();
  rho.assign(load_terms.size(), Vector<double>(nw));
  supg.assign(load_terms.size(), Vector<double>(nw));
  for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
  {
    const Point<dim> &x = fv.quadrature_point(q);
    const Tensor<1, dim> b = scene.convection(x, 0.);
    for (unsigned int j = 0; j < load_terms.size(); ++j)
    {
      const double jg = fv.JxW(q) * load_terms[j].g(x);
      for (unsigned int l = 0; l < nw; ++l)
      {
        rho[j](l) += jg * fv.shape_value(l, q);
        supg[j](l) += jg * weak_form::supg_test(1., b, fv.shape_grad(l, q));
      }
    }
  }
}

template <int dim>
void CellKernel<dim>::add_cell_terms_by_matrices(unsigned int m, double t, double wt,
                                                 double delta, double tau,
                                                 SlabFunctional &rho,
                                                 SlabFunctional &supg) const
{
  const unsigned int nw = fe_w.n_dofs_per_cell();
  for (unsigned int k = 0; k < node_terms.size(); ++k)
  {
    const auto &terms = node_terms[k];
    const double v = wt * ell[m][k], d = wt * dell[m][k] / tau;
    sv::add(rho.val[m], v, terms[1]);
    sv::add(rho.val[m], d, terms[2]);
    sv::add(supg.val[m], delta * v, terms[3]);
    sv::add(supg.val[m], delta * d, terms[4]);
    if (cw.active)
      sv::add(supg.val[m], v, terms[5]);
  }
  if (separable_load)
  {
    const std::vector<double> &a = load_factors_at(t);
    for (unsigned int j = 0; j < load_terms.size(); ++j)
    {
      sv::add(rho.val[m], wt * a[j], load_rho[j]);
      sv::add(supg.val[m], -wt * delta * a[j], load_supg[j]);
    }
    return;
  }
  for (unsigned int q = 0; q < quad.size(); ++q)
  {
    const double f = f_at[m][q] = scene.rhs(fv_p.quadrature_point(q), t);
    const double jf = fv_p.JxW(q) * wt * f;
    for (unsigned int l = 0; l < nw; ++l)
    {
      rho.val[m](l) += jf * fv_w.shape_value(l, q);
      supg.val[m](l) -=
          jf * weak_form::supg_test(delta, coefficients_at_q[q].b, fv_w.shape_grad(l, q));
    }
  }
}

template <int dim>
void CellKernel<dim>::add_temporal_jump_by_matrices(double delta,
                                                    const Vector<double> &Un,
                                                    const Vector<double> *Uprev,
                                                    SlabFunctional &rho,
                                                    SlabFunctional &supg) const
{
  // the temporal jump u^+ - u^- at t_{n-1} (u^- = u_0 on the first slab)
  const unsigned int np = fe_p.n_dofs_per_cell(), nw = fe_w.n_dofs_per_cell();
  Vector<double> &d = scratch[0];
  d.reinit(np, true);
  combine(Un, idx, basis.left_trace(), 1., d);
  if (Uprev)
    for (unsigned int l = 0; l < np; ++l)
      d(l) -= (*Uprev)(SlabLayout{basis.n_dofs()}.last(idx[l]));
  sv::add_vmult(rho.jump, 1., primal_matrices[1], d);
  sv::add_vmult(supg.jump, delta, primal_matrices[3], d);
  if (!Uprev) // u_0 on the data rule (fv_load)
    for (unsigned int q = 0; q < fv_load.n_quadrature_points; ++q)
    {
      const Point<dim> &x = fv_load.quadrature_point(q);
      const double ju = fv_load.JxW(q) * scene.initial_value(x);
      const Tensor<1, dim> b = scene.convection(x, 0.);
      for (unsigned int l = 0; l < nw; ++l)
      {
        rho.jump(l) += ju * fv_load.shape_value(l, q);
        supg.jump(l) -= ju * weak_form::supg_test(delta, b, fv_load.shape_grad(l, q));
      }
    }
}

template void CellKernel<2>::build_cell_matrices();
template void CellKernel<2>::load_vectors_on(const FEValues<2> &,
                                             std::vector<Vector<double>> &,
                                             std::vector<Vector<double>> &) const;
template void CellKernel<2>::add_cell_terms_by_matrices(unsigned int, double, double,
                                                        double, double, SlabFunctional &,
                                                        SlabFunctional &) const;
template void CellKernel<2>::add_temporal_jump_by_matrices(double, const Vector<double> &,
                                                           const Vector<double> *,
                                                           SlabFunctional &,
                                                           SlabFunctional &) const;
} // namespace anisodwr
