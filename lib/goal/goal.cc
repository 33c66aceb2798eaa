#include "goal/goal.h"

#include "base/errors.h"
#include "time/slab_vector.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <queue>
#include <sstream>

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

/// The largest quadrature rule of a goal part on one cell whose FEValues are built at
/// once (and cached per sub-cell count); larger ones are evaluated in slices.
constexpr unsigned int max_rule_points = 4096;

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
  /// FEValues on iterated Gauss rules, one per number of sub-cells along each unit
  /// direction of the cell (built on demand)
  using SubCells = std::array<unsigned int, dim>;
  mutable std::map<SubCells, std::unique_ptr<FEValues<dim>>> values;

  /// Sub-cells along each unit direction of `cell`: for mollifiers at most s/16 wide
  /// along that direction (a power of two), so that a long thin cell near the goal is
  /// subdivided along its length only, with at most 64^dim sub-cells in all (a long
  /// thin cell: up to 1024 along its length); 32 per direction for a cell cut by a
  /// rectangle's edge, 1 inside it. `capped` tells whether a cap kept a sub-cell wider
  /// than s/16 (a cell much larger than the mollifier's support).
  SubCells sub_cells(const typename Triangulation<dim>::active_cell_iterator &cell,
                     bool *capped = nullptr) const
  {
    SubCells n;
    if (capped)
      *capped = false;
    if (goal.kind == GoalKind::point)
    {
      std::array<double, dim> want;
      for (unsigned int d = 0; d < dim; ++d)
      {
        want[d] = std::ceil(16. * edge_length(cell, d) / goal.radius);
        n[d] = 1;
        while (n[d] < want[d] && n[d] < 1024)
          n[d] *= 2;
      }
      // at most 64^dim sub-cells: halve the largest count (a large square cell gets
      // 64 x 64, a long thin one up to 1024 along its length)
      auto product = [&]()
      {
        unsigned int k = 1;
        for (unsigned int m : n)
          k *= m;
        return k;
      };
      while (product() > std::pow(64u, dim))
        *std::max_element(n.begin(), n.end()) /= 2;
      if (capped)
        for (unsigned int d = 0; d < dim; ++d)
          *capped |= n[d] < want[d];
      return n;
    }
    n.fill(1);
    for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
      for (unsigned int d = 0; d < dim; ++d)
        if (cell->vertex(v)[d] < lo[d] || cell->vertex(v)[d] > hi[d])
          n.fill(32);
    return n;
  }
  /// The longest edge of `cell` along unit direction d (vertices v and v + 2^d).
  static double edge_length(const typename Triangulation<dim>::active_cell_iterator &cell,
                            unsigned int d)
  {
    double length = 0;
    for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
      if (!(v & (1u << d)))
        length = std::max(length, cell->vertex(v).distance(cell->vertex(v | (1u << d))));
    return length;
  }
  /// The tensor product of q0 (index running fastest) and q1. Built point by point:
  /// deal.II's tensor-product constructor asserts (Debug) that the weights sum to 1,
  /// which a clipped rule or a slice of a rule does not.
  static Quadrature<dim> tensor_rule(const Quadrature<1> &q0, const Quadrature<1> &q1)
  {
    static_assert(dim == 2, "LocalGoal: tensor rule for dim = 2");
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
  FEValues<dim> &fe_values(const SubCells &n, const Mapping<dim> &mapping,
                           const FiniteElement<dim> &fe) const
  {
    auto &v = values[n];
    if (!v)
    {
      const QGauss<1> base(fe.degree + 2);
      v = std::make_unique<FEValues<dim>>(
          mapping, fe, tensor_rule(QIterated<1>(base, n[0]), QIterated<1>(base, n[1])),
          update_values | update_quadrature_points | update_JxW_values);
    }
    return *v;
  }
  /// The rule for a cell much larger than the mollifier's support: the iterated Gauss
  /// rule restricted to the box of unit coordinates that holds the support (the
  /// preimage of the circle |x - c| = s, sampled at 64 points, widened by 2% and
  /// clipped to the unit cell), with sub-cells at most s/32 wide (a power of two, at
  /// most 128 along a direction: the widened support spans 2.04 s; finer than s/16
  /// because the support is cut by cell edges here, where the composite rule loses the
  /// bump's smooth end). Returns false if a sample point cannot be mapped back (then
  /// `rule` is left untouched); true otherwise, with `empty` set if that box is empty
  /// (the support misses the cell) and `rule` (the 1D rules per direction) set if not.
  bool clipped_rule(const typename Triangulation<dim>::active_cell_iterator &cell,
                    const Mapping<dim> &mapping, const FiniteElement<dim> &fe,
                    std::array<Quadrature<1>, dim> &rule, bool &empty) const
  {
    static_assert(dim == 2, "LocalGoal: clipped rule for dim = 2");
    empty = false;
    Point<dim> a, b;
    for (unsigned int d = 0; d < dim; ++d)
      a[d] = 1e300, b[d] = -1e300;
    constexpr unsigned int samples = 64;
    for (unsigned int k = 0; k < samples; ++k)
    {
      const double phi = 2. * M_PI * k / samples;
      const Point<dim> x = c + goal.radius * Point<dim>(std::cos(phi), std::sin(phi));
      Point<dim> xi;
      try
      {
        xi = mapping.transform_real_to_unit_cell(cell, x);
      }
      catch (...)
      {
        return false;
      }
      for (unsigned int d = 0; d < dim; ++d)
        a[d] = std::min(a[d], xi[d]), b[d] = std::max(b[d], xi[d]);
    }
    std::array<Quadrature<1>, dim> q;
    const QGauss<1> base(fe.degree + 2);
    for (unsigned int d = 0; d < dim; ++d)
    {
      const double margin = 0.02 * (b[d] - a[d]);
      const double lo_d = std::max(0., a[d] - margin), hi_d = std::min(1., b[d] + margin);
      if (!(hi_d > lo_d))
      {
        empty = true;
        return true;
      }
      unsigned int m = 1;
      while (m < 1024 && m * goal.radius < 32. * (hi_d - lo_d) * edge_length(cell, d))
        m *= 2;
      const QIterated<1> unit(base, m);
      std::vector<Point<1>> points(unit.size());
      std::vector<double> weights(unit.size());
      for (unsigned int i = 0; i < unit.size(); ++i)
      {
        points[i][0] = lo_d + (hi_d - lo_d) * unit.point(i)[0];
        weights[i] = (hi_d - lo_d) * unit.weight(i);
      }
      q[d] = Quadrature<1>(points, weights);
    }
    rule = q;
    return true;
  }

  /// For a mean goal on a cell that is an axis-parallel rectangle mapped affinely (its
  /// vertices form the box and the mapping puts the centre and the edge midpoints where
  /// the bilinear map of the vertices does): the Gauss rule of degree fe.degree + 2 on
  /// the cell's part inside the goal's rectangle, in `rule`; it integrates the shape
  /// functions times the constant density exactly. Returns false for other cells (and
  /// for point goals); true with `empty` set if the two do not overlap.
  bool box_rule(const typename Triangulation<dim>::active_cell_iterator &cell,
                const Mapping<dim> &mapping, const FiniteElement<dim> &fe,
                std::array<Quadrature<1>, dim> &rule, bool &empty) const
  {
    static_assert(dim == 2, "LocalGoal: box rule for dim = 2");
    if (goal.kind != GoalKind::mean)
      return false;
    const Point<dim> a = cell->vertex(0), b = cell->vertex(3);
    const double tol = 1e-12 * a.distance(b);
    if (!(b[0] > a[0] && b[1] > a[1]) ||
        cell->vertex(1).distance(Point<dim>(b[0], a[1])) > tol ||
        cell->vertex(2).distance(Point<dim>(a[0], b[1])) > tol)
      return false;
    for (const auto &xi : {Point<dim>(0.5, 0.5), Point<dim>(0.5, 0.), Point<dim>(0.5, 1.),
                           Point<dim>(0., 0.5), Point<dim>(1., 0.5)})
    {
      const Point<dim> x = mapping.transform_unit_to_real_cell(cell, xi);
      if (x.distance(Point<dim>(a[0] + xi[0] * (b[0] - a[0]),
                                a[1] + xi[1] * (b[1] - a[1]))) > tol)
        return false;
    }
    const QGauss<1> base(fe.degree + 2);
    empty = false;
    for (unsigned int d = 0; d < dim; ++d)
    {
      const double lo_d = std::max(0., (lo[d] - a[d]) / (b[d] - a[d])),
                   hi_d = std::min(1., (hi[d] - a[d]) / (b[d] - a[d]));
      if (!(hi_d > lo_d))
      {
        empty = true;
        return true;
      }
      std::vector<Point<1>> points(base.size());
      std::vector<double> weights(base.size());
      for (unsigned int i = 0; i < base.size(); ++i)
      {
        points[i][0] = lo_d + (hi_d - lo_d) * base.point(i)[0];
        weights[i] = (hi_d - lo_d) * base.weight(i);
      }
      rule[d] = Quadrature<1>(points, weights);
    }
return true;
  }

  double density(const Point<dim> &x) const
  {
    if (goal.kind == GoalKind::point)
      return mollifier(x, c, goal.radius, C);
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < lo[d] || x[d] > hi[d])
        return 0.;
    return 1. / area;
  }
  bool meets(const typename Triangulation<dim>::active_cell_iterator &cell) const
  {
    if (goal.kind == GoalKind::point)
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
    if (goal.kind == GoalKind::point)
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
    else if (goal.kind == GoalKind::mean)
    {
      part->lo = to_point<dim>(goal, goal.lower);
      part->hi = to_point<dim>(goal, goal.upper);
      for (unsigned int d = 0; d < dim; ++d)
        part->area *= part->hi[d] - part->lo[d];
      if (!(part->area > 0))
        throw InputError("goal '" + goal.name + "': the rectangle has no area");
    }
    else
      throw InputError("goal '" + goal.name + "': unknown kind '" + name(goal.kind) +
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
    const auto add = [&](FEValues<dim> &fv)
    {
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
    };
    bool capped = false, empty = false;
    const auto n = part->sub_cells(cell, &capped);
    std::array<Quadrature<1>, dim> q;
    // a cell cut by a rectangle's edge: exactly where the cell is an axis-parallel box
    if ((n[0] > 1 && part->box_rule(cell, mapping, fe, q, empty)) ||
        (capped && part->clipped_rule(cell, mapping, fe, q, empty)))
    {
      if (empty)
        continue;
    }
    else
    {
      const QGauss<1> base(fe.degree + 2);
      if (n[0] * n[1] * base.size() * base.size() <= max_rule_points)
      {
        add(part->fe_values(n, mapping, fe));
        continue;
      }
      q[0] = QIterated<1>(base, n[0]);
      q[1] = QIterated<1>(base, n[1]);
    }
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
      FEValues<dim> fv(mapping, fe, Part::tensor_rule(q0, part_q1),
                       update_values | update_quadrature_points | update_JxW_values);
      add(fv);
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

template class LocalGoal<2>;
template void assemble_goal_vector<2>(const Space<2> &, const GoalSpec &,
                                      Vector<double> &);
template GoalVectors assemble_goal_vectors<2>(const Space<2> &,
                                              const std::vector<GoalSpec> &);
} // namespace anisodwr
