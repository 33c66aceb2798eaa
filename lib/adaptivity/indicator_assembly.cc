#include "adaptivity/indicator_assembly.h"

#include "adaptivity/short_vectors.h"

#include <algorithm>
#include <cmath>

namespace anisodwr
{
using namespace dealii;
namespace sv = short_vectors;

template <int dim>
IndicatorAssembly<dim>::IndicatorAssembly(
    const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
    const TemporalBasis &basis, const std::vector<Vector<double>> &U,
    const std::vector<Vector<double>> &Z, const std::vector<GoalSpec> &goals,
    TimeIndicator time_indicator, const HigherOrderPrimal *hi,
    SpaceIndicator space_indicator, const Vector<double> &zT, const Vector<double> &u0,
    const DataQuadrature &data_rule, const HangingDefect<dim> &hanging)
    : primal(primal), adjoint(adjoint), mesh(mesh), basis(basis), U(U), Z(Z),
      time_indicator(time_indicator), hi(hi), space_indicator(space_indicator),
      tria(primal.dof_handler().get_triangulation()),
      ops(primal.dof_handler(), weight_degree(primal, adjoint)),
      fe_w(ops.weight_element()),
      from_primal(ops.interpolation_from(primal.finite_element())),
      from_adjoint(ops.interpolation_from(adjoint.finite_element())),
      kernel(primal, fe_w, basis, data_rule), recon(basis),
      goal_t(primal.scene, primal.mapping(), fe_w, tria, goals, true),
      goal_T(primal.scene, primal.mapping(), fe_w, tria, goals, false), N(mesh.n_slabs()),
      n_nodes(basis.n_dofs()), n_w(fe_w.n_dofs_per_cell()), zT(zT), u0(u0),
      recon_z(kernel.n_points()), recon_u(kernel.n_points()),
      n_nodes_hi(hi ? hi->basis.n_dofs() : 0), hanging(hanging),
      defect_p(primal.finite_element().n_dofs_per_cell()), u_hi_nodes(n_nodes_hi),
      e_prev(n_w), idx_q(adjoint.finite_element().n_dofs_per_cell()), z_nodes(n_nodes),
      u_nodes(n_nodes), lift_nodes(n_nodes), z_nodes_next(n_nodes), lift_error_last(dim),
      Rz_nodes(n_nodes), z_next(n_w), u_prev(n_w), tmp(n_w), work_T(n_w), work_z(n_w),
      work_u(n_w), lift(dim)
{
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
    for (unsigned int d = 0; d < 2; ++d)
    {
      recon_z[m][d] = recon.adjoint(kernel.point(m), d == 1);
      recon_u[m][d] = recon.primal(kernel.point(m), d == 1);
    }
  if (hi)
    for (unsigned int m = 0; m < kernel.n_points(); ++m)
    {
      hi_val.push_back(hi->basis.values(kernel.point(m)));
      std::vector<double> d(n_nodes_hi);
      for (unsigned int k = 0; k < n_nodes_hi; ++k)
        d[k] = hi->basis.derivative(k, kernel.point(m));
      hi_der.push_back(d);
    }
}

template <int dim>
void IndicatorAssembly<dim>::add_cell(const cell_iterator &cell, Indicators<dim> &cells,
                                      Indicators<dim> &ind)
{
  kernel.reinit(cell);
  hanging.cell_slots(kernel.dof_indices(), cell_slots);
  n_groups = 0;
  for (const auto &[j, slot] : cell_slots)
  {
    const unsigned int dir = hanging.direction(slot);
    unsigned int g = 0;
    while (g < n_groups && groups[g].direction != dir)
      ++g;
    if (g == n_groups)
    {
      if (groups.size() == n_groups)
        groups.emplace_back().w.assign(n_nodes, Vector<double>(n_w));
      groups[g].direction = dir;
      groups[g].slots.clear();
      ++n_groups;
    }
    groups[g].slots.emplace_back(j, slot);
  }
  typename DoFHandler<dim>::active_cell_iterator cq(&tria, cell->level(), cell->index(),
                                                    &adjoint.dof_handler());
  cq->get_dof_indices(idx_q);
  for (unsigned int i = 0; i < dim; ++i)
    lift[i] = ops.directional_lift(cell, i);
  if (!goal_t.empty())
    goal_t.cell_vector(cell, goal_vector_I);
  if (!goal_T.empty())
    goal_T.cell_vector(cell, goal_vector_T);
  const auto c = cell->active_cell_index();
  double supg_part = 0;                // S(u)(R_h z) on this cell
  double quad_part = 0;                // D(R_h z): the primal's data quadrature error
  std::array<double, dim> lift_size{}; // ||I_2h,i u - u||^2 over the slabs

  for (unsigned int n = 0; n < N; ++n)
    add_slab(n, c, cells, ind, supg_part, quad_part, lift_size);
  // The SUPG consistency term is not directional (the seed formula's 1/2 S(u)(R_i z)
  // is nearly the same for every i: R_i z does not measure direction i), nor is the
  // data quadrature term. Their cell total S(u)(R_h z) + D(R_h z) is split over the
  // directions in proportion to the size of the directional primal error
  // ||I_2h,i u - u||^2 (summed over the slabs).
  ind.eta_h_supg += supg_part;
  ind.eta_h_quad += quad_part;
  for (unsigned int i = 0; i < dim; ++i)
    ind.no_lift += lift[i].exists ? 0 : 1;
  double total = 0;
  for (double l : lift_size)
    total += l;
  for (unsigned int i = 0; i < dim; ++i)
  {
    const double share =
        (total > 0 ? lift_size[i] / total : 1. / dim) * (supg_part + quad_part);
    cells.eta_h_cell[c][i] += share;
    ind.eta_h[i] += share;
  }
}

template <int dim>
void IndicatorAssembly<dim>::add_slab(unsigned int n, unsigned int c,
                                      Indicators<dim> &cells, Indicators<dim> &ind,
                                      double &supg_part, double &quad_part,
                                      std::array<double, dim> &lift_size)
{
  const double t0 = mesh.start(n), tau = mesh.tau(n);
  kernel.primal_functionals(t0, tau, U[n], n ? &U[n - 1] : nullptr, rho_u, supg_u);
  gather_slab(n);

  slab_function(kernel, basis, tau, z_nodes, z);
  restrict_weights(n);
  slab_function(kernel, basis, tau, Rz_nodes, Rh_z);
  kernel.adjoint_functionals(t0, tau,
                             {{&Rz_nodes, &Rh_z, false, &adjoint_form_Rhz},
                              {&Rz_nodes, &Rh_z, true, &supg_derivative_Rhz},
                              {&z_nodes, &z, false, &adjoint_form_z}});
  kernel.goal_functional(tau, goal_vector_I, goal_derivative);
  const bool last = n + 1 == N;
  slab_function(kernel, basis, tau, u_nodes, u);
  // S(u)(R_h z): with z_h = R_h z in the primal space, J(e) = rho(u)(z - z_h) +
  // S(u)(z_h) and J(e) = rho*(z_h)(u - u_h) + S(u)(z_h) hold exactly, so the
  // average of the two carries the full SUPG consistency term.
  supg_part += apply(supg_u, Rh_z, false);
  // the primal's quadrature error in its data: with it J(e) = rho(u)(z - z_h) +
  // S(u)(z_h) + D(z_h) holds for the u_h the primal's rule gave (rho(u)(z_h) = S(u)(z_h)
  // + D(z_h)); not directional either, so split with S(u)(R_h z)
  if (kernel.data_quadrature_error())
  {
    kernel.load_quadrature_error(t0, tau, n == 0, load_error);
    quad_part += apply(load_error, Rh_z, false);
  }

  double split = 0; // sum_i rho(u)(z - R_i z)
  for (unsigned int i = 0; i < dim; ++i)
  {
    double half_rho;
    const double eta =
        directional_indicator(i, n, tau, last, lift_size[i], half_rho, ind);
    cells.eta_h_cell[c][i] += eta;
    ind.eta_h[i] += eta;
    split += 2 * half_rho;
  }
  split += add_defect_indicators(tau, c, cells, ind);
  difference(z, Rh_z, z_minus_Rz);
  ind.eta_h_split_rest += split - apply(rho_u, z_minus_Rz, false);
  // the Dirichlet data's share, weighted by z itself (u_h interpolates g on Gamma_D)
  if (kernel.dirichlet_data_functionals(t0, tau, U[n], data))
    for (unsigned int i = 0; i < dim; ++i)
    {
      const double eta = apply(data[i], z, false);
      cells.eta_h_cell[c][i] += eta;
      ind.eta_h[i] += eta;
      ind.eta_h_data += eta;
    }

  reconstruction_errors(tau);
  // J_T(E u - u) at T: 0 for the Radau reconstruction (E u - u vanishes at t_n)
  const double end_part = hi ? higher_order_errors(n, tau, last) : 0.;
  const double jv = apply(goal_derivative, recon_error_u, false) +
                    end_part; // J'(E u - u) over I and at T
  const double half_rho = 0.5 * apply(rho_u, recon_error_z, false),
               half_rhostar = 0.5 * (jv - apply(adjoint_form_z, recon_error_u, true));
  const double eta_tau = time_indicator == TimeIndicator::average
                             ? half_rho + half_rhostar
                             : 2 * half_rhostar;
  ind.eta_tau_rho += half_rho;
  ind.eta_tau_rhostar += half_rhostar;
  cells.eta_tau_cell[c] += eta_tau;
  ind.eta_tau_slab[n] += eta_tau;
  ind.eta_tau += eta_tau;
}

template <int dim> void IndicatorAssembly<dim>::restrict_weights(unsigned int n)
{
  // R_h z from R_h applied to z's nodal vectors (R_h acts in space only); at hanging
  // nodes the conforming I_h z (adaptivity/hanging_defect.h)
  for (unsigned int k = 0; k < n_nodes; ++k)
    sv::vmult(Rz_nodes[k], ops.restriction(dim), z_nodes[k]);
  if (!n_groups)
    return;
  gather_defects(n);
  for (unsigned int g = 0; g < n_groups; ++g)
    for (unsigned int k = 0; k < n_nodes; ++k)
      sv::subtract(Rz_nodes[k], groups[g].w[k]);
}

template <int dim>
double IndicatorAssembly<dim>::add_defect_indicators(double tau, unsigned int c,
                                                     Indicators<dim> &cells,
                                                     Indicators<dim> &ind)
{
  // the hanging-node defects' part of rho(u)(z - I_h z), in the direction along their
  // coarse face
  double sum = 0;
  for (unsigned int g = 0; g < n_groups; ++g)
  {
    slab_function(kernel, basis, tau, groups[g].w, defect);
    const double d = apply(rho_u, defect, false),
                 eta = space_indicator == SpaceIndicator::primal_residual ? d : d / 2;
    cells.eta_h_cell[c][groups[g].direction] += eta;
    ind.eta_h[groups[g].direction] += eta;
    ind.eta_h_rho += d / 2;
    sum += d;
  }
  return sum;
}

template <int dim> void IndicatorAssembly<dim>::gather_defects(unsigned int n)
{
  for (unsigned int g = 0; g < n_groups; ++g)
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      sv::zero(defect_p);
      for (const auto &[j, slot] : groups[g].slots)
        defect_p[j] = hanging.value(n, slot, k);
      sv::vmult(groups[g].w[k], from_primal, defect_p);
    }
}

