// goal.kind = point: the mollified point value int delta_{s,c} u dx (s = goal.radius),
// or for s = 0 the point value u(c) (a Dirac).
#include "base/errors.h"
#include "base/nested_quadrature.h"
#include "goal/goal.h"
#include "goal/goal_quadrature.h"
#include "scene/scene.h"
#include "space/space.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_tools.h>

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
template double mollifier<2>(const Point<2> &, const Point<2> &, double, double);

namespace
{
using Cell = Triangulation<2>::active_cell_iterator;

/// The centre of a point goal (GoalSpec::location: x, y).
Point<2> center(const GoalSpec &g)
{
  if (g.location.size() != 2)
    throw InputError("goal '" + g.name + "': expected 2 coordinates, got " +
                     std::to_string(g.location.size()));
  return Point<2>(g.location[0], g.location[1]);
}

/// Whether p lies in a cell of the space's mesh (through its mapping).
bool inside(const Space<2> &space, const Point<2> &p)
{
  try
  {
    const auto found = GridTools::find_active_cell_around_point(
        space.mapping(), space.dof_handler().get_triangulation(), p);
    return found.first.state() == IteratorState::valid;
  }
  catch (...)
  {
    return false;
  }
}

/// s = 0: the shape functions at the point, on the cell that holds it.
class DiracPart : public GoalPart<2>
{
public:
  DiracPart(const GoalSpec &g, const Mapping<2> &mapping, const FiniteElement<2> &fe,
            const Triangulation<2> &tria)
      : fe(fe)
  {
    const auto found = GridTools::find_active_cell_around_point(
        mapping, tria, center(g));
    cell = found.first;
    unit = found.second;
  }
  bool add_cell_vector(const Cell &c, double weight, Vector<double> &j) const override
  {
    if (c != cell)
      return false;
    for (unsigned int l = 0; l < j.size(); ++l)
      j(l) += weight * fe.shape_value(l, unit);
    return true;
  }

private:
  const FiniteElement<2> &fe;
  Cell cell;
  Point<2> unit;
};

/// s > 0: the mollifier of radius s about c.
class MollifierPart : public DensityGoalPart<2>
{
public:
  MollifierPart(const GoalSpec &g, const Mapping<2> &mapping, const FiniteElement<2> &fe)
      : DensityGoalPart<2>(mapping, fe), c(center(g)), s(g.radius),
        C(mollifier_constant(2, s))
  {
  }

protected:
  bool meets(const Cell &cell) const override
  {
    return cell->center().distance(c) <= s + cell->diameter();
  }
  double density(const Point<2> &x) const override { return mollifier(x, c, s, C); }

  /// At least 8 Gauss points per sub-cell and direction: the mollifier is smooth but no
  /// polynomial, and its derivatives grow steeply towards |x - c| = s. On sub-cells of
  /// s/16, the 2D mollifier integrates to a relative error of 1.2e-8 with 4 points (the
  /// rule of Q2), 1.5e-10 with 6 and 3.9e-12 with 8 (worst of three offsets of the
  /// sub-cells against c), so that J(u_h) is not off by more than the DWR estimate can
  /// see once the error falls to 1e-9.
  unsigned int base_points() const override { return std::max(fe.degree + 2, 8u); }

  /// At most s/16 wide along each unit direction (a power of two), so that a long thin
  /// cell near the goal is subdivided along its length only, with at most 64^2
  /// sub-cells in all (a long thin cell: up to 1024 along its length).
  SubCells sub_cells(const Cell &cell, bool &capped) const override
  {
    SubCells n;
    std::array<double, 2> want;
    for (unsigned int d = 0; d < 2; ++d)
    {
      want[d] = std::ceil(16. * edge_length(cell, d) / s);
      n[d] = 1;
      while (n[d] < want[d] && n[d] < 1024)
        n[d] *= 2;
    }
    // at most 64^2 sub-cells: halve the largest count (a large square cell gets
    // 64 x 64, a long thin one up to 1024 along its length)
    while (n[0] * n[1] > 64u * 64u)
      *std::max_element(n.begin(), n.end()) /= 2;
    capped = false;
    for (unsigned int d = 0; d < 2; ++d)
      capped |= n[d] < want[d];
    return n;
  }

