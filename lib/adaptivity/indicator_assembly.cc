#include "adaptivity/indicator_assembly.h"

#include "adaptivity/short_vectors.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace anisodwr
{
using namespace dealii;
namespace sv = short_vectors;

template <int dim>
IndicatorAssembly<dim>::Weights::Weights(const AssemblyAdjoint<dim> &in,
                                         const Space<dim> &primal,
                                         const FE_Q<dim> &fe_w, unsigned int n_nodes,
                                         unsigned int n_w)
    : Z(in.Z), zT(in.zT), hanging(in.hanging),
      goal_t(primal.scene, primal.mapping(), fe_w,
             primal.dof_handler().get_triangulation(), in.goals, true),
      goal_T(primal.scene, primal.mapping(), fe_w,
             primal.dof_handler().get_triangulation(), in.goals, false),
      z_nodes(n_nodes), z_nodes_next(n_nodes), Rz_nodes(n_nodes), z_next(n_w)
{
}

template <int dim>
IndicatorAssembly<dim>::IndicatorAssembly(
    const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
    const TemporalBasis &basis, const std::vector<Vector<double>> &U,
    const std::vector<AssemblyAdjoint<dim>> &adjoints, TimeIndicator time_indicator,
    const HigherOrderPrimal *hi, SpaceIndicator space_indicator, const Vector<double> &u0,
    const DataQuadrature &data_rule)
    : primal(primal), adjoint(adjoint), mesh(mesh), basis(basis), U(U),
      time_indicator(time_indicator), hi(hi), space_indicator(space_indicator),
      tria(primal.dof_handler().get_triangulation()),
      ops(primal.dof_handler(), weight_degree(primal, adjoint)),
      fe_w(ops.weight_element()),
      from_primal(ops.interpolation_from(primal.finite_element())),
      from_adjoint(ops.interpolation_from(adjoint.finite_element())),
      kernel(primal, fe_w, basis, data_rule), recon(basis), N(mesh.n_slabs()),
      n_nodes(basis.n_dofs()), n_w(fe_w.n_dofs_per_cell()), u0(u0),
      recon_z(kernel.n_points()), recon_u(kernel.n_points()),
      n_nodes_hi(hi ? hi->basis.n_dofs() : 0),
      defect_p(primal.finite_element().n_dofs_per_cell()), u_hi_nodes(n_nodes_hi),
      e_prev(n_w), idx_q(adjoint.finite_element().n_dofs_per_cell()), u_nodes(n_nodes),
      lift_error_last(dim), u_prev(n_w), tmp(n_w), work_T(n_w), work_z(n_w), work_u(n_w),
      lift(dim)
{
  for (auto &nodes : lift_nodes)
    nodes.resize(n_nodes);
  // add_cell groups the cell's hanging slots once, by the first adjoint's defects
  if (adjoints.empty())
    throw std::invalid_argument("IndicatorAssembly: no adjoint");
  weights.reserve(adjoints.size());
  for (const auto &a : adjoints)
  {
    if (a.hanging.n_slots() != adjoints.front().hanging.n_slots())
      throw std::logic_error("IndicatorAssembly: the adjoints' hanging-node defects "
                             "are not on the same constrained DoFs");
    weights.emplace_back(a, primal, fe_w, n_nodes, n_w);
  }
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
void IndicatorAssembly<dim>::add_cell(const cell_iterator &cell,
                                      std::vector<Indicators<dim>> &cells,
                                      std::vector<Indicators<dim>> &sums)
{
  kernel.reinit(cell);
  // (the slots are the mesh's constrained DoFs: every adjoint's HangingDefect has them)
  weights.front().hanging.cell_slots(kernel.dof_indices(), cell_slots);
  n_groups = 0;
  for (const auto &[j, slot] : cell_slots)
  {
    const unsigned int dir = weights.front().hanging.direction(slot);
    unsigned int g = 0;
    while (g < n_groups && groups[g].direction != dir)
      ++g;
    if (g == n_groups)
    {
      if (groups.size() == n_groups)
      {
        groups.emplace_back();
        for (auto &a : weights)
          a.defects.emplace_back(n_nodes, Vector<double>(n_w));
      }
      groups[g].direction = dir;
      groups[g].slots.clear();
      ++n_groups;
    }
    groups[g].slots.emplace_back(j, slot);
  }
  typename DoFHandler<dim>::active_cell_iterator cq(&tria, cell->level(), cell->index(),
                                                    &adjoint.dof_handler());
  cq->get_dof_indices(idx_q);
  wall_w.clear();
  if (adjoint.has_natural_outflow() && cell->at_boundary())
    for (const auto f : cell->face_indices())
      if (cell->at_boundary(f) &&
          primal.scene.dirichlet_ids.count(cell->face(f)->boundary_id()))
        for (unsigned int i = 0; i < fe_w.n_dofs_per_face(); ++i)
          wall_w.push_back(fe_w.face_to_cell_index(i, f));
  for (unsigned int i = 0; i < dim; ++i)
    lift[i] = ops.directional_lift(cell, i);
  for (auto &a : weights)
  {
    if (!a.goal_t.empty())
      a.goal_t.cell_vector(cell, a.goal_vector_I);
    if (!a.goal_T.empty())
      a.goal_T.cell_vector(cell, a.goal_vector_T);
    a.supg_part = 0; // S(u)(R_h z) on this cell
    a.quad_part = 0; // D(R_h z): the primal's data quadrature error
  }
  const auto c = cell->active_cell_index();
  std::array<double, dim> lift_size{}; // ||I_2h,i u - u||^2 over the slabs

  for (unsigned int n = 0; n < N; ++n)
  {
    add_primal_slab(n, lift_size);
    for (std::size_t k = 0; k < weights.size(); ++k)
      add_slab(weights[k], n, c, cells[k], sums[k]);
  }
  // The SUPG consistency term is not directional (the seed formula's 1/2 S(u)(R_i z)
  // is nearly the same for every i: R_i z does not measure direction i), nor is the
  // data quadrature term. Their cell total S(u)(R_h z) + D(R_h z) is split over the
  // directions in proportion to the size of the directional primal error
  // ||I_2h,i u - u||^2 (summed over the slabs).
  double total = 0;
  for (double l : lift_size)
    total += l;
  for (std::size_t k = 0; k < weights.size(); ++k)
  {
    const Weights &a = weights[k];
    Indicators<dim> &ind = sums[k];
    ind.eta_h_supg += a.supg_part;
    ind.eta_h_quad += a.quad_part;
    for (unsigned int i = 0; i < dim; ++i)
      ind.no_lift += lift[i].exists ? 0 : 1;
    for (unsigned int i = 0; i < dim; ++i)
    {
      const double share =
          (total > 0 ? lift_size[i] / total : 1. / dim) * (a.supg_part + a.quad_part);
      cells[k].eta_h_cell[c][i] += share;
      ind.eta_h[i] += share;
    }
  }
}

template <int dim>
void IndicatorAssembly<dim>::add_primal_slab(unsigned int n,
                                             std::array<double, dim> &lift_size)
{
  const double t0 = mesh.start(n), tau = mesh.tau(n);
  kernel.primal_functionals(t0, tau, U[n], n ? &U[n - 1] : nullptr, rho_u, supg_u);
  // (load_quadrature_error reuses f's values of primal_functionals)
  if (kernel.data_quadrature_error())
    kernel.load_quadrature_error(t0, tau, n == 0, load_error);
  gather_primal(n);
  slab_function(kernel, basis, tau, u_nodes, u);
  has_data = kernel.dirichlet_data_functionals(t0, tau, U[n], data);
  if (space_indicator != SpaceIndicator::primal_residual)
    lift_errors(n, tau, lift_size);
  if (hi)
    higher_order_errors(n, tau, n + 1 == N);
  else
  {
    reconstruction_error(recon_u, u_prev, u_nodes, u, tau, work_u, recon_error_u);
    sv::copy(recon_error_u.plus, u_prev); // E u(t_{n-1}) - u(t_{n-1}^+)
    sv::subtract(recon_error_u.plus, u.plus);
  }
}

template <int dim>
void IndicatorAssembly<dim>::add_slab(Weights &a, unsigned int n, unsigned int c,
                                      Indicators<dim> &cells, Indicators<dim> &ind)
{
  const double t0 = mesh.start(n), tau = mesh.tau(n);
  gather_adjoint(a, n);

  slab_function(kernel, basis, tau, a.z_nodes, a.z);
  restrict_weights(a, n);
  slab_function(kernel, basis, tau, a.Rz_nodes, a.Rh_z);
  kernel.adjoint_functionals(t0, tau,
                             {{&a.Rz_nodes, &a.Rh_z, false, &a.adjoint_form_Rhz},
                              {&a.Rz_nodes, &a.Rh_z, true, &a.supg_derivative_Rhz},
                              {&a.z_nodes, &a.z, false, &a.adjoint_form_z}});
  kernel.goal_functional(tau, a.goal_vector_I, a.goal_derivative);
  const bool last = n + 1 == N;
  // S(u)(R_h z): with z_h = R_h z in the primal space, J(e) = rho(u)(z - z_h) +
  // S(u)(z_h) and J(e) = rho*(z_h)(u - u_h) + S(u)(z_h) hold exactly, so the
  // average of the two carries the full SUPG consistency term.
  a.supg_part += apply(supg_u, a.Rh_z, false);
  // the primal's quadrature error in its data: with it J(e) = rho(u)(z - z_h) +
  // S(u)(z_h) + D(z_h) holds for the u_h the primal's rule gave (rho(u)(z_h) = S(u)(z_h)
  // + D(z_h)); not directional either, so split with S(u)(R_h z)
  if (kernel.data_quadrature_error())
    a.quad_part += apply(load_error, a.Rh_z, false);

  double split = 0; // sum_i rho(u)(z - R_i z)
  for (unsigned int i = 0; i < dim; ++i)
  {
    double half_rho;
    const double eta = directional_indicator(a, i, tau, last, half_rho, ind);
    cells.eta_h_cell[c][i] += eta;
    ind.eta_h[i] += eta;
    split += 2 * half_rho;
  }
  split += add_defect_indicators(a, tau, c, cells, ind);
  difference(a.z, a.Rh_z, z_minus_Rz);
  ind.eta_h_split_rest += split - apply(rho_u, z_minus_Rz, false);
  // the Dirichlet data's share, weighted by z itself (u_h interpolates g on Gamma_D)
  if (has_data)
    for (unsigned int i = 0; i < dim; ++i)
    {
      const double eta = apply(data[i], a.z, false);
      cells.eta_h_cell[c][i] += eta;
      ind.eta_h[i] += eta;
      ind.eta_h_data += eta;
    }

  reconstruction_error(recon_z, a.z_next, a.z_nodes, a.z, tau, work_z, recon_error_z);
  sv::zero(recon_error_z.plus, n_w); // E z(t_{n-1}) = z(t_{n-1}^+)
  // J_T(E u - u) at T: 0 for the Radau reconstruction (E u - u vanishes at t_n)
  const double end_part =
      hi && last && a.goal_vector_T.size() ? a.goal_vector_T * hi_end : 0.;
  const double jv = apply(a.goal_derivative, recon_error_u, false) +
                    end_part; // J'(E u - u) over I and at T
  const double half_rho = 0.5 * apply(rho_u, recon_error_z, false),
               half_rhostar = 0.5 * (jv - apply(a.adjoint_form_z, recon_error_u, true));
  const double eta_tau = time_indicator == TimeIndicator::average
                             ? half_rho + half_rhostar
                             : 2 * half_rhostar;
  ind.eta_tau_rho += half_rho;
  ind.eta_tau_rhostar += half_rhostar;
  cells.eta_tau_cell[c] += eta_tau;
  ind.eta_tau_slab[n] += eta_tau;
  ind.eta_tau += eta_tau;
}

template <int dim>
void IndicatorAssembly<dim>::restrict_nodes(const Weights &a, const FullMatrix<double> &R,
                                            std::vector<Vector<double>> &out)
{
  for (unsigned int k = 0; k < n_nodes; ++k)
    if (wall_w.empty())
      sv::vmult(out[k], R, a.z_nodes[k]);
    else
    {
      // z's nodal values on the Dirichlet faces are those faces' values of z (W is
      // nodal), so R (z with them zeroed) vanishes there
      sv::copy(z_wall, a.z_nodes[k]);
      for (const unsigned int j : wall_w)
        z_wall[j] = 0.;
      sv::vmult(out[k], R, z_wall);
    }
}

template <int dim> void IndicatorAssembly<dim>::restrict_weights(Weights &a, unsigned int n)
{
  // R_h z from R_h applied to z's nodal vectors (R_h acts in space only); at hanging
  // nodes the conforming I_h z (adaptivity/hanging_defect.h)
  restrict_nodes(a, ops.restriction(dim), a.Rz_nodes);
  if (!n_groups)
    return;
  gather_defects(a, n);
  for (unsigned int g = 0; g < n_groups; ++g)
    for (unsigned int k = 0; k < n_nodes; ++k)
      sv::subtract(a.Rz_nodes[k], a.defects[g][k]);
}

template <int dim>
double IndicatorAssembly<dim>::add_defect_indicators(Weights &a, double tau, unsigned int c,
                                                     Indicators<dim> &cells,
                                                     Indicators<dim> &ind)
{
  // the hanging-node defects' part of rho(u)(z - I_h z), in the direction along their
  // coarse face
  double sum = 0;
  for (unsigned int g = 0; g < n_groups; ++g)
  {
    slab_function(kernel, basis, tau, a.defects[g], defect);
    const double d = apply(rho_u, defect, false),
                 eta = space_indicator == SpaceIndicator::primal_residual ? d : d / 2;
    cells.eta_h_cell[c][groups[g].direction] += eta;
    ind.eta_h[groups[g].direction] += eta;
    ind.eta_h_rho += d / 2;
    sum += d;
  }
  return sum;
}

template <int dim> void IndicatorAssembly<dim>::gather_defects(Weights &a, unsigned int n)
{
  for (unsigned int g = 0; g < n_groups; ++g)
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      sv::zero(defect_p);
      for (const auto &[j, slot] : groups[g].slots)
        defect_p[j] = a.hanging.value(n, slot, k);
      sv::vmult(a.defects[g][k], from_primal, defect_p);
    }
}

template <int dim> void IndicatorAssembly<dim>::gather_primal(unsigned int n)
{
  // The slabs run in order on a cell: slab n-1 gathered U[n-1]'s last node (its own u),
  // so each slab vector is gathered once per cell.
  const auto &idx = kernel.dof_indices();
  if (n > 0)
    sv::copy(u_prev, u_nodes[n_nodes - 1]);
  else
    gather(u0, idx, 1, 0, from_primal, u_prev);
  for (unsigned int k = 0; k < n_nodes; ++k)
    gather(U[n], idx, n_nodes, k, from_primal, u_nodes[k]);
}

template <int dim> void IndicatorAssembly<dim>::gather_adjoint(Weights &a, unsigned int n)
{
  // slab n-1 gathered Z[n] (for z(t_{n-1}^+)), so each slab vector is gathered once per
  // cell
  if (n > 0)
    a.z_nodes.swap(a.z_nodes_next);
  else
    for (unsigned int k = 0; k < n_nodes; ++k)
      gather(a.Z[n], idx_q, n_nodes, k, from_adjoint, a.z_nodes[k]);
  sv::zero(a.z_next);
  if (n + 1 < N)
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      gather(a.Z[n + 1], idx_q, n_nodes, k, from_adjoint, a.z_nodes_next[k]);
      sv::add(a.z_next, basis.left_trace()[k], a.z_nodes_next[k]);
    }
  else if (a.zT.size())
    gather(a.zT, idx_q, 1, 0, from_adjoint, a.z_next);
}