template <int dim> void IndicatorAssembly<dim>::gather_slab(unsigned int n)
{
  // The slabs run in order on a cell: slab n-1 gathered Z[n] (for z(t_{n-1}^+)) and
  // U[n-1]'s last node (its own u), so each slab vector is gathered once per cell.
  const auto &idx = kernel.dof_indices();
  if (n > 0)
  {
    sv::copy(u_prev, u_nodes[n_nodes - 1]);
    z_nodes.swap(z_nodes_next);
  }
  else
  {
    gather(u0, idx, 1, 0, from_primal, u_prev);
    for (unsigned int k = 0; k < n_nodes; ++k)
      gather(Z[n], idx_q, n_nodes, k, from_adjoint, z_nodes[k]);
  }
  for (unsigned int k = 0; k < n_nodes; ++k)
    gather(U[n], idx, n_nodes, k, from_primal, u_nodes[k]);
  sv::zero(z_next);
  if (n + 1 < N)
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      gather(Z[n + 1], idx_q, n_nodes, k, from_adjoint, z_nodes_next[k]);
      sv::add(z_next, basis.left_trace()[k], z_nodes_next[k]);
    }
  else if (zT.size())
    gather(zT, idx_q, 1, 0, from_adjoint, z_next);
}

template <int dim>
double IndicatorAssembly<dim>::directional_indicator(unsigned int i, unsigned int n,
                                                     double tau, bool last,
                                                     double &lift_size, double &half_rho,
                                                     Indicators<dim> &ind)
{
  for (unsigned int k = 0; k < n_nodes; ++k)
    sv::vmult(Rz_nodes[k], ops.restriction(i), z_nodes[k]);
  slab_function(kernel, basis, tau, Rz_nodes, Ri_z);
  difference(z, Ri_z, z_minus_Rz);
  half_rho = 0.5 * apply(rho_u, z_minus_Rz, false);
  ind.eta_h_rho += half_rho;
  if (space_indicator == SpaceIndicator::primal_residual)
    return 2 * half_rho;
  if (!lift[i].exists)
    return half_rho;
  for (unsigned int k = 0; k < n_nodes; ++k)
  {
    lift[i].apply(U[n], lift_nodes[k], n_nodes, k);
    sv::subtract(lift_nodes[k], u_nodes[k]);
  }
  slab_function(kernel, basis, tau, lift_nodes, lift_error);
  for (const auto &vv : lift_error.val)
    lift_size += tau * sv::norm_sqr(vv);
  if (n > 0)
    sv::copy(lift_error.minus, lift_error_last[i]); // I_2h,i u - u at U[n-1]'s last node
  else
    lift_error.minus.reinit(0);
  sv::copy(lift_error_last[i], lift_nodes[n_nodes - 1]);
  double jv = apply(goal_derivative, lift_error, false); // J' over I
  if (last && goal_vector_T.size())
  {
    sv::zero(work_T);
    for (unsigned int k = 0; k < n_nodes; ++k)
      sv::add(work_T, basis.right_trace()[k], lift_nodes[k]);
    jv += sv::dot(goal_vector_T, work_T);
  }
  const double half_rhostar = 0.5 * (jv - apply(adjoint_form_Rhz, lift_error, true)) +
                              0.5 * apply(supg_derivative_Rhz, lift_error, true);
  ind.eta_h_rhostar += half_rhostar;
  return half_rho + half_rhostar;
}

