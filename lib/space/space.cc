#include "space/space.h"

#include "space/stabilization_terms.h"
#include "space/weak_form.h"

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <limits>
#include <optional>

namespace anisodwr
{
using namespace dealii;

template <int dim>
Space<dim>::Space(const Scene<dim> &scene, const Triangulation<dim> &tria,
                  unsigned int degree, const Stabilization &stabilization,
                  unsigned int mapping_degree)
    : scene(scene), stab(stabilization), fe(degree), map(mapping_degree), dofs(tria)
{
}

template <int dim> void Space<dim>::setup()
{
  dofs.distribute_dofs(fe);
  if (downstream && downstream(dofs.n_dofs()))
  {
    const auto box = scene.bounding_box();
    const Tensor<1, dim> b = scene.convection(0.5 * (box[0] + box[1]), 0.);
    if (b.norm() > 0)
      DoFRenumbering::downstream(dofs, b, true);
  }
  homogeneous.clear();
  DoFTools::make_hanging_node_constraints(dofs, homogeneous);
  hanging.copy_from(homogeneous);
  hanging.close();
  natural_outflow = false;
  if (!natural_rule)
    for (const auto id : scene.dirichlet_ids)
      VectorTools::interpolate_boundary_values(
          map, dofs, id, Functions::ZeroFunction<dim>(), homogeneous);
  else
  {
    // the DoFs of the Dirichlet faces the rule does not select
    std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
    for (const auto &cell : dofs.active_cell_iterators())
      for (const auto f : cell->face_indices())
        if (cell->at_boundary(f) && scene.dirichlet_ids.count(cell->face(f)->boundary_id()))
        {
          if (outflow_speed(*cell, f, scene).first > 0. && natural_rule(*cell, f))
          {
            natural_outflow = true;
            continue;
          }
          cell->face(f)->get_dof_indices(face_dofs);
          for (const auto i : face_dofs)
            if (!homogeneous.is_constrained(i))
              homogeneous.add_line(i);
        }
  }
  homogeneous.close();
  DynamicSparsityPattern dsp(dofs.n_dofs());
  // keep_constrained_dofs = true: the unconstrained M, A live on the same pattern.
  DoFTools::make_sparsity_pattern(dofs, dsp, homogeneous, true);
  pattern.copy_from(dsp);
  const std::lock_guard<std::mutex> lock(load_terms_mutex);
  load_terms.clear();
}

template <int dim>
std::map<types::global_dof_index, double> Space<dim>::dirichlet_values(double t) const
{
  std::map<types::global_dof_index, double> values, of_id;
  for (const auto id : scene.dirichlet_ids)
  {
    const ScalarFunctionFromFunctionObject<dim> g(
        [&](const Point<dim> &x) { return scene.boundary_value(x, t, id); });
    of_id.clear();
    VectorTools::interpolate_boundary_values(map, dofs, id, g, of_id);
    for (const auto &[i, value] : of_id)
      if (!hanging.is_constrained(i))
        values.insert({i, value}); // (an earlier id's value stays)
  }
  return values;
}

template <int dim>
void Space<dim>::distribute_dirichlet(const std::map<types::global_dof_index, double> &values,
                                      Vector<double> &v) const
{
  for (const auto &[i, value] : values)
    v(i) = value;
  hanging.distribute(v);
}

template <int dim>
double Space<dim>::length_along(const typename Triangulation<dim>::cell_iterator &cell,
                                const Tensor<1, dim> &beta) const
{
  // 1 / ||J^{-1} beta||_inf at the centre (exact for parallelograms)
  Tensor<2, dim> J;
  for (unsigned int d = 0; d < dim; ++d)
  {
    // columns of the Jacobian of the (bi)linear map at the centre, from the vertices
    Tensor<1, dim> col;
    for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
    {
      const double sign = (v >> d) & 1 ? 1. : -1.;
      col += sign * cell->vertex(v) / (GeometryInfo<dim>::vertices_per_cell / 2);
    }
    for (unsigned int e = 0; e < dim; ++e)
      J[e][d] = col[e];
  }
  const Tensor<1, dim> d = invert(J) * beta;
  double m = 0;
  for (unsigned int i = 0; i < dim; ++i)
    m = std::max(m, std::abs(d[i]));
  return 1. / m;
}

template <int dim>
double
Space<dim>::unbounded_delta(const typename Triangulation<dim>::cell_iterator &cell) const
{
  const double delta0 = stab.delta0;
  if (delta0 == 0.)
    return 0.;
  double delta = delta0 * std::pow(cell->measure(), 1.0 / dim);
  if (stab.supg_length == SupgLength::streamline)
  {
    // the length along beta = b/|b| at the centre at t = 0
    const Tensor<1, dim> b = scene.convection(cell->center(), 0.);
    if (b.norm() > 0)
      delta = delta0 * length_along(cell, b / b.norm());
  }
  if (stab.inverse_bound && scene.epsilon > 0.)
  {
    const double h = cell->minimum_vertex_distance(), q2 = double(fe.degree * fe.degree);
    delta = std::min(delta, h * h / (scene.epsilon * q2 * q2));
  }
  return delta;
}

template <int dim>
typename Space<dim>::CellDiffusion
Space<dim>::cell_diffusion(const typename Triangulation<dim>::cell_iterator &cell) const
{
  static_assert(dim == 2, "the stabilization terms are defined in 2D");
  CellDiffusion sum;
  std::optional<StabilizationCell> seen; // formed for the first active term only
  for (const DiffusionTerm &term : diffusion_terms())
  {
    if (!term.active(stab))
      continue;
    if (!seen)
      seen = StabilizationCell{
          scene.convection(cell->center(), 0.), scene.epsilon,
          [this, &cell](const Tensor<1, dim> &beta) { return length_along(cell, beta); },
          cw_scale.empty() || !cell->is_active() ? 1.
                                                 : cw_scale[cell->active_cell_index()]};
    sum.D += term.diffusion(stab, *seen);
  }
  sum.active = sum.D.norm_square() != 0.;
  return sum;
}

template <int dim>
void Space<dim>::assemble_matrices(double t, double tau, SpatialMatrices &m) const
{
  for (auto *mat : {&m.M, &m.A, &m.Mc, &m.Ac})
    mat->reinit(pattern);
  const QGauss<dim> quad(fe.degree + 2);
  FEValues<dim> fv(map, fe, quad,
                   update_values | update_gradients | update_hessians |
                       update_quadrature_points | update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  FullMatrix<double> cm(n, n), ca(n, n);
  std::vector<types::global_dof_index> idx(n);
  for (const auto &cell : dofs.active_cell_iterators())
  {
    fv.reinit(cell);
    cm = 0.;
    ca = 0.;
    const double dK = delta(cell, tau);
    const CellDiffusion cw = cell_diffusion(cell);
    for (unsigned int q = 0; q < quad.size(); ++q)
    {
      const auto c = weak_form::coefficients(scene, fv.quadrature_point(q), t);
      const double JxW = fv.JxW(q);
      for (unsigned int i = 0; i < n; ++i)
      {
        const double phi_i = fv.shape_value(i, q);
        const Tensor<1, dim> grad_i = fv.shape_grad(i, q);
        const double supg_i = weak_form::supg_test(dK, c.b, grad_i);
        for (unsigned int j = 0; j < n; ++j)
        {
          const double phi_j = fv.shape_value(j, q);
          const Tensor<1, dim> grad_j = fv.shape_grad(j, q);
          const double strong_j =
              weak_form::strong(c, phi_j, grad_j, trace(fv.shape_hessian(j, q)));
          cm(i, j) += phi_j * (phi_i + supg_i) * JxW;
          ca(i, j) += (weak_form::galerkin(c, phi_j, grad_j, phi_i, grad_i) +
                       strong_j * supg_i + cw.form(grad_j, grad_i)) *
                      JxW;
        }
      }
    }
    cell->get_dof_indices(idx);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
      {
        m.M.add(idx[i], idx[j], cm(i, j));
        m.A.add(idx[i], idx[j], ca(i, j));
      }
    homogeneous.distribute_local_to_global(cm, idx, m.Mc);
    homogeneous.distribute_local_to_global(ca, idx, m.Ac);
  }
}

template <int dim>
void Space<dim>::assemble_volume_loads(
    unsigned int n_sources, double tau,
    const std::function<void(const Point<dim> &, double *)> &f,
    const std::function<Tensor<1, dim>(const Point<dim> &, unsigned int)> &b,
    std::vector<Vector<double>> &F) const
{
  // one pass over the cells for all sources: the shape values are computed once, the
  // sources at a point all at once (f_k(x) for all k)
  F.resize(n_sources);
  for (auto &v : F)
    v.reinit(dofs.n_dofs());
  const QGauss<dim> quad(fe.degree + 2);
  FEValues<dim> fv(map, fe, quad,
                   update_values | update_gradients | update_quadrature_points |
                       update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell(), nq = quad.size();
  Vector<double> cf(n);
  std::vector<double> fx(nq * n_sources); // fx[q * n_sources + k] = f_k(x_q)
  std::vector<types::global_dof_index> idx(n);
  for (const auto &cell : dofs.active_cell_iterators())
  {
    fv.reinit(cell);
    cell->get_dof_indices(idx);
    const double dK = delta(cell, tau);
    for (unsigned int q = 0; q < nq; ++q)
      f(fv.quadrature_point(q), &fx[q * n_sources]);
    for (unsigned int k = 0; k < n_sources; ++k)
    {
      cf = 0.;
      for (unsigned int q = 0; q < nq; ++q)
      {
        const Point<dim> &x = fv.quadrature_point(q);
        const double fq = fx[q * n_sources + k] * fv.JxW(q);
        if (fq == 0.)
          continue;
        if (dK == 0.)
          for (unsigned int i = 0; i < n; ++i)
            cf(i) += fq * fv.shape_value(i, q);
        else
        {
          const Tensor<1, dim> bq = b(x, k);
          for (unsigned int i = 0; i < n; ++i)
            cf(i) += fq * (fv.shape_value(i, q) +
                           weak_form::supg_test(dK, bq, fv.shape_grad(i, q)));
        }
      }
      for (unsigned int i = 0; i < n; ++i)
        F[k](idx[i]) += cf(i);
    }
  }
}

template <int dim>
void Space<dim>::add_neumann_loads(const std::vector<double> &times,
                                   std::vector<Vector<double>> &F) const
{
  if (scene.neumann_ids.empty())
    return;
  const QGauss<dim - 1> fquad(fe.degree + 2);
  FEFaceValues<dim> ffv(map, fe, fquad,
                        update_values | update_quadrature_points | update_normal_vectors |
                            update_JxW_values);
  const unsigned int n = fe.n_dofs_per_cell();
  std::vector<types::global_dof_index> idx(n);
  for (const auto &cell : dofs.active_cell_iterators())
    if (cell->at_boundary())
      for (const auto face : cell->face_indices())
        if (cell->at_boundary(face) &&
            scene.neumann_ids.count(cell->face(face)->boundary_id()))
        {
          const types::boundary_id id = cell->face(face)->boundary_id();
          ffv.reinit(cell, face);
          cell->get_dof_indices(idx);
          for (std::size_t k = 0; k < times.size(); ++k)
            for (unsigned int q = 0; q < fquad.size(); ++q)
            {
              const double g = scene.boundary_flux(ffv.quadrature_point(q),
                                                   ffv.normal_vector(q), times[k], id) *
                               ffv.JxW(q);
              for (unsigned int i = 0; i < n; ++i)
                F[k](idx[i]) += g * ffv.shape_value(i, q);
            }
        }
}

template <int dim>
void Space<dim>::assemble_loads(const std::vector<double> &times, double tau,
                                std::vector<Vector<double>> &F) const
{
  std::vector<LoadTerm<dim>> terms;
  if (!scene.separable_rhs(terms))
    assemble_volume_loads(
        times.size(), tau,
        [&](const Point<dim> &x, double *out) { scene.rhs_at_times(x, times, out); },
        [&](const Point<dim> &x, unsigned int k)
        { return scene.convection(x, times[k]); },
        F);
  else
  {
    // b does not depend on t here (separable_rhs' contract)
    const std::lock_guard<std::mutex> lock(load_terms_mutex);
    const double key = delta_depends_on_tau() ? tau : 0.;
    auto G = load_terms.find(key);
    if (G == load_terms.end())
    {
      if (load_terms.size() >= 8)
        load_terms.clear();
      G = load_terms.emplace(key, std::vector<Vector<double>>()).first;
      assemble_volume_loads(
          terms.size(), tau,
          [&](const Point<dim> &x, double *out)
          {
            for (std::size_t j = 0; j < terms.size(); ++j)
              out[j] = terms[j].g(x);
          },
          [&](const Point<dim> &x, unsigned int) { return scene.convection(x, 0.); },
          G->second);
    }
    F.resize(times.size());
    for (std::size_t k = 0; k < times.size(); ++k)
    {
      F[k].reinit(dofs.n_dofs());
      for (std::size_t j = 0; j < terms.size(); ++j)
        F[k].add(terms[j].a(times[k]), G->second[j]);
    }
  }
  add_neumann_loads(times, F);
}

template <int dim> void Space<dim>::assemble_initial(double tau, Vector<double> &U0) const
{
  std::vector<Vector<double>> F;
  assemble_volume_loads(
      1, tau, [&](const Point<dim> &x, double *out) { *out = scene.initial_value(x); },
      [&](const Point<dim> &x, unsigned int) { return scene.convection(x, 0.); }, F);
  U0 = std::move(F[0]);
}

template <int dim>
unsigned int auto_mapping_degree(const Triangulation<dim> &tria, unsigned int p)
{
  for (const types::manifold_id id : tria.get_manifold_ids())
    if (id != numbers::flat_manifold_id)
      return p;
  return 1;
}

double thickness_across(const CellAccessor<2, 2> &cell, unsigned int f)
{
  return cell.face(f)->center().distance(cell.face(f ^ 1u)->center());
}

std::pair<double, double>
outflow_speed(const CellAccessor<2, 2> &cell, unsigned int f,
              const Scene<2> &scene)
{
  const auto face = cell.face(f);
  const Tensor<1, 2> n = outward_normal(cell, f);
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const double time : {0., 0.5 * scene.end_time, scene.end_time})
  {
    const double bn = scene.convection(face->center(), time) * n;
    lo = std::min(lo, bn);
    hi = std::max(hi, bn);
  }
  return {lo, hi};
}

template class Space<2>;
template unsigned int auto_mapping_degree(const Triangulation<2> &, unsigned int);
} // namespace anisodwr
