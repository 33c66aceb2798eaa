// The functionals of the estimator on one cell and one slab: the primal residual rho(u)
// (cell residual, face fluxes, temporal jump), the SUPG form S(u), the adjoint form
// A(.)(z) and S'(., z), and J'.
#include "adaptivity/cell_kernel.h"
#include "adaptivity/short_vectors.h"

#include "space/weak_form.h"
#include "time/slab_vector.h"

#include <algorithm>
#include <array>

namespace anisodwr
{
using namespace dealii;
namespace sv = short_vectors;

template <int dim>
template <typename Out>
void CellKernel<dim>::rhs_at_points(double t0, double tau, const FEValues<dim> &fv,
                                    const Out &out) const
{
  std::vector<double> &times = times_scratch;
  times.resize(g.size());
  for (unsigned int m = 0; m < g.size(); ++m)
    times[m] = t0 + g[m] * tau;
  double values[16];
  AssertThrow(g.size() <= 16, ExcMessage("rhs_at_points: at most 16 temporal points"));
  for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
  {
    scene.rhs_at_times(fv.quadrature_point(q), times, values);
    for (unsigned int m = 0; m < g.size(); ++m)
      out(m, q) = values[m];
  }
}

template <int dim>
void CellKernel<dim>::primal_functionals(double t0, double tau, const Vector<double> &Un,
                                         const Vector<double> *Uprev, SlabFunctional &rho,
                                         SlabFunctional &supg) const
{
  const unsigned int nw = fe_w.n_dofs_per_cell(), np = fe_p.n_dofs_per_cell();
  const unsigned int nq = quad.size();
  rho.reset(g.size(), nw);
  supg.reset(g.size(), nw);
  const double delta = primal.bounded_delta(delta_h, tau);
  Vector<double> &c = scratch[0], &ct = scratch[1];
  c.reinit(np, true);
  ct.reinit(np, true);
  // the matrices act on u's nodal coefficients, once per temporal node (not per point)
  nodal_products(Un);
  if (!constant_coefficients) // f at every point, all temporal points at once
    rhs_at_points(t0, tau, fv_p, [this](unsigned int m, unsigned int q) -> double &
                  { return f_at[m][q]; });
  for (unsigned int m = 0; m < g.size(); ++m)
  {
    const double t = t0 + g[m] * tau, wt = tau * omega[m];
    add_face_terms(m, t, wt, rho);
    if (constant_coefficients)
    {
      add_cell_terms_by_matrices(m, t, wt, delta, tau, rho, supg);
      continue;
    }
    combine(Un, idx, ell[m], 1., c);
    combine(Un, idx, dell[m], 1. / tau, ct);
    // (coefficients that depend on t: the load is not separable, Scene::separable_rhs)
    for (unsigned int q = 0; q < nq; ++q)
    {
      double uh = 0, ut = 0, lap = 0;
      Tensor<1, dim> grad;
      for (unsigned int l = 0; l < np; ++l)
      {
        uh += c(l) * fv_p.shape_value(l, q);
        ut += ct(l) * fv_p.shape_value(l, q);
        grad += c(l) * fv_p.shape_grad(l, q);
        lap += c(l) * trace(fv_p.shape_hessian(l, q));
      }
      const auto cf = coefficients(q, t);
      const double f = f_at[m][q];
      const double R = weak_form::residual(cf, f, ut, uh, grad, lap);
      const double jx = fv_p.JxW(q) * wt;
      for (unsigned int l = 0; l < nw; ++l)
      {
        const Tensor<1, dim> &gw = fv_w.shape_grad(l, q);
        rho.val[m](l) += jx * R * fv_w.shape_value(l, q);
        supg.val[m](l) +=
            jx * (cw.form(grad, gw) - R * weak_form::supg_test(delta, cf.b, gw));
      }
    }
  }
  if (constant_coefficients)
    add_temporal_jump_by_matrices(delta, Un, Uprev, rho, supg);
  else
    add_temporal_jump(t0, delta, Un, Uprev, rho, supg);
}

template <int dim>
void CellKernel<dim>::load_quadrature_error(double t0, double tau, bool first_slab,
                                            SlabFunctional &D) const
{
  const unsigned int nw = fe_w.n_dofs_per_cell();
  D.reset(g.size(), nw);
  const double delta = primal.bounded_delta(delta_h, tau);
  // out += sign (data, w + delta b.grad w) on the rule of fv (W's shapes; the weights
  // from geo); data(q) and b(q) at its points
  const auto add = [&](const FEValues<dim> &fv, const FEValues<dim> &geo, double sign,
                       const auto &data, const auto &b, Vector<double> &out)
  {
    for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
    {
      const double jd = sign * geo.JxW(q) * data(q);
      if (jd == 0.)
        continue;
      const Tensor<1, dim> bq = b(q);
      for (unsigned int l = 0; l < nw; ++l)
        out(l) += jd * (fv.shape_value(l, q) +
                        weak_form::supg_test(delta, bq, fv.shape_grad(l, q)));
    }
  };
  const auto b_lo = [&](double t)
  {
    return [&, t](unsigned int q)
    { return scene.convection(fv_lo.quadrature_point(q), t); };
  };
  // f on the low-order rule at every temporal point (after primal_functionals: f_at
  // holds f on the cell rule)
  std::vector<double> &f_lo = f_scratch;
  if (!separable_load)
  {
    f_lo.resize(g.size() * fv_lo.n_quadrature_points);
    rhs_at_points(t0, tau, fv_lo, [&](unsigned int m, unsigned int q) -> double &
                  { return f_lo[m * fv_lo.n_quadrature_points + q]; });
  }
  for (unsigned int m = 0; m < g.size(); ++m)
  {
    const double t = t0 + g[m] * tau, wt = tau * omega[m];
    if (separable_load) // the rules' vectors, formed once per cell
    {
      const std::vector<double> &a = load_factors_at(t);
      for (unsigned int j = 0; j < a.size(); ++j)
      {
        sv::add(D.val[m], wt * a[j], load_rho[j]);
        sv::add(D.val[m], -wt * a[j], lo_rho[j]);
        sv::add(D.val[m], wt * delta * a[j], load_supg[j]);
        sv::add(D.val[m], -wt * delta * a[j], lo_supg[j]);
      }
      continue;
    }
    add(
        fv_w, fv_p, wt, [&](unsigned int q) { return f_at[m][q]; },
        [&](unsigned int q) { return coefficients(q, t).b; }, D.val[m]);
    add(
        fv_lo, fv_lo, -wt,
        [&](unsigned int q) { return f_lo[m * fv_lo.n_quadrature_points + q]; }, b_lo(t),
        D.val[m]);
  }
  if (!first_slab)
    return;
  // u_0 on the rule the primal residual's jump takes it (fv_load with coefficients
  // constant in time, else the cell rule)
  const auto u0_on = [&](const FEValues<dim> &fv)
  {
    return [this, fv = &fv](unsigned int q)
    { return scene.initial_value(fv->quadrature_point(q)); };
  };
  if (constant_coefficients)
    add(
        fv_load, fv_load, 1., u0_on(fv_load),
        [&](unsigned int q) { return scene.convection(fv_load.quadrature_point(q), t0); },
        D.jump);
  else
    add(
        fv_w, fv_p, 1., u0_on(fv_p),
        [&](unsigned int q) { return coefficients(q, t0).b; }, D.jump);
  add(fv_lo, fv_lo, -1., u0_on(fv_lo), b_lo(t0), D.jump);
}

template <int dim>
bool CellKernel<dim>::dirichlet_data_functionals(
    double t0, double tau, const Vector<double> &Un,
    std::array<SlabFunctional, dim> &data) const
{
  if (std::none_of(pieces.begin(), pieces.end(),
                   [](const Piece &pc) { return pc.kind == 2; }))
    return false;
  const unsigned int nw = fe_w.n_dofs_per_cell(), np = fe_p.n_dofs_per_cell();
  for (auto &d : data)
    d.reset(g.size(), nw);
  Vector<double> &c = scratch[0];
  c.reinit(np, true);
  // g at the slab's temporal nodes, where u_h takes it (slab/slab_operator.cc): the
  // mismatch below is g_tau - u_h with g_tau = sum_k g(t_k) l_k, the spatial part only.
  // The temporal part g - g_tau is the primal's temporal error on Gamma_D, which eta_tau
  // carries; weighed here as well it was counted twice (doc/method.md §8).
  const auto &s = basis.nodes();
  std::vector<double> &g_nodes = boundary_scratch;
  g_nodes.clear();
  for (const auto &pc : pieces)
    if (pc.kind == 2)
      for (unsigned int q = 0; q < pc.JxW.size(); ++q)
        for (const double sk : s)
          g_nodes.push_back(scene.boundary_value(pc.x[q], t0 + sk * tau, pc.id));
  for (unsigned int m = 0; m < g.size(); ++m)
  {
    const double wt = tau * omega[m];
    combine(Un, idx, ell[m], 1., c); // u at the Gauss point, once for all faces
    auto gk = g_nodes.cbegin();
    for (const auto &pc : pieces)
      if (pc.kind == 2)
        for (unsigned int q = 0; q < pc.JxW.size(); ++q)
        {
          double uh = 0, g_tau = 0;
          for (unsigned int l = 0; l < np; ++l)
            uh += c(l) * pc.u_values(l, q);
          for (unsigned int k = 0; k < s.size(); ++k, ++gk)
            g_tau += ell[m][k] * *gk;
          const double mismatch = g_tau - uh;
          const double a = -wt * pc.JxW[q] * scene.epsilon * mismatch;
          if (a != 0)
            for (unsigned int l = 0; l < nw; ++l)
              data[pc.tangential].val[m](l) += a * pc.dn_w(l, q);
        }
  }
  return true;
}

template <int dim> void CellKernel<dim>::nodal_products(const Vector<double> &Un) const
{
  const unsigned int np = fe_p.n_dofs_per_cell(), m1 = basis.n_dofs();
  const SlabLayout slab{m1};
  Vector<double> &c = scratch[2];
  c.reinit(np, true);
  node_terms.resize(m1);
  for (unsigned int k = 0; k < m1; ++k)
  {
    auto &terms = node_terms[k];
    for (unsigned int l = 0; l < np; ++l)
      c(l) = Un(slab.index(idx[l], k));
    sv::vmult(terms[0], own_flux, c);
    // (the stabilization terms' matrix [4] only where a term acts on the cell)
    const unsigned int n_matrices = constant_coefficients ? (cw.active ? 5 : 4) : 0;
    for (unsigned int i = 0; i < n_matrices; ++i)
      sv::vmult(terms[i + 1], primal_matrices[i], c);
    for (const auto &pc : pieces)
      if (pc.kind == 0)
      {
        for (unsigned int l = 0; l < np; ++l)
          c(l) = Un(slab.index(pc.nb_dofs[l], k));
        sv::add_vmult(terms[0], 1., pc.nb_flux, c);
      }
  }
}

template <int dim>
void CellKernel<dim>::add_face_terms(unsigned int m, double t, double wt,
                                     SlabFunctional &rho) const
{
  const unsigned int nw = fe_w.n_dofs_per_cell();
  for (unsigned int k = 0; k < node_terms.size(); ++k)
    sv::add(rho.val[m], wt * ell[m][k], node_terms[k][0]);
  for (const auto &pc : pieces)
    if (pc.kind == 1) // the Neumann data
      for (unsigned int q = 0; q < pc.JxW.size(); ++q)
      {
        const double data = scene.boundary_flux(pc.x[q], pc.normal[q], t, pc.id);
        for (unsigned int l = 0; l < nw; ++l)
          rho.val[m](l) += wt * data * pc.JxW[q] * pc.w(l, q);
      }
}

template <int dim>
void CellKernel<dim>::add_temporal_jump(double t0, double delta, const Vector<double> &Un,
                                        const Vector<double> *Uprev, SlabFunctional &rho,
                                        SlabFunctional &supg) const
{
  const unsigned int nw = fe_w.n_dofs_per_cell(), np = fe_p.n_dofs_per_cell();
  const unsigned int m1 = basis.n_dofs(), nq = quad.size();
  // temporal jump at t_{n-1}: u^+ - u^-
  Vector<double> &cp = scratch[0], &cm = scratch[1];
  cp.reinit(np, true);
  cm.reinit(np);
  combine(Un, idx, basis.left_trace(), 1., cp);
  if (Uprev)
    for (unsigned int l = 0; l < np; ++l)
      cm(l) = (*Uprev)(SlabLayout{m1}.last(idx[l]));
  for (unsigned int q = 0; q < nq; ++q)
  {
    const Point<dim> &x = fv_p.quadrature_point(q);
    double jump = Uprev ? 0. : -scene.initial_value(x);
    for (unsigned int l = 0; l < np; ++l)
      jump += (cp(l) - cm(l)) * fv_p.shape_value(l, q);
    const Tensor<1, dim> b = coefficients(q, t0).b;
    for (unsigned int l = 0; l < nw; ++l)
    {
      rho.jump(l) -= fv_p.JxW(q) * jump * fv_w.shape_value(l, q);
      supg.jump(l) +=
          fv_p.JxW(q) * jump * weak_form::supg_test(delta, b, fv_w.shape_grad(l, q));
    }
  }
}

template <int dim>
void CellKernel<dim>::adjoint_functional(double t0, double tau,
                                         const std::vector<Vector<double>> &nodal,
                                         const SlabFunction &zt, bool supg,
                                         SlabFunctional &A) const
{
  adjoint_functionals(t0, tau, {{&nodal, &zt, supg, &A}});
}

template <int dim>
void CellKernel<dim>::adjoint_functionals(double t0, double tau,
                                          std::initializer_list<AdjointRequest> requests) const
{
  const unsigned int nw = fe_w.n_dofs_per_cell(), nq = quad.size();
  constexpr unsigned int max_requests = 3;
  const unsigned int R = requests.size();
  AssertThrow(R <= max_requests, ExcMessage("adjoint_functionals: at most 3 requests"));
  const AdjointRequest *const req = requests.begin();
  for (const auto &r : requests)
    r.A->reset(g.size(), nw);
  if (constant_coefficients)
  {
    for (const auto &r : requests)
    {
      // the same functional through the cell matrices: val = wt K z, dt = wt M z
      // (S' matrices per unit delta_K), with K z and M z formed once per temporal node
      const bool supg = r.supg;
      const auto &nodal = *r.nodal;
      SlabFunctional &A = *r.A;
      const auto &Kc = supg ? adj_matrices[2] : adj_matrices[0],
                 &Mc = supg ? adj_matrices[3] : adj_matrices[1];
      const double scale = supg ? primal.bounded_delta(delta_h, tau) : 1.;
      auto &kz = nodal_scratch[0], &mz = nodal_scratch[1];
      kz.resize(nodal.size());
      mz.resize(nodal.size());
      for (unsigned int k = 0; k < nodal.size(); ++k)
      {
        sv::vmult(kz[k], Kc, nodal[k]);
        if (scale != 1.)
          kz[k] *= scale;
        if (supg && cw.active) // S' also holds the stabilization terms' form
          sv::add_vmult(kz[k], 1., adj_matrices[4], nodal[k]);
        sv::vmult(mz[k], Mc, nodal[k]);
        sv::add(A.jump, scale * basis.left_trace()[k], mz[k]);
      }
      for (unsigned int m = 0; m < g.size(); ++m)
      {
        const double wt = tau * omega[m];
        for (unsigned int k = 0; k < nodal.size(); ++k)
        {
          sv::add(A.val[m], wt * ell[m][k], kz[k]);
          sv::add(A.dt[m], wt * scale * ell[m][k], mz[k]);
        }
      }
    }
    return;
  }
  // Point by point, on the cell's tables of W's shapes: per point the integrand is
  // phi_l c_value + grad phi_l . c_gradient + Lap phi_l c_laplacian, so each point costs
  // a few products per shape function and request.
  //   A:  c_value = jx alpha z,  c_gradient = jx (eps grad z + b z)
  //   S': with test = delta b.grad y: c_value = jx alpha test,
  //       c_gradient = jx (b test + D_K^T grad y), c_laplacian = -jx eps test
  // (weak_form::galerkin, weak_form::strong and the stabilization terms' form, in that
  // order of terms)
  const double delta = primal.bounded_delta(delta_h, tau);
  for (unsigned int m = 0; m <= g.size(); ++m) // m == g.size(): the jump at t_{n-1}^+
  {
    const bool jump = m == g.size();
    const double t = jump ? t0 : t0 + g[m] * tau, wt = jump ? 1. : tau * omega[m];
    std::array<const Vector<double> *, max_requests> z{};
    std::array<double *, max_requests> dt{}, val{};
    for (unsigned int r = 0; r < R; ++r)
    {
      const SlabFunction &zt = *req[r].zt;
      z[r] = jump ? &zt.plus : &zt.val[m];
      dt[r] = jump ? req[r].A->jump.data() : req[r].A->dt[m].data();
      val[r] = jump ? nullptr : req[r].A->val[m].data();
    }
    for (unsigned int q = 0; q < nq; ++q)
    {
      const double *phi = &w_value[q * nw], *lap = &w_laplacian[q * nw];
      std::array<const double *, dim> gphi;
      for (unsigned int d = 0; d < dim; ++d)
        gphi[d] = &w_gradient[d][q * nw];
      const auto cf = coefficients(q, t);
      const double jx = wt * fv_p.JxW(q);
      std::array<double, max_requests> c_dt{}, c_value{}, c_laplacian{};
      std::array<Tensor<1, dim>, max_requests> c_gradient;
      double zq = 0;
      Tensor<1, dim> gz;
      for (unsigned int r = 0; r < R; ++r)
      {
        if (r == 0 || z[r] != z[r - 1]) // zt at the point (once for the same zt)
        {
          zq = 0;
          gz = Tensor<1, dim>();
          const Vector<double> &zr = *z[r];
          for (unsigned int l = 0; l < nw; ++l)
          {
            zq += zr(l) * phi[l];
            for (unsigned int d = 0; d < dim; ++d)
              gz[d] += zr(l) * gphi[d][l];
          }
        }
        // the test side: zq (A) or delta b.grad y (S')
        const bool supg = req[r].supg;
        const double test = supg ? weak_form::supg_test(delta, cf.b, gz) : zq;
        c_dt[r] = jx * test;
        if (jump)
          continue;
        if (supg)
        {
          c_value[r] = c_dt[r] * cf.alpha;
          c_laplacian[r] = -c_dt[r] * cf.eps;
          c_gradient[r] = c_dt[r] * cf.b;
          if (cw.active)
            c_gradient[r] += jx * (transpose(cw.D) * gz);
        }
        else
        {
          c_value[r] = jx * cf.alpha * zq;
          c_gradient[r] = jx * (cf.eps * gz + zq * cf.b);
        }
      }
      for (unsigned int r = 0; r < R; ++r)
        for (unsigned int l = 0; l < nw; ++l)
          dt[r][l] += c_dt[r] * phi[l];
      if (jump)
        continue;
      for (unsigned int r = 0; r < R; ++r)
        for (unsigned int l = 0; l < nw; ++l)
        {
          double v = c_value[r] * phi[l] + c_laplacian[r] * lap[l];
          for (unsigned int d = 0; d < dim; ++d)
            v += c_gradient[r][d] * gphi[d][l];
          val[r][l] += v;
        }
    }
  }
}

template <int dim>
void CellKernel<dim>::goal_functional(double tau, const Vector<double> &jt,
                                      SlabFunctional &J) const
{
  J.reset(g.size(), fe_w.n_dofs_per_cell());
  if (jt.size())
    for (unsigned int m = 0; m < g.size(); ++m)
      sv::add(J.val[m], tau * omega[m], jt);
}

template void CellKernel<2>::primal_functionals(double, double, const Vector<double> &,
                                                const Vector<double> *, SlabFunctional &,
                                                SlabFunctional &) const;
template void CellKernel<2>::adjoint_functional(double, double,
                                                const std::vector<Vector<double>> &,
                                                const SlabFunction &, bool,
                                                SlabFunctional &) const;
template void CellKernel<2>::adjoint_functionals(double, double,
                                                 std::initializer_list<AdjointRequest>) const;
template bool
CellKernel<2>::dirichlet_data_functionals(double, double, const Vector<double> &,
                                          std::array<SlabFunctional, 2> &) const;
template void CellKernel<2>::load_quadrature_error(double, double, bool,
                                                   SlabFunctional &) const;
template void CellKernel<2>::goal_functional(double, const Vector<double> &,
                                             SlabFunctional &) const;
} // namespace anisodwr