template <int dim>
void IndicatorAssembly<dim>::lift_errors(unsigned int n, double tau,
                                         std::array<double, dim> &lift_size)
{
  for (unsigned int i = 0; i < dim; ++i)
  {
    if (!lift[i].exists)
      continue;
    auto &nodes = lift_nodes[i];
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      lift[i].apply(U[n], nodes[k], n_nodes, k);
      sv::subtract(nodes[k], u_nodes[k]);
    }
    slab_function(kernel, basis, tau, nodes, lift_error[i]);
    for (const auto &vv : lift_error[i].val)
      lift_size[i] += tau * sv::norm_sqr(vv);
    if (n > 0)
      sv::copy(lift_error[i].minus,
               lift_error_last[i]); // I_2h,i u - u at U[n-1]'s last node
    else
      lift_error[i].minus.reinit(0);
    sv::copy(lift_error_last[i], nodes[n_nodes - 1]);
  }
}

template <int dim>
double IndicatorAssembly<dim>::directional_indicator(Weights &a, unsigned int i, double tau,
                                                     bool last, double &half_rho,
                                                     Indicators<dim> &ind)
{
  restrict_nodes(a, ops.restriction(i), a.Rz_nodes);
  slab_function(kernel, basis, tau, a.Rz_nodes, Ri_z);
  difference(a.z, Ri_z, z_minus_Rz);
  half_rho = 0.5 * apply(rho_u, z_minus_Rz, false);
  ind.eta_h_rho += half_rho;
  if (space_indicator == SpaceIndicator::primal_residual)
    return 2 * half_rho;
  if (!lift[i].exists)
    return half_rho;
  const SlabFunction &le = lift_error[i];
  double jv = apply(a.goal_derivative, le, false); // J' over I
  if (last && a.goal_vector_T.size())
  {
    sv::zero(work_T);
    for (unsigned int k = 0; k < n_nodes; ++k)
      sv::add(work_T, basis.right_trace()[k], lift_nodes[i][k]);
    jv += sv::dot(a.goal_vector_T, work_T);
  }
  const double half_rhostar = 0.5 * (jv - apply(a.adjoint_form_Rhz, le, true)) +
                              0.5 * apply(a.supg_derivative_Rhz, le, true);
  ind.eta_h_rhostar += half_rhostar;
  return half_rho + half_rhostar;
}

