// goal.kind = mean: the mean of u over a rectangle [x0, x1] x [y0, y1].
#include "base/errors.h"
#include "base/nested_quadrature.h"
#include "goal/goal_quadrature.h"
#include "scene/scene.h"

namespace anisodwr
{
using namespace dealii;

namespace
{
/// A corner of a mean goal's rectangle (GoalSpec::location: x0, y0, x1, y1): 0 the
/// lower left, 1 the upper right.
Point<2> corner(const GoalSpec &g, unsigned int which)
{
  if (g.location.size() != 4)
    throw InputError("goal '" + g.name + "': expected x0,y0,x1,y1, got " +
                     std::to_string(g.location.size()) + " numbers");
  return Point<2>(g.location[2 * which], g.location[2 * which + 1]);
}
using Cell = Triangulation<2>::active_cell_iterator;

class MeanPart : public DensityGoalPart<2>
{
public:
  MeanPart(const GoalSpec &g, const Mapping<2> &mapping, const FiniteElement<2> &fe)
      : DensityGoalPart<2>(mapping, fe)
  {
    lo = corner(g, 0);
    hi = corner(g, 1);
    for (unsigned int d = 0; d < 2; ++d)
      area *= hi[d] - lo[d];
    if (!(area > 0))
      throw InputError("goal '" + g.name + "': the rectangle has no area");
  }

protected:
  bool meets(const Cell &cell) const override
  {
    for (unsigned int d = 0; d < 2; ++d)
    {
      double a = 1e300, b = -1e300;
      for (unsigned int v = 0; v < GeometryInfo<2>::vertices_per_cell; ++v)
      {
        a = std::min(a, cell->vertex(v)[d]);
        b = std::max(b, cell->vertex(v)[d]);
      }
      if (b < lo[d] || a > hi[d])
        return false;
    }
    return true;
  }
  double density(const Point<2> &x) const override
  {
    for (unsigned int d = 0; d < 2; ++d)
      if (x[d] < lo[d] || x[d] > hi[d])
        return 0.;
    return 1. / area;
  }
  /// 32 per direction for a cell cut by the rectangle's edge, 1 inside it.
  SubCells sub_cells(const Cell &cell, bool &capped) const override
  {
    capped = false;
    SubCells n;
    n.fill(1);
    for (unsigned int v = 0; v < GeometryInfo<2>::vertices_per_cell; ++v)
      for (unsigned int d = 0; d < 2; ++d)
        if (cell->vertex(v)[d] < lo[d] || cell->vertex(v)[d] > hi[d])
          n.fill(32);
    return n;
  }
  /// A cut cell that is an axis-parallel rectangle mapped affinely (its vertices form
  /// the box and the mapping puts the centre and the edge midpoints where the bilinear
  /// map of the vertices does): the Gauss rule of degree fe.degree + 2 on the cell's
  /// part inside the goal's rectangle, which integrates the shape functions times the
  /// constant density exactly. False for other cells.
  bool own_rule(const Cell &cell, const SubCells &n, bool, Rule &rule,
                bool &empty) const override
  {
    if (n[0] == 1)
      return false;
    const Point<2> a = cell->vertex(0), b = cell->vertex(3);
    const double tol = 1e-12 * a.distance(b);
    if (!(b[0] > a[0] && b[1] > a[1]) ||
        cell->vertex(1).distance(Point<2>(b[0], a[1])) > tol ||
        cell->vertex(2).distance(Point<2>(a[0], b[1])) > tol)
      return false;
    for (const auto &xi : {Point<2>(0.5, 0.5), Point<2>(0.5, 0.), Point<2>(0.5, 1.),
                           Point<2>(0., 0.5), Point<2>(1., 0.5)})
    {
      const Point<2> x = mapping.transform_unit_to_real_cell(cell, xi);
      if (x.distance(Point<2>(a[0] + xi[0] * (b[0] - a[0]), a[1] + xi[1] * (b[1] - a[1]))) >
          tol)
        return false;
    }
    empty = false;
    for (unsigned int d = 0; d < 2; ++d)
    {
      const double lo_d = std::max(0., (lo[d] - a[d]) / (b[d] - a[d])),
                   hi_d = std::min(1., (hi[d] - a[d]) / (b[d] - a[d]));
      if (!(hi_d > lo_d))
      {
        empty = true;
        return true;
      }
      rule[d] = gauss_on(lo_d, hi_d);
    }
    return true;
  }

private:
  Point<2> lo, hi;
  double area = 1;
};

class MeanGoal : public GoalType
{
public:
  std::string name() const override { return "mean"; }
  std::string doc() const override
  {
    return "means over the rectangles 'x0,y0,x1,y1; ...' (lower-left, upper-right) of "
           "goal.locations";
  }
  std::string noun() const override { return "rectangle"; }
  std::string syntax() const override { return "x0,y0,x1,y1"; }
  std::string example() const override { return "0.1,0.2,0.6,0.7"; }
  unsigned int n_numbers() const override { return 4; }

