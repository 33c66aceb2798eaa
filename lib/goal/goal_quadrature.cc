#include "goal/goal_quadrature.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_tools.h>
#include <deal.II/fe/mapping_q.h>

namespace anisodwr
{
using namespace dealii;

template <int dim>
DensityGoalPart<dim>::DensityGoalPart(const Mapping<dim> &mapping,
                                      const FiniteElement<dim> &fe)
    : mapping(mapping), fe(fe)
{
  const auto *q = dynamic_cast<const MappingQ<dim> *>(&mapping);
  if (!q || q->get_degree() != 1 || !dynamic_cast<const FE_Q<dim> *>(&fe))
    return;
  // FE_Q's shape function with lexicographic index a + (k+1) b is the product of the
  // 1D Lagrange polynomials through its support points' x coordinates a and b
  lex_to_fe = FETools::lexicographic_to_hierarchic_numbering<dim>(fe.degree);
  std::vector<Point<1>> nodes(fe.degree + 1);
  for (unsigned int a = 0; a <= fe.degree; ++a)
    nodes[a][0] = fe.get_unit_support_points()[lex_to_fe[a]][0];
  basis_1d = Polynomials::generate_complete_Lagrange_basis(nodes);
  tensor = true;
}

template <int dim>
double DensityGoalPart<dim>::edge_length(const CellIterator &cell, unsigned int d)
{
  double length = 0;
  for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
    if (!(v & (1u << d)))
      length = std::max(length, cell->vertex(v).distance(cell->vertex(v | (1u << d))));
  return length;
}

template <int dim>
Quadrature<dim> DensityGoalPart<dim>::tensor_rule(const Quadrature<1> &q0,
                                                  const Quadrature<1> &q1)
{
  static_assert(dim == 2, "goal quadrature: tensor rule for dim = 2");
  std::vector<Point<dim>> points;
  std::vector<double> weights;
  points.reserve(q0.size() * q1.size());
  weights.reserve(q0.size() * q1.size());
  for (unsigned int j = 0; j < q1.size(); ++j)
    for (unsigned int i = 0; i < q0.size(); ++i)
    {
      points.emplace_back(q0.point(i)[0], q1.point(j)[0]);
      weights.push_back(q0.weight(i) * q1.weight(j));
    }
  return Quadrature<dim>(points, weights);
}

template <int dim> Quadrature<1> DensityGoalPart<dim>::gauss_on(double lo, double hi) const
{
  const QGauss<1> base(base_points());
  std::vector<Point<1>> points(base.size());
  std::vector<double> weights(base.size());
  for (unsigned int i = 0; i < base.size(); ++i)
  {
    points[i][0] = lo + (hi - lo) * base.point(i)[0];
    weights[i] = (hi - lo) * base.weight(i);
  }
  return Quadrature<1>(points, weights);
}

template <int dim> FEValues<dim> &DensityGoalPart<dim>::fe_values(const SubCells &n) const
{
  auto &v = values[n];
  if (!v)
  {
    const QGauss<1> base(base_points());
    v = std::make_unique<FEValues<dim>>(
        mapping, fe, tensor_rule(QIterated<1>(base, n[0]), QIterated<1>(base, n[1])),
        update_values | update_quadrature_points | update_JxW_values);
  }
  return *v;
}

template <int dim>
bool DensityGoalPart<dim>::add_cell_vector(const CellIterator &cell, double weight,
                                           Vector<double> &j) const
{
  if (!meets(cell))
    return false;
  bool nonzero = false;
  const auto add = [&](FEValues<dim> &fv)
  {
    fv.reinit(cell);
    for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
    {
      const double w = weight * density(fv.quadrature_point(q)) * fv.JxW(q);
      if (w != 0.)
      {
        nonzero = true;
        for (unsigned int l = 0; l < j.size(); ++l)
          j(l) += w * fv.shape_value(l, q);
      }
    }
  };
  bool capped = false, empty = false;
  const SubCells n = sub_cells(cell, capped);
  Rule q;
  if (own_rule(cell, n, capped, q, empty))
  {
    if (empty)
      return false;
  }
  else
  {
    const QGauss<1> base(base_points());
    if (!tensor && n[0] * n[1] * base.size() * base.size() <= max_rule_points)
    {
      add(fe_values(n));
      return nonzero;
    }
    q[0] = QIterated<1>(base, n[0]);
    q[1] = QIterated<1>(base, n[1]);
  }
  if (tensor)
    return add_tensor(cell, q[0], q[1], weight, j);
  // A rule of a small support on a coarse cell can hold 10^5-10^6 points: it is
  // evaluated in slices of at most max_rule_points, so that its FEValues stay small.
  const Quadrature<1> &q0 = q[0], &q1 = q[1];
  const unsigned int slice = std::max<unsigned int>(1, max_rule_points / q0.size());
  for (unsigned int k0 = 0; k0 < q1.size(); k0 += slice)
  {
    const unsigned int k1 = std::min<unsigned int>(q1.size(), k0 + slice);
    const Quadrature<1> part_q1(
        std::vector<Point<1>>(q1.get_points().begin() + k0, q1.get_points().begin() + k1),
        std::vector<double>(q1.get_weights().begin() + k0, q1.get_weights().begin() + k1));
    FEValues<dim> fv(mapping, fe, tensor_rule(q0, part_q1),
                     update_values | update_quadrature_points | update_JxW_values);
    add(fv);
  }
  return nonzero;
}

template <int dim>
bool DensityGoalPart<dim>::add_tensor(const CellIterator &cell, const Quadrature<1> &q0,
                                      const Quadrature<1> &q1, double weight,
                                      Vector<double> &j) const
{
  static_assert(dim == 2, "goal quadrature: tensor evaluation for dim = 2");
  const unsigned int m = basis_1d.size(), n0 = q0.size(), n1 = q1.size();
  std::vector<double> f0(n0 * m), r(m), jl(m * m, 0.);
  for (unsigned int i = 0; i < n0; ++i)
    for (unsigned int a = 0; a < m; ++a)
      f0[i * m + a] = basis_1d[a].value(q0.point(i)[0]);
  const Point<dim> v0 = cell->vertex(0), v1 = cell->vertex(1), v2 = cell->vertex(2),
                   v3 = cell->vertex(3);
  // the bilinear map: dx/deta = e + xi g everywhere on the cell
  const Tensor<1, dim> e = v2 - v0, g = (v3 - v1) - (v2 - v0);
  bool nonzero = false;
  for (unsigned int k = 0; k < n1; ++k)
  {
    const double eta = q1.point(k)[0];
    // along xi at this eta: x = a + xi d
    const Tensor<1, dim> d = (v1 - v0) * (1. - eta) + (v3 - v2) * eta;
    const Point<dim> a = v0 + (v2 - v0) * eta;
    std::fill(r.begin(), r.end(), 0.);
    for (unsigned int i = 0; i < n0; ++i)
    {
      const double xi = q0.point(i)[0];
      const double w = density(a + d * xi);
      if (w == 0.)
        continue;
      const Tensor<1, dim> dy = e + g * xi;
      const double JxW = (d[0] * dy[1] - d[1] * dy[0]) * q0.weight(i) * q1.weight(k);
      const double c = weight * w * JxW;
      nonzero |= c != 0.;
      for (unsigned int l = 0; l < m; ++l)
        r[l] += c * f0[i * m + l];
    }
    for (unsigned int b = 0; b < m; ++b)
    {
      const double fb = basis_1d[b].value(eta);
      for (unsigned int l = 0; l < m; ++l)
        jl[l + m * b] += fb * r[l];
    }
  }
  for (unsigned int l = 0; l < m * m; ++l)
    j(lex_to_fe[l]) += jl[l];
  return nonzero;
}

template class DensityGoalPart<2>;
} // namespace anisodwr