template <int dim>
void IndicatorAssembly<dim>::reconstruction_error(
    const std::vector<std::array<TimeCombination, 2>> &combination,
    const Vector<double> &outside, const std::vector<Vector<double>> &nodes,
    const SlabFunction &f, double tau, Vector<double> &work, SlabFunction &error) const
{
  error.val.resize(kernel.n_points());
  error.dt.resize(kernel.n_points());
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
    for (bool deriv : {false, true})
    {
      const TimeCombination &c = combination[m][deriv];
      sv::zero(work);
      sv::add(work, c.outside, outside);
      for (unsigned int k = 0; k < n_nodes; ++k)
        sv::add(work, c.slab[k], nodes[k]);
      if (deriv)
      {
        // (deal.II's operator/= multiplies by the reciprocal)
        sv::scale(work, 1. / tau);
        sv::subtract(work, f.dt[m]);
        sv::copy(error.dt[m], work);
      }
      else
      {
        sv::subtract(work, f.val[m]);
        sv::copy(error.val[m], work);
      }
    }
}

template <int dim>
void IndicatorAssembly<dim>::higher_order_errors(unsigned int n, double tau, bool last)
{
  // E u := u_r+1: values and derivatives at the Gauss points, the jump of
  // e = u_r+1 - u at t_{n-1} (e(t_0^-) = 0: both start from u_0), and u_r+1(T) - u(T)
  const auto &idx = kernel.dof_indices();
  if (n > 0) // u_r+1(t_{n-1}^-) from slab n-1's nodal vectors, still in u_hi_nodes
  {
    e_prev = 0.;
    for (unsigned int k = 0; k < n_nodes_hi; ++k)
      e_prev.add(hi->basis.right_trace()[k], u_hi_nodes[k]);
  }
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    gather(hi->U[n], idx, n_nodes_hi, k, from_primal, u_hi_nodes[k]);
  recon_error_u.val.resize(kernel.n_points());
  recon_error_u.dt.resize(kernel.n_points());
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
  sv::zero(recon_error_u.plus, n_w);
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    recon_error_u.plus.add(hi->basis.left_trace()[k], u_hi_nodes[k]);
  recon_error_u.plus -= u.plus;
  if (n > 0)
  {
    e_prev -= u_prev; // u(t_{n-1}^-)
    recon_error_u.plus -= e_prev;
  }
  if (!last)
    return;
  hi_end.reinit(n_w);
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    hi_end.add(hi->basis.right_trace()[k], u_hi_nodes[k]);
  for (unsigned int k = 0; k < n_nodes; ++k)
    hi_end.add(-basis.right_trace()[k], u_nodes[k]);
}

template class IndicatorAssembly<2>;
} // namespace anisodwr
