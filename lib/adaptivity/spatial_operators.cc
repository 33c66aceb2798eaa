#include "adaptivity/spatial_operators.h"

#include "adaptivity/temporal_reconstruction.h"
#include "time/slab_vector.h"

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// The multilinear map of a cell through its vertices, the map of MappingQ(1): exact
/// for any straight-edged cell (parallelograms, trapezoids, the chords of a curved
/// boundary), extrapolated linearly beyond the cell. to_unit() is Newton's method from
/// the affine guess through vertices 0, 1, 2(, 4), which is exact for parallelograms.
template <int dim> struct CellMap
{
  std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell> v;
  Point<dim> origin;
  Tensor<2, dim> J0_inv;
  template <typename Cell> explicit CellMap(const Cell &cell) : origin(cell->vertex(0))
  {
    for (unsigned int k = 0; k < v.size(); ++k)
      v[k] = cell->vertex(k);
    Tensor<2, dim> J0;
    for (unsigned int d = 0; d < dim; ++d)
      for (unsigned int e = 0; e < dim; ++e)
        J0[e][d] = v[1u << d][e] - origin[e];
    J0_inv = invert(J0);
  }
  Point<dim> to_real(const Point<dim> &xi, Tensor<2, dim> *jacobian = nullptr) const
  {
    Point<dim> x;
    if (jacobian)
      *jacobian = 0;
    for (unsigned int k = 0; k < v.size(); ++k)
    {
      double phi = 1;
      Tensor<1, dim> dphi;
      for (unsigned int d = 0; d < dim; ++d)
        dphi[d] = 1;
      for (unsigned int d = 0; d < dim; ++d)
      {
        const bool upper = (k >> d) & 1u;
        const double f = upper ? xi[d] : 1. - xi[d], df = upper ? 1. : -1.;
        phi *= f;
        for (unsigned int e = 0; e < dim; ++e)
          dphi[e] *= (e == d ? df : f);
      }
      x += phi * v[k];
      if (jacobian)
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            (*jacobian)[a][b] += v[k][a] * dphi[b];
    }
    return x;
  }
  Point<dim> to_unit(const Point<dim> &x) const
  {
    Point<dim> xi(J0_inv * (x - origin));
    Tensor<2, dim> J;
    for (unsigned int it = 0; it < 30; ++it)
    {
      const Tensor<1, dim> res = to_real(xi, &J) - x;
      const Tensor<1, dim> step = invert(J) * res;
      xi -= step;
      if (step.norm() < 1e-14 * (1. + xi.norm()))
        break;
    }
    return xi;
  }

  /// Extent [lo, hi] of another cell along `direction` in this cell's unit coordinates.
  template <typename Cell>
  std::pair<double, double> extent(const Cell &other, unsigned int direction) const
  {
    double lo = 1e300, hi = -1e300;
    for (unsigned int k = 0; k < GeometryInfo<dim>::vertices_per_cell; ++k)
    {
      const double x = to_unit(other->vertex(k))[direction];
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    return {lo, hi};
  }
};
/// The cell of a patch holding the grid point xi (unit coordinates of maps[0]'s cell),
/// with the point in that cell's unit coordinates (xc): maps[0]'s cell if xi is inside
/// it, else the candidate containing the point or, on curved patches (children placed
/// on a manifold do not tile their parent's straight-edged image exactly), the nearest
/// one if the point is at most `slack` outside it. maps.size() if there is none.
template <int dim>
unsigned int locate(const std::vector<CellMap<dim>> &maps, const Point<dim> &xi,
                    Point<dim> &xc)
{
  const double tol = 1e-8, slack = 0.2;
  auto inside = [&](const Point<dim> &x)
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < -tol || x[d] > 1 + tol)
        return false;
    return true;
  };
  unsigned int c_found = maps.size();
  if (inside(xi))
  {
    c_found = 0;
    xc = xi;
  }
  else
  {
    const Point<dim> x = maps[0].to_real(xi);
    double best = slack;
    for (unsigned int c = 1; c < maps.size() && best > 0.; ++c)
    {
      const Point<dim> y = maps[c].to_unit(x);
      double outside = 0;
      for (unsigned int d = 0; d < dim; ++d)
        outside = std::max(outside, std::max(-y[d], y[d] - 1.));
      if (outside < best)
      {
        best = std::max(outside, 0.);
        c_found = c;
        xc = y;
      }
    }
  }
  return c_found;
}
} // namespace

