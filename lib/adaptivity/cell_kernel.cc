// CellKernel: the cell, its face pieces and neighbours (hanging nodes on either side),
// and the gathering of cell coefficients from interleaved slab vectors.
#include "adaptivity/cell_kernel.h"
#include "adaptivity/estimator.h"

#include "time/slab_vector.h"

#include <algorithm>

namespace anisodwr
{
using namespace dealii;

template <int dim>
CellKernel<dim>::CellKernel(const Space<dim> &primal, const FE_Q<dim> &fe_w,
                            const TemporalBasis &basis, const DataQuadrature &data)
    : primal(primal), scene(primal.scene), fe_p(primal.finite_element()), fe_w(fe_w),
      basis(basis), quad(fe_w.degree + 2), fquad(fe_w.degree + 2),
      fv_p(primal.mapping(), fe_p, quad,
           update_values | update_gradients | update_hessians | update_quadrature_points |
               update_JxW_values),
      fv_w(primal.mapping(), fe_w, quad,
           update_values | update_gradients | update_hessians),
      data_error(data.error_term), quad_primal(fe_p.degree + 2),
      fv_lo(primal.mapping(), fe_w, quad_primal,
            update_values | update_gradients | update_quadrature_points |
                update_JxW_values),
      quad_load(QGauss<1>(fe_w.degree + 2), std::max(1u, data.copies)),
      fv_load(primal.mapping(), fe_w, quad_load,
              update_values | update_gradients | update_quadrature_points |
                  update_JxW_values),
      ff_p(primal.mapping(), fe_p, fquad,
           update_values | update_gradients | update_normal_vectors | update_quadrature_points |
               update_JxW_values),
      ff_w(primal.mapping(), fe_w, fquad, update_values | update_gradients),
      fs_p(primal.mapping(), fe_p, fquad,
           update_gradients | update_normal_vectors | update_quadrature_points |
               update_JxW_values),
      fs_w(primal.mapping(), fe_w, fquad, update_values),
      fn_p(primal.mapping(), fe_p, fquad, update_gradients | update_quadrature_points),
      fns_p(primal.mapping(), fe_p, fquad, update_gradients | update_quadrature_points),
      constant_coefficients(!scene.coefficients_depend_on_time())
{
  gauss_rule(basis.n_dofs() + 1, g, omega);
  separable_load = scene.separable_rhs(load_terms);
  f_at.assign(g.size(), std::vector<double>(quad.size()));
  for (double s : g)
  {
    ell.push_back(basis.values(s));
    std::vector<double> d(basis.n_dofs());
    for (unsigned int k = 0; k < basis.n_dofs(); ++k)
      d[k] = basis.derivative(k, s);
    dell.push_back(d);
  }
}

template <int dim>
const std::vector<double> &CellKernel<dim>::load_factors_at(double t) const
{
  auto [it, inserted] = load_factors.try_emplace(t);
  if (inserted)
    for (const auto &term : load_terms)
      it->second.push_back(term.a(t));
  return it->second;
}

template <int dim> void CellKernel<dim>::reinit(const cell_iterator &cell)
{
  K = cell;
  fv_p.reinit(cell);
  fv_w.reinit(typename Triangulation<dim>::cell_iterator(cell));
  delta_h = primal.unbounded_delta(cell);
  cw = primal.cell_diffusion(cell);
  if (data_error)
    fv_lo.reinit(typename Triangulation<dim>::cell_iterator(cell));
  fv_load.reinit(typename Triangulation<dim>::cell_iterator(cell));
  if (constant_coefficients)
  {
    coefficients_at_q.clear();
    for (unsigned int q = 0; q < quad.size(); ++q)
      coefficients_at_q.push_back(
          weak_form::coefficients(scene, fv_p.quadrature_point(q), 0.));
    build_cell_matrices();
  }
  else
  {
    const unsigned int nw = fe_w.n_dofs_per_cell(), nq = quad.size();
    w_value.resize(nq * nw);
    w_laplacian.resize(nq * nw);
    for (auto &g : w_gradient)
      g.resize(nq * nw);
    for (unsigned int q = 0; q < nq; ++q)
      for (unsigned int l = 0; l < nw; ++l)
      {
        w_value[q * nw + l] = fv_w.shape_value(l, q);
        w_laplacian[q * nw + l] = trace(fv_w.shape_hessian(l, q));
        for (unsigned int d = 0; d < dim; ++d)
          w_gradient[d][q * nw + l] = fv_w.shape_grad(l, q)[d];
      }
  }
  idx.resize(fe_p.n_dofs_per_cell());
  cell->get_dof_indices(idx);
  pieces.clear();
  own_flux.reinit(fe_w.n_dofs_per_cell(), fe_p.n_dofs_per_cell());
  for (unsigned int f = 0; f < GeometryInfo<dim>::faces_per_cell; ++f)
  {
    if (cell->at_boundary(f))
    {
      ff_p.reinit(cell, f);
      ff_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f);
      const auto id = cell->face(f)->boundary_id();
      add_piece(ff_p, ff_w, nullptr, {}, scene.neumann_ids.count(id) ? 1 : 2);
      pieces.back().id = id;
      pieces.back().tangential = dim == 2 ? 1 - f / 2 : 0;
    }
    else if (cell->face(f)->has_children())
    {
      const unsigned int nn = cell->neighbor_of_neighbor(f);
      for (unsigned int sf = 0; sf < cell->face(f)->n_children(); ++sf)
      {
        const auto nb = cell->neighbor_child_on_subface(f, sf);
        fs_p.reinit(cell, f, sf);
        fs_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f, sf);
        fn_p.reinit(nb, nn);
        add_piece(fs_p, fs_w, &fn_p, dofs_of(nb), 0);
      }
    }
    else if (cell->neighbor_is_coarser(f))
    {
      const auto nb = cell->neighbor(f);
      const auto [nf, nsf] = cell->neighbor_of_coarser_neighbor(f);
      ff_p.reinit(cell, f);
      ff_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f);
      fns_p.reinit(nb, nf, nsf);
      add_piece(ff_p, ff_w, &fns_p, dofs_of(nb), 0);
    }
    else
    {
      const auto nb = cell->neighbor(f);
      ff_p.reinit(cell, f);
      ff_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f);
      fn_p.reinit(nb, cell->neighbor_of_neighbor(f));
      add_piece(ff_p, ff_w, &fn_p, dofs_of(nb), 0);
    }
  }
}

