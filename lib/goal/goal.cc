#include "goal/goal.h"

#include "config/errors.h"
#include "slab/kronecker.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <map>
#include <cmath>

namespace anisodwr
{
using namespace dealii;

double mollifier_constant(unsigned int dim, double s)
{
  // int_{R^d} exp(1 - 1/(1-|y|^2)) dy = |S^{d-1}| int_0^1 exp(1 - 1/(1-rho^2)) rho^{d-1}
  // drho
  const QIterated<1> q(QGauss<1>(8), 400);
  double radial = 0;
  for (unsigned int i = 0; i < q.size(); ++i)
  {
    const double rho = q.point(i)[0];
    radial +=
        q.weight(i) * std::exp(1. - 1. / (1. - rho * rho)) * std::pow(rho, dim - 1.);
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

namespace
{
template <int dim> Point<dim> to_point(const GoalSpec &goal, const std::vector<double> &v)
{
  if (v.size() != dim)
    throw InputError("goal '" + goal.name + "': expected " + std::to_string(dim) +
                     " coordinates, got " + std::to_string(v.size()));
  Point<dim> p;
  for (unsigned int d = 0; d < dim; ++d)
    p[d] = v[d];
  return p;
}
} // namespace

/// One goal of a LocalGoal: its density (mollifier or 1/|rectangle|) or, for s = 0,
/// the point and the cell that holds it.
template <int dim> struct LocalGoal<dim>::Part
{
  GoalSpec goal;
  Point<dim> c, lo, hi;
  double C = 0, area = 1;
  bool dirac = false;
  typename Triangulation<dim>::active_cell_iterator dirac_cell;
  Point<dim> dirac_unit;
  /// FEValues on iterated Gauss rules, one per number of sub-cells (built on demand)
  mutable std::map<unsigned int, std::unique_ptr<FEValues<dim>>> values;

  /// Sub-cells per direction on `cell`: at most s/16 wide for mollifiers (at most 64
  /// per direction), 8 for a cell cut by a rectangle's edge, 1 inside it.
  unsigned int sub_cells(const typename Triangulation<dim>::active_cell_iterator &cell) const
  {
    if (goal.kind == "point")
    {
      const double n = std::ceil(16. * cell->diameter() / goal.radius);
      unsigned int k = 1;
      while (k < n && k < 64)
        k *= 2;
      return k;
    }
    for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
      for (unsigned int d = 0; d < dim; ++d)
        if (cell->vertex(v)[d] < lo[d] || cell->vertex(v)[d] > hi[d])
          return 8;
    return 1;
  }
  FEValues<dim> &fe_values(unsigned int n, const Mapping<dim> &mapping,
                           const FiniteElement<dim> &fe) const
  {
    auto &v = values[n];
    if (!v)
      v = std::make_unique<FEValues<dim>>(
        mapping, fe, QIterated<dim>(QGauss<1>(fe.degree + 2), n),
        update_values | update_quadrature_points | update_JxW_values);
    return *v;
  }

  double density(const Point<dim> &x) const
  {
    if (goal.kind == "point")
      return mollifier(x, c, goal.radius, C);
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < lo[d] || x[d] > hi[d])
        return 0.;
    return 1. / area;
  }
  bool meets(const typename Triangulation<dim>::active_cell_iterator &cell) const
  {
    if (goal.kind == "point")
      return cell->center().distance(c) <= goal.radius + cell->diameter();
    for (unsigned int d = 0; d < dim; ++d)
    {
      double a = 1e300, b = -1e300;
      for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
      {
        a = std::min(a, cell->vertex(v)[d]);
        b = std::max(b, cell->vertex(v)[d]);
      }
      if (b < lo[d] || a > hi[d])
        return false;
    }
    return true;
  }
};

template <int dim>
LocalGoal<dim>::LocalGoal(const Mapping<dim> &mapping, const FiniteElement<dim> &fe,
                          const Triangulation<dim> &tria,
                          const std::vector<GoalSpec> &goals, bool over_time)
    : mapping(mapping), fe(fe)
{
  for (const auto &goal : goals)
  {
    if (goal.over_time != over_time)
      continue;
    auto part = std::make_shared<Part>();
    part->goal = goal;
    if (goal.kind == "point")
    {
      part->c = to_point<dim>(goal, goal.center);
      if (goal.radius == 0.)
      {
        part->dirac = true;
        const auto found =
            GridTools::find_active_cell_around_point(mapping, tria, part->c);
        part->dirac_cell = found.first;
        part->dirac_unit = found.second;
      }
      else
        part->C = mollifier_constant(dim, goal.radius);
    }
    else if (goal.kind == "mean")
    {
      part->lo = to_point<dim>(goal, goal.lower);
      part->hi = to_point<dim>(goal, goal.upper);
      for (unsigned int d = 0; d < dim; ++d)
        part->area *= part->hi[d] - part->lo[d];
      if (!(part->area > 0))
        throw InputError("goal '" + goal.name + "': the rectangle has no area");
    }
    else
      throw InputError("goal '" + goal.name + "': unknown kind '" + goal.kind +
                       "'; expected point or mean");
    parts.push_back(part);
  }
}

template <int dim>
bool LocalGoal<dim>::cell_vector(
    const typename Triangulation<dim>::active_cell_iterator &cell,
    Vector<double> &j) const
{
  j.reinit(fe.n_dofs_per_cell());
  bool nonzero = false;
  for (const auto &part : parts)
  {
    if (part->dirac)
    {
      if (cell == part->dirac_cell)
      {
        for (unsigned int l = 0; l < j.size(); ++l)
          j(l) += part->goal.weight * fe.shape_value(l, part->dirac_unit);
        nonzero = true;
      }
      continue;
    }
    if (!part->meets(cell))
      continue;
    FEValues<dim> &fv = part->fe_values(part->sub_cells(cell), mapping, fe);
    fv.reinit(cell);
    for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
    {
      const double w =
          part->goal.weight * part->density(fv.quadrature_point(q)) * fv.JxW(q);
      if (w != 0.)
      {
        nonzero = true;
        for (unsigned int l = 0; l < j.size(); ++l)
          j(l) += w * fv.shape_value(l, q);
      }
    }
  }
  return nonzero;
}

template <int dim>
void assemble_goal_vector(const Space<dim> &space, const GoalSpec &goal,
                          Vector<double> &j)
{
  GoalSpec unit = goal;
  unit.weight = 1;
  const LocalGoal<dim> local(space.mapping(), space.finite_element(),
                             space.dof_handler().get_triangulation(), {unit},
                             goal.over_time);
  j.reinit(space.n_dofs());
  Vector<double> jc;
  std::vector<types::global_dof_index> idx(space.finite_element().n_dofs_per_cell());
  for (const auto &cell : space.dof_handler().active_cell_iterators())
    if (local.cell_vector(cell, jc))
    {
      cell->get_dof_indices(idx);
      for (unsigned int i = 0; i < idx.size(); ++i)
        j(idx[i]) += jc(i);
    }
}

template <int dim>
GoalVectors assemble_goal_vectors(const Space<dim> &space,
                                  const std::vector<GoalSpec> &goals)
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

double evaluate_goal(const GoalVectors &j, const TimeMesh &mesh,
                     const TemporalBasis &basis, const std::vector<Vector<double>> &U)
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
namespace
{
/// Adaptive bisection with 10-point Gauss on each piece until two levels agree.
template <typename F>
double adaptive(const F &f, double a, double b, double tol, unsigned int depth = 0)
{
  static const QGauss<1> q(10);
  auto gauss = [&](double lo, double hi)
  {
    double s = 0;
    for (unsigned int i = 0; i < q.size(); ++i)
      s += q.weight(i) * f(lo + (hi - lo) * q.point(i)[0]);
    return s * (hi - lo);
  };
  const double m = 0.5 * (a + b), whole = gauss(a, b), left = gauss(a, m),
               right = gauss(m, b);
  if (std::abs(left + right - whole) <= tol || depth > 40)
    return left + right;
  return adaptive(f, a, m, 0.5 * tol, depth + 1) +
         adaptive(f, m, b, 0.5 * tol, depth + 1);
}
} // namespace

template <int dim>
double exact_goal(const Scene<dim> &scene, const GoalSpec &goal, double tol)
{
  static_assert(dim == 2, "exact goals are implemented in 2D");
  const auto *u = scene.exact();
  if (!u)
    throw InputError("goal '" + goal.name + "': the scene has no exact solution");
  auto spatial = [&](double t) -> double
  {
    if (goal.kind == "point")
    {
      const Point<dim> c = to_point<dim>(goal, goal.center);
      if (goal.radius == 0.)
        return u->value(c, t);
      const double s = goal.radius, C = mollifier_constant(dim, s);
      return adaptive(
          [&](double x)
          {
            const double h = std::sqrt(std::max(0., s * s - (x - c[0]) * (x - c[0])));
            return adaptive(
                [&](double y)
                {
                  const Point<dim> p(x, y);
                  return mollifier(p, c, s, C) * u->value(p, t);
                },
                c[1] - h, c[1] + h, tol * C * s * s);
          },
          c[0] - s, c[0] + s, tol);
    }
    const Point<dim> lo = to_point<dim>(goal, goal.lower),
                     hi = to_point<dim>(goal, goal.upper);
    const double area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    return adaptive(
               [&](double x)
               {
                 return adaptive([&](double y) { return u->value(Point<dim>(x, y), t); },
                                 lo[1], hi[1], tol * area);
               },
               lo[0], hi[0], tol * area) /
           area;
  };
  if (!goal.over_time)
    return spatial(scene.end_time);
  // composite 12-point Gauss in time on 16 panels (the scenes are smooth in t)
  const QIterated<1> q(QGauss<1>(12), 16);
  double J = 0;
  for (unsigned int i = 0; i < q.size(); ++i)
    J += q.weight(i) * scene.end_time * spatial(q.point(i)[0] * scene.end_time);
  return J;
}

template double exact_goal<2>(const Scene<2> &, const GoalSpec &, double);
template class LocalGoal<2>;
template void assemble_goal_vector<2>(const Space<2> &, const GoalSpec &,
                                      Vector<double> &);
template GoalVectors assemble_goal_vectors<2>(const Space<2> &,
                                              const std::vector<GoalSpec> &);
} // namespace anisodwr