  void set_location(const std::vector<double> &v, const Scene<2> &scene,
                    const std::string &bad, GoalSpec &g) const override
  {
    g.location = v;
    if (!(v[2] > v[0] && v[3] > v[1]))
      throw InputError(bad + "expected x0,y0,x1,y1 with x1 > x0, y1 > y0");
    if (!scene.contains_box(Point<2>(v[0], v[1]), Point<2>(v[2], v[3])))
      throw InputError(bad + "it is not inside the domain " + scene.domain_text() +
                       " of scene '" + scene.name() + "'");
  }

  std::unique_ptr<GoalPart<2>> part(const GoalSpec &g, const Scene<2> &,
                                    const Mapping<2> &mapping, const FiniteElement<2> &fe,
                                    const Triangulation<2> &, bool over_time) const override
  {
    if (g.over_time != over_time)
      return nullptr;
    return std::make_unique<MeanPart>(g, mapping, fe);
  }

  double exact_value(const Scene<2> &scene, const GoalSpec &g, double t,
                     nested::NestedIntegrals &n) const override
  {
    const auto *u = scene.exact();
    const auto box = scene.bounding_box();
    const Point<2> lo = corner(g, 0), hi = corner(g, 1);
    const double area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    return n.outer(
               [&](double x)
               {
                 return n.inner([&](double y) { return u->value(Point<2>(x, y), t); },
                                std::max(lo[1], box[0][1]), std::min(hi[1], box[1][1]));
               },
               std::max(lo[0], box[0][0]), std::min(hi[0], box[1][0])) /
           area;
  }

  /// 1e-3: exact on axis-parallel cells; on other cells cut by the rectangle's edges
  /// 32 x 32 sub-cells reach about 1e-5 to 1e-4 for rectangles of the cells' size.
  bool weight_accepted(const GoalSpec &, const Scene<2> &, double w) const override
  {
    return std::abs(w - 1.) <= 1e-3;
  }

  std::string unresolved(const Space<2> &space, const GoalSpec &goal, const GoalInput &in,
                         const Scene<2> &scene,
                         const std::string &integrates) const override
  {
    GoalSpec g = goal;
    double w = 0;
    const Point<2> lo = corner(g, 0), hi = corner(g, 1);
    const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    double hx = 0.5 * (hi[0] - lo[0]), hy = 0.5 * (hi[1] - lo[1]);
    std::string smallest = "none of the larger rectangles about its centre (in steps of "
                           "2) inside the domain is accepted there; refine the initial "
                           "mesh (discretization.initial_refinements)";
    // the shorter side doubled first (a thin strip widened), then both
    const auto grow = [&]()
    {
      const double x = hx, y = hy;
      hx = x <= y ? 2. * x : x;
      hy = y <= x ? 2. * y : y;
    };
    for (grow();
         scene.contains_box(Point<2>(cx - hx, cy - hy), Point<2>(cx + hx, cy + hy));
         grow())
    {
      g.location = {cx - hx, cy - hy, cx + hx, cy + hy};
      if (goal_weight_resolved(space, g, scene, w))
      {
        smallest = "the smallest one about its centre (in steps of 2) accepted there is " +
                   six_digits(2. * hx) + " x " + six_digits(2. * hy);
        break;
      }
    }
    return in.locations_source + ": invalid value '" + in.locations +
           "' in key 'goal.locations': " + integrates +
           " (the rectangle is too small for the cells it cuts, which are not "
           "axis-parallel); expected a rectangle the mesh resolves: " +
           smallest;
  }
};
} // namespace

const GoalType &mean_goal()
{
  static const MeanGoal type;
  return type;
}
} // namespace anisodwr