template <int dim>
std::vector<types::global_dof_index>
CellKernel<dim>::dofs_of(const typename DoFHandler<dim>::cell_iterator &c)
{
  std::vector<types::global_dof_index> d(fe_p.n_dofs_per_cell());
  c->get_dof_indices(d);
  return d;
}

template <int dim>
void CellKernel<dim>::add_piece(const FEFaceValuesBase<dim> &fp,
                                const FEFaceValuesBase<dim> &fw,
                                const FEFaceValuesBase<dim> *fn,
                                std::vector<types::global_dof_index> nb, int kind)
{
  const unsigned int nq = fp.n_quadrature_points, np = fe_p.n_dofs_per_cell(),
                     nw = fe_w.n_dofs_per_cell();
  Piece pc;
  pc.kind = kind;
  pc.nb_dofs = std::move(nb);
  pc.w.reinit(nw, nq);
  if (kind == 2)
  {
    pc.dn_w.reinit(nw, nq);
    pc.u_values.reinit(np, nq);
  }
  // the normal derivatives of u (ours and the neighbour's) at the piece's points
  FullMatrix<double> gradn(np, nq), nb_gradn(fn ? np : 0, nq);
  for (unsigned int q = 0; q < nq; ++q)
  {
    pc.JxW.push_back(fp.JxW(q));
    pc.x.push_back(fp.quadrature_point(q));
    pc.normal.push_back(fp.normal_vector(q));
    for (unsigned int l = 0; l < nw; ++l)
      pc.w(l, q) = fw.shape_value(l, q);
    for (unsigned int l = 0; l < np; ++l)
      gradn(l, q) = fp.shape_grad(l, q) * fp.normal_vector(q);
    if (kind == 2)
    {
      for (unsigned int l = 0; l < nw; ++l)
        pc.dn_w(l, q) = fw.shape_grad(l, q) * fp.normal_vector(q);
      for (unsigned int l = 0; l < np; ++l)
        pc.u_values(l, q) = fp.shape_value(l, q);
    }
    if (fn) // match the neighbour's quadrature point to ours
    {
      unsigned int qn = 0;
      double best = 1e300;
      for (unsigned int k = 0; k < nq; ++k)
        if (const double d = fn->quadrature_point(k).distance(fp.quadrature_point(q));
            d < best)
        {
          best = d;
          qn = k;
        }
      for (unsigned int l = 0; l < np; ++l)
        nb_gradn(l, q) = fn->shape_grad(l, qn) * fp.normal_vector(q);
    }
  }
  // the flux terms as matrices: -eps/2 (d_n u - d_n u_nb, w) on interior faces,
  // -eps (d_n u, w) on the boundary (the Neumann data is added per point)
  const double eps = scene.epsilon, own = kind == 0 ? -0.5 * eps : -eps;
  if (fn)
    pc.nb_flux.reinit(nw, np);
  for (unsigned int q = 0; q < nq; ++q)
    for (unsigned int l = 0; l < nw; ++l)
    {
      const double w = pc.JxW[q] * pc.w(l, q);
      for (unsigned int k = 0; k < np; ++k)
      {
        own_flux(l, k) += own * w * gradn(k, q);
        if (fn)
          pc.nb_flux(l, k) += 0.5 * eps * w * nb_gradn(k, q);
      }
    }
  pieces.push_back(std::move(pc));
}

template <int dim>
void CellKernel<dim>::combine(const Vector<double> &U,
                              const std::vector<types::global_dof_index> &dofs,
                              const std::vector<double> &a, double scale,
                              Vector<double> &c) const
{
  const SlabLayout slab{basis.n_dofs()};
  for (unsigned int l = 0; l < dofs.size(); ++l)
  {
    double s = 0;
    for (unsigned int k = 0; k < slab.m; ++k)
      s += a[k] * U(slab.index(dofs[l], k));
    c(l) = scale * s;
  }
}

template CellKernel<2>::CellKernel(const Space<2> &, const FE_Q<2> &,
                                   const TemporalBasis &, const DataQuadrature &);
template void CellKernel<2>::reinit(const cell_iterator &);
template const std::vector<double> &CellKernel<2>::load_factors_at(double) const;
template void CellKernel<2>::combine(const Vector<double> &,
                                     const std::vector<types::global_dof_index> &,
                                     const std::vector<double> &, double,
                                     Vector<double> &) const;
} // namespace anisodwr