template <int dim> void IndicatorAssembly<dim>::reconstruction_errors(double tau)
{
  recon_error_z.val.resize(kernel.n_points());
  recon_error_z.dt.resize(kernel.n_points());
  recon_error_u.val.resize(kernel.n_points());
  recon_error_u.dt.resize(kernel.n_points());
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
  {
    for (bool deriv : {false, true})
    {
      const TimeCombination &a = recon_z[m][deriv], &b = recon_u[m][deriv];
      sv::zero(work_z);
      sv::zero(work_u);
      sv::add(work_z, a.outside, z_next);
      sv::add(work_u, b.outside, u_prev);
      for (unsigned int k = 0; k < n_nodes; ++k)
      {
        sv::add(work_z, a.slab[k], z_nodes[k]);
        sv::add(work_u, b.slab[k], u_nodes[k]);
      }
      if (deriv)
      {
        // (deal.II's operator/= multiplies by the reciprocal)
        sv::scale(work_z, 1. / tau);
        sv::scale(work_u, 1. / tau);
        sv::subtract(work_z, z.dt[m]);
        sv::subtract(work_u, u.dt[m]);
        sv::copy(recon_error_z.dt[m], work_z);
        sv::copy(recon_error_u.dt[m], work_u);
      }
      else
      {
        sv::subtract(work_z, z.val[m]);
        sv::subtract(work_u, u.val[m]);
        sv::copy(recon_error_z.val[m], work_z);
        sv::copy(recon_error_u.val[m], work_u);
      }
    }
  }
  sv::zero(recon_error_z.plus, n_w);    // E z(t_{n-1}) = z(t_{n-1}^+)
  sv::copy(recon_error_u.plus, u_prev); // E u(t_{n-1}) - u(t_{n-1}^+)
  sv::subtract(recon_error_u.plus, u.plus);
}