void LocalMap::apply(const Vector<double> &global, Vector<double> &local,
                     unsigned int stride, unsigned int offset) const
{
  const SlabLayout slab{stride};
  local.reinit(matrix.m());
  for (unsigned int m = 0; m < matrix.m(); ++m)
  {
    double s = 0;
    for (unsigned int c = 0; c < dofs.size(); ++c)
      s += matrix(m, c) * global(slab.index(dofs[c], offset));
    local(m) = s;
  }
}

template <int dim>
SpatialOperators<dim>::SpatialOperators(const DoFHandler<dim> &dofs,
                                        unsigned int weight_degree)
    : dofs(dofs), p(dofs.get_fe().degree), fe_w(weight_degree)
{
  const QGaussLobatto<1> q(p + 1);
  for (unsigned int k = 0; k < q.size(); ++k)
    gl.push_back(q.point(k)[0]);
  // R_i: (R_i w)(xi_m) = sum_a L_a(xi_m[i]) w(xi_m with xi[i] = a)
  const auto &pts = fe_w.get_unit_support_points();
  const unsigned int n = fe_w.n_dofs_per_cell();
  R.assign(dim + 1, FullMatrix<double>(n, n));
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int m = 0; m < n; ++m)
      for (unsigned int a = 0; a < gl.size(); ++a)
      {
        Point<dim> x = pts[m];
        x[i] = gl[a];
        const double L = lagrange(gl, a, pts[m][i]);
        for (unsigned int l = 0; l < n; ++l)
          R[i](m, l) += L * fe_w.shape_value(l, x);
      }
  R[dim] = R[0];
  for (unsigned int i = 1; i < dim; ++i)
  {
    FullMatrix<double> t(n, n);
    R[i].mmult(t, R[dim]);
    R[dim] = t;
  }
}

template <int dim>
FullMatrix<double>
SpatialOperators<dim>::interpolation_from(const FiniteElement<dim> &fe) const
{
  const auto &pts = fe_w.get_unit_support_points();
  FullMatrix<double> I(fe_w.n_dofs_per_cell(), fe.n_dofs_per_cell());
  for (unsigned int m = 0; m < pts.size(); ++m)
    for (unsigned int l = 0; l < fe.n_dofs_per_cell(); ++l)
      I(m, l) = fe.shape_value(l, pts[m]);
  return I;
}

template <int dim>
std::vector<double> SpatialOperators<dim>::extended_nodes(double lo, double hi) const
{
  std::vector<double> x = gl;
  if (hi > 1. + 1e-10)
    for (unsigned int k = 1; k <= p; ++k)
      x.push_back(1. + (hi - 1.) * gl[k]);
  else
    for (unsigned int k = 0; k < p; ++k)
      x.push_back(lo * (1. - gl[k]));
  std::sort(x.begin(), x.end());
  return x;
}

template <int dim>
typename SpatialOperators<dim>::cell_iterator
SpatialOperators<dim>::partner(const cell_iterator &K, unsigned int i) const
{
  for (unsigned int f = 2 * i; f < 2 * i + 2; ++f)
    if (!K->at_boundary(f) && K->level() > 0)
    {
      const auto N = K->neighbor(f);
      if (N->is_active() && N->level() == K->level() && N->parent() == K->parent() &&
          (K->parent()->refinement_case() & RefinementCase<dim>::cut_axis(i)))
        return cell_iterator(&dofs.get_triangulation(), N->level(), N->index(), &dofs);
    }
  for (unsigned int f = 2 * i; f < 2 * i + 2; ++f)
    if (!K->at_boundary(f) && !K->face(f)->has_children())
    {
      const auto N = K->neighbor(f);
      if (N->is_active())
        return cell_iterator(&dofs.get_triangulation(), N->level(), N->index(), &dofs);
    }
  return cell_iterator();
}

