#include "goal/goal.h"

#include "config/errors.h"
#include "slab/kronecker.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>

namespace anisodwr
{
using namespace dealii;

double mollifier_constant(unsigned int dim, double s)
{
  // int_{R^d} exp(1 - 1/(1-|y|^2)) dy = |S^{d-1}| int_0^1 exp(1 - 1/(1-rho^2)) rho^{d-1} drho
  const QIterated<1> q(QGauss<1>(8), 400);
  double radial = 0;
  for (unsigned int i = 0; i < q.size(); ++i)
  {
    const double rho = q.point(i)[0];
    radial += q.weight(i) * std::exp(1. - 1. / (1. - rho * rho)) * std::pow(rho, dim - 1.);
  }
  const double sphere = dim == 1 ? 2. : dim == 2 ? 2. * M_PI : 4. * M_PI;
  return 1. / (sphere * radial * std::pow(s, double(dim)));
}

template <int dim>
double mollifier(const Point<dim> &x, const Point<dim> &c, double s, double C)
{
  const double q = (x - c).norm_square() / (s * s);
  return q < 1. ? C * std::exp(1. - 1. / (1. - q)) : 0.;
}

template <int dim>
void assemble_goal_vector(const Space<dim> &space, const GoalSpec &goal, Vector<double> &j)
{
  j.reinit(space.n_dofs());
  const auto to_point = [&](const std::vector<double> &v) {
    if (v.size() != dim)
      throw InputError("goal '" + goal.name + "': expected " + std::to_string(dim) +
                       " coordinates");
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = v[d];
    return p;
  };
  if (goal.kind == "point" && goal.radius == 0.)
  {
    VectorTools::create_point_source_vector(space.mapping(), space.dof_handler(),
                                            to_point(goal.center), j);
    return;
  }
  // Iterated Gauss on the cells that meet the support, with sub-cells of at most
  // 1/16 of the mollifier radius (at most 64 per direction), resolves the
  // mollifier or the rectangle's edges inside a cell.
  unsigned int n_sub = 8;
  if (goal.kind == "point")
  {
    double h = 0;
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->center().distance(to_point(goal.center)) <= goal.radius + cell->diameter())
        h = std::max(h, cell->diameter());
    n_sub = std::min(64u, std::max(8u, unsigned(std::ceil(16. * h / goal.radius))));
  }
  const QIterated<dim> quad(QGauss<1>(space.degree() + 2), n_sub);
  FEValues<dim> fv(space.mapping(), space.finite_element(), quad,
                   update_values | update_quadrature_points | update_JxW_values);
  const unsigned int n = space.finite_element().n_dofs_per_cell();
  std::vector<types::global_dof_index> idx(n);
  Point<dim> c, lo, hi;
  double C = 0, area = 1;
  if (goal.kind == "point")
  {
    c = to_point(goal.center);
    C = mollifier_constant(dim, goal.radius);
  }
  else if (goal.kind == "mean")
  {
    lo = to_point(goal.lower);
    hi = to_point(goal.upper);
    for (unsigned int d = 0; d < dim; ++d)
      area *= hi[d] - lo[d];
    if (!(area > 0))
      throw InputError("goal '" + goal.name + "': the rectangle has no area");
  }
  else
    throw InputError("goal '" + goal.name + "': unknown kind '" + goal.kind +
                     "'; expected point or mean");
  auto weight = [&](const Point<dim> &x) {
    if (goal.kind == "point")
      return mollifier(x, c, goal.radius, C);
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < lo[d] || x[d] > hi[d])
        return 0.;
    return 1. / area;
  };
  for (const auto &cell : space.dof_handler().active_cell_iterators())
  {
    if (goal.kind == "point" &&
        cell->center().distance(c) > goal.radius + cell->diameter())
      continue;
    fv.reinit(cell);
    cell->get_dof_indices(idx);
    for (unsigned int q = 0; q < quad.size(); ++q)
    {
      const double w = weight(fv.quadrature_point(q)) * fv.JxW(q);
      if (w != 0.)
        for (unsigned int i = 0; i < n; ++i)
          j(idx[i]) += w * fv.shape_value(i, q);
    }
  }
}

template <int dim>
GoalVectors assemble_goal_vectors(const Space<dim> &space, const std::vector<GoalSpec> &goals)
{
  GoalVectors g;
  Vector<double> j;
  for (const auto &goal : goals)
  {
    assemble_goal_vector(space, goal, j);
    Vector<double> &target = goal.over_time ? g.over_time : g.at_end;
    if (target.size() == 0)
      target.reinit(space.n_dofs());
    target.add(goal.weight, j);
  }
  return g;
}

namespace
{
/// int_0^1 l_k ds = row sums of the temporal mass matrix.
std::vector<double> basis_integrals(const TemporalBasis &basis)
{
  std::vector<double> s(basis.n_dofs(), 0.);
  for (unsigned int k = 0; k < basis.n_dofs(); ++k)
    for (unsigned int l = 0; l < basis.n_dofs(); ++l)
      s[k] += basis.mass()(k, l);
  return s;
}
} // namespace

void slab_goal_rhs(const GoalVectors &j, const TimeMesh &mesh, const TemporalBasis &basis,
                   unsigned int n, Vector<double> &rhs)
{
  const unsigned int m = basis.n_dofs();
  const auto nd = j.over_time.size() ? j.over_time.size() : j.at_end.size();
  rhs.reinit(nd * m);
  if (j.over_time.size())
    add_kron_vector(mesh.tau(n), basis_integrals(basis), j.over_time, rhs);
  if (j.at_end.size() && n + 1 == mesh.n_slabs())
    add_kron_vector(1., basis.right_trace(), j.at_end, rhs);
}

double evaluate_goal(const GoalVectors &j, const TimeMesh &mesh, const TemporalBasis &basis,
                     const std::vector<Vector<double>> &U)
{
  double J = 0;
  Vector<double> rhs;
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    slab_goal_rhs(j, mesh, basis, n, rhs);
    J += rhs * U[n];
  }
  return J;
}

template double mollifier<2>(const Point<2> &, const Point<2> &, double, double);
template void assemble_goal_vector<2>(const Space<2> &, const GoalSpec &, Vector<double> &);
template GoalVectors assemble_goal_vectors<2>(const Space<2> &, const std::vector<GoalSpec> &);
} // namespace anisodwr