template <int dim>
double IndicatorAssembly<dim>::higher_order_errors(unsigned int n, double tau, bool last)
{
  // E u := u_r+1: values and derivatives at the Gauss points, the jump of
  // e = u_r+1 - u at t_{n-1} (e(t_0^-) = 0: both start from u_0), and J_T(e(T))
  const auto &idx = kernel.dof_indices();
  if (n > 0) // u_r+1(t_{n-1}^-) from slab n-1's nodal vectors, still in u_hi_nodes
  {
    e_prev = 0.;
    for (unsigned int k = 0; k < n_nodes_hi; ++k)
      e_prev.add(hi->basis.right_trace()[k], u_hi_nodes[k]);
  }
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    gather(hi->U[n], idx, n_nodes_hi, k, from_primal, u_hi_nodes[k]);
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
  {
    sv::zero(work_u);
    sv::zero(tmp);
    for (unsigned int k = 0; k < n_nodes_hi; ++k)
    {
      sv::add(work_u, hi_val[m][k], u_hi_nodes[k]);
      sv::add(tmp, hi_der[m][k] / tau, u_hi_nodes[k]);
    }
    sv::subtract(work_u, u.val[m]);
    sv::subtract(tmp, u.dt[m]);
    sv::copy(recon_error_u.val[m], work_u);
    sv::copy(recon_error_u.dt[m], tmp);
  }
  recon_error_u.plus = 0.;
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    recon_error_u.plus.add(hi->basis.left_trace()[k], u_hi_nodes[k]);
  recon_error_u.plus -= u.plus;
  if (n > 0)
  {
    e_prev -= u_prev; // u(t_{n-1}^-)
    recon_error_u.plus -= e_prev;
  }
  if (!(last && goal_vector_T.size()))
    return 0.;
  work_T = 0.;
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    work_T.add(hi->basis.right_trace()[k], u_hi_nodes[k]);
  for (unsigned int k = 0; k < n_nodes; ++k)
    work_T.add(-basis.right_trace()[k], u_nodes[k]);
  return goal_vector_T * work_T;
}

template class IndicatorAssembly<2>;
} // namespace anisodwr