template <int dim>
LocalMap SpatialOperators<dim>::directional_lift(const cell_iterator &K,
                                                 unsigned int i) const
{
  const auto P = partner(K, i);
  if (P.state() != IteratorState::valid)
    return LocalMap();
  std::vector<std::vector<double>> nodes(dim, gl);
  const auto [lo, hi] = CellMap<dim>(K).extent(P, i);
  nodes[i] = extended_nodes(lo, hi);
  return build(K, nodes, {K, P});
}

template <int dim>
LocalMap SpatialOperators<dim>::patch_lift(const cell_iterator &K) const
{
  if (K->level() == 0)
    return LocalMap();
  const auto parent = K->parent();
  std::vector<cell_iterator> cells{K};
  for (unsigned int c = 0; c < parent->n_children(); ++c)
  {
    if (!parent->child(c)->is_active())
      return LocalMap();
    if (parent->child(c)->index() != K->index())
      cells.emplace_back(&dofs.get_triangulation(), parent->child(c)->level(),
                         parent->child(c)->index(), &dofs);
  }
  std::vector<std::vector<double>> nodes(dim, gl);
  for (unsigned int i = 0; i < dim; ++i)
    if (parent->refinement_case() & RefinementCase<dim>::cut_axis(i))
    {
      const auto [lo, hi] = CellMap<dim>(K).extent(parent, i);
      nodes[i] = extended_nodes(lo, hi);
    }
  return build(K, nodes, cells);
}

template <int dim>
LocalMap SpatialOperators<dim>::build(const cell_iterator & /*K = candidates[0]*/,
                                      const std::vector<std::vector<double>> &nodes,
                                      const std::vector<cell_iterator> &candidates) const
{
  const auto &fe = dofs.get_fe();
  const unsigned int np = fe.n_dofs_per_cell(), nw = fe_w.n_dofs_per_cell();
  LocalMap map;
  map.exists = true;
  map.dofs.resize(candidates.size() * np);
  std::vector<types::global_dof_index> idx(np);
  for (unsigned int c = 0; c < candidates.size(); ++c)
  {
    candidates[c]->get_dof_indices(idx);
    std::copy(idx.begin(), idx.end(), map.dofs.begin() + c * np);
  }
  map.matrix.reinit(nw, map.dofs.size());

  // tensor grid of nodes; value of u at each grid point as a row over map.dofs
  std::vector<unsigned int> n(dim), a(dim, 0);
  unsigned int n_grid = 1;
  for (unsigned int d = 0; d < dim; ++d)
    n_grid *= (n[d] = nodes[d].size());
  const auto &wpts = fe_w.get_unit_support_points();
  std::vector<CellMap<dim>> maps;
  for (const auto &c : candidates)
    maps.emplace_back(c);
  std::vector<double> phi(np); // the primal shape functions at one grid point
  for (unsigned int g = 0; g < n_grid; ++g)
  {
    Point<dim> xi;
    for (unsigned int d = 0, rest = g; d < dim; ++d)
    {
      a[d] = rest % n[d];
      rest /= n[d];
      xi[d] = nodes[d][a[d]];
    }
    Point<dim> xc;
    const unsigned int c_found = locate(maps, xi, xc);
    if (c_found == candidates.size())
      return LocalMap();
    for (unsigned int d = 0; d < dim; ++d)
      xc[d] = std::min(1., std::max(0., xc[d]));
    for (unsigned int l = 0; l < np; ++l)
      phi[l] = fe.shape_value(l, xc);
    for (unsigned int m = 0; m < nw; ++m)
    {
      double L = 1;
      for (unsigned int d = 0; d < dim; ++d)
        L *= lagrange(nodes[d], a[d], wpts[m][d]);
      if (L != 0.)
        for (unsigned int l = 0; l < np; ++l)
          map.matrix(m, c_found * np + l) += L * phi[l];
    }
  }
  return map;
}

template class SpatialOperators<2>;
} // namespace anisodwr