  /// For a cell larger than the support (capped, or its iterated rule more than
  /// max_rule_points): the iterated Gauss rule restricted to the box of unit coordinates
  /// that holds the support (the preimage of the circle |x - c| = s, sampled at 64
  /// points, widened by 2% and clipped to the unit cell), with sub-cells at most s/16
  /// wide (a power of two, at most 1024 along a direction). False for smaller cells or
  /// if a sample point cannot be mapped back.
  bool own_rule(const Cell &cell, const SubCells &n, bool capped, Rule &rule,
                bool &empty) const override
  {
    const unsigned int n_base = base_points();
    if (!capped && n[0] * n[1] * n_base * n_base <= max_rule_points)
      return false;
    empty = false;
    Point<2> a(1e300, 1e300), b(-1e300, -1e300);
    constexpr unsigned int samples = 64;
    for (unsigned int k = 0; k < samples; ++k)
    {
      const double phi = 2. * M_PI * k / samples;
      const Point<2> x = c + s * Point<2>(std::cos(phi), std::sin(phi));
      Point<2> xi;
      try
      {
        xi = mapping.transform_real_to_unit_cell(cell, x);
      }
      catch (...)
      {
        return false;
      }
      for (unsigned int d = 0; d < 2; ++d)
        a[d] = std::min(a[d], xi[d]), b[d] = std::max(b[d], xi[d]);
    }
    Rule q;
    const QGauss<1> base(n_base);
    for (unsigned int d = 0; d < 2; ++d)
    {
      const double margin = 0.02 * (b[d] - a[d]);
      const double lo_d = std::max(0., a[d] - margin), hi_d = std::min(1., b[d] + margin);
      if (!(hi_d > lo_d))
      {
        empty = true;
        return true;
      }
      unsigned int m = 1;
      while (m < 1024 && m * s < 16. * (hi_d - lo_d) * edge_length(cell, d))
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

private:
  Point<2> c;
  double s, C;
};

class PointGoal : public GoalType
{
public:
  std::string name() const override { return "point"; }
  std::string doc() const override
  {
    return "mollified point values (goal.radius; 0: exact point values) at the points "
           "'x,y; x,y; ...' of goal.locations";
  }
  std::string noun() const override { return "point"; }
  std::string syntax() const override { return "x,y"; }
  std::string example() const override { return "0.4,0.55"; }
  unsigned int n_numbers() const override { return 2; }
  bool has_radius() const override { return true; }

  void set_location(const std::vector<double> &v, const Scene<2> &scene,
                    const std::string &bad, GoalSpec &g) const override
  {
    g.location = v;
    if (!scene.contains(Point<2>(v[0], v[1])))
      throw InputError(bad + "it lies outside the domain " + scene.domain_text() +
                       " of scene '" + scene.name() + "'");
  }

  std::unique_ptr<GoalPart<2>> part(const GoalSpec &g, const Scene<2> &,
                                    const Mapping<2> &mapping, const FiniteElement<2> &fe,
                                    const Triangulation<2> &tria, bool over_time) const override
  {
    if (g.over_time != over_time)
      return nullptr;
    center(g); // 2 coordinates
    if (g.radius == 0.)
      return std::make_unique<DiracPart>(g, mapping, fe, tria);
    return std::make_unique<MollifierPart>(g, mapping, fe);
  }

  double exact_value(const Scene<2> &scene, const GoalSpec &g, double t,
                     nested::NestedIntegrals &n) const override
  {
    const auto *u = scene.exact();
    const Point<2> c = center(g);
    if (g.radius == 0.)
      return u->value(c, t);
    const auto box = scene.bounding_box();
    const double s = g.radius, C = mollifier_constant(2, s);
    return n.outer(
        [&](double x)
        {
          const double h = std::sqrt(std::max(0., s * s - (x - c[0]) * (x - c[0])));
          return n.inner(
              [&](double y)
              {
                const Point<2> p(x, y);
                return mollifier(p, c, s, C) * u->value(p, t);
              },
              std::max(c[1] - h, box[0][1]), std::min(c[1] + h, box[1][1]));
        },
        std::max(c[0] - s, box[0][0]), std::min(c[0] + s, box[1][0]));
  }

  /// 1e-6 (the quadrature reaches 1e-12 once the cells resolve the mollifier, and
  /// fails abruptly below that); a mollifier whose support leaves the domain: in
  /// (0, 1 + 1e-6].
  bool weight_accepted(const GoalSpec &g, const Scene<2> &scene, double w) const override
  {
    constexpr double tolerance = 1e-6;
    const double s = g.radius;
    const Point<2> c = center(g);
    if (s > 0 && !scene.contains_box(Point<2>(c[0] - s, c[1] - s), Point<2>(c[0] + s, c[1] + s)))
      return w > 0 && w <= 1 + tolerance;
    return std::abs(w - 1.) <= tolerance;
  }

  std::string unresolved(const Space<2> &space, const GoalSpec &goal, const GoalInput &in,
                         const Scene<2> &scene,
                         const std::string &integrates) const override
  {
    const Point<2> c = center(goal);
    if (!inside(space, c))
    {
      const bool custom = scene.name() == "custom" && in.kind == "scene";
      return in.locations_source +
             (custom ? ": key 'scene.goals'" : ": key 'goal.locations'") + ": goal " +
             goal.name + " is centred at (" + six_digits(c[0]) + ", " + six_digits(c[1]) +
             "), outside the domain " + scene.domain_text() +
             " (in a hole or beyond its boundary); expected a centre inside the domain" +
             (custom ? " (without scene.goals the goal sits at the centre of the domain's "
                       "bounding box)"
                     : "");
    }
    const auto box = scene.bounding_box();
    const double diameter = box[0].distance(box[1]);
    // the smallest radius accepted: the goal grown by factors of 2
    std::string smallest = "no radius up to the domain's diameter is accepted there";
    GoalSpec g = goal;
    double w = 0;
    for (double s = 2. * goal.radius; s <= diameter; s *= 2.)
      if (g.radius = s; goal_weight_resolved(space, g, scene, w))
      {
        smallest = "the smallest radius (in steps of 2) accepted there is " + six_digits(s);
        break;
      }
    return in.radius_source + ": invalid value '" + six_digits(goal.radius) +
           "' for key 'goal.radius': " + integrates +
           " (the mollifier is too small for the cells); expected a radius whose "
           "mollifier the mesh resolves: " +
           smallest;
  }
};
} // namespace

const GoalType &point_goal()
{
  static const PointGoal type;
  return type;
}
} // namespace anisodwr
