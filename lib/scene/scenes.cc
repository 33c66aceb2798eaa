#include "scene/scenes.h"

#include "base/errors.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>

namespace anisodwr
{
namespace
{
constexpr double pi = M_PI;

void require_variant(const std::string &scene, const std::string &variant,
                     std::initializer_list<const char *> allowed)
{
  std::string list;
  for (const char *a : allowed)
  {
    if (variant == a)
      return;
    list += std::string(list.empty() ? "" : ", ") + (*a ? a : "\"\"");
  }
  throw InputError("invalid value '" + variant + "' for key 'scene.variant' of scene '" +
                   scene + "'; expected one of: " + list);
}

/// The moving hump of John, Maubach & Tobiska: 16 sin(pi t) g(x,y) h(x,y).
class HumpSolution : public ExactSolution<2>
{
public:
  explicit HumpSolution(double eps) : A(2. / std::sqrt(eps)) {}

  // u = T(t) S(x) with T = sin(pi t), S = 16 g h: separable, so that loads and the
  // estimator's residual evaluate S (one atan) once per point instead of per time
  double value(const dealii::Point<2> &p, double t) const override
  {
    return std::sin(pi * t) * space_value(p);
  }
  double time_derivative(const dealii::Point<2> &p, double t) const override
  {
    return pi * std::cos(pi * t) * space_value(p);
  }
  dealii::Tensor<1, 2> gradient(const dealii::Point<2> &p, double t) const override
  {
    return std::sin(pi * t) * space_gradient(p);
  }
  double laplacian(const dealii::Point<2> &p, double t) const override
  {
    return std::sin(pi * t) * space_laplacian(p);
  }

  bool separable() const override { return true; }
  double time_factor(double t, unsigned int derivative) const override
  {
    return derivative == 0 ? std::sin(pi * t) : pi * std::cos(pi * t);
  }
  double space_value(const dealii::Point<2> &p) const override { return 16. * g(p) * h(p); }
  dealii::Tensor<1, 2> space_gradient(const dealii::Point<2> &p) const override
  {
    const double x = p[0], y = p[1];
    const double gx = (1. - 2. * x) * y * (1. - y), gy = x * (1. - x) * (1. - 2. * y);
    const double k = dh(p), hp = h(p), gp = g(p); // h_x = k s_x, s_x = -2(x - x0)
    dealii::Tensor<1, 2> grad;
    grad[0] = gx * hp + gp * k * (-2. * (x - c));
    grad[1] = gy * hp + gp * k * (-2. * (y - c));
    return 16. * grad;
  }
  double space_laplacian(const dealii::Point<2> &p) const override
  {
    const double x = p[0], y = p[1];
    const double gx = (1. - 2. * x) * y * (1. - y), gy = x * (1. - x) * (1. - 2. * y);
    const double gxx = -2. * y * (1. - y), gyy = -2. * x * (1. - x);
    const double s = s_of(p), q = 1. + A * A * s * s, hp = h(p), gp = g(p);
    const double sx = -2. * (x - c), sy = -2. * (y - c);
    // h = 1/2 + atan(A s)/pi: h_i = A s_i / (pi q), h_ii = (A s_ii q - A s_i 2 A^2 s
    // s_i)/(pi q^2)
    const double hx = A * sx / (pi * q), hy = A * sy / (pi * q);
    const double hxx = (A * (-2.) * q - A * sx * 2. * A * A * s * sx) / (pi * q * q);
    const double hyy = (A * (-2.) * q - A * sy * 2. * A * A * s * sy) / (pi * q * q);
    return 16. * (gxx * hp + 2. * gx * hx + gp * hxx + gyy * hp + 2. * gy * hy + gp * hyy);
  }

private:
  static constexpr double r0 = 0.25, c = 0.5;
  double A;
  static double g(const dealii::Point<2> &p)
  {
    return p[0] * (1. - p[0]) * p[1] * (1. - p[1]);
  }
  static double s_of(const dealii::Point<2> &p)
  {
    return r0 * r0 - (p[0] - c) * (p[0] - c) - (p[1] - c) * (p[1] - c);
  }
  double h(const dealii::Point<2> &p) const { return 0.5 + std::atan(A * s_of(p)) / pi; }
  /// dh/ds
  double dh(const dealii::Point<2> &p) const
  {
    const double s = s_of(p);
    return A / (pi * (1. + A * A * s * s));
  }
};

/// x (1 - e^{(x-1)/eps}) (1 + y/2) (1 + t): linear in y (Q1 is exact across the layer),
/// so that the whole discretization error sits in the layer at x = 1.
class LayerSolution : public ExactSolution<2>
{
public:
  explicit LayerSolution(double eps) : eps(eps) {}
  double value(const dealii::Point<2> &p, double t) const override
  {
    return X(p[0]) * (1. + 0.5 * p[1]) * (1. + t);
  }
  double time_derivative(const dealii::Point<2> &p, double) const override
  {
    return X(p[0]) * (1. + 0.5 * p[1]);
  }
  dealii::Tensor<1, 2> gradient(const dealii::Point<2> &p, double t) const override
  {
    const double x = p[0], E = std::exp((x - 1.) / eps);
    return dealii::Tensor<1, 2>(
        {(1. - E - x * E / eps) * (1. + 0.5 * p[1]) * (1. + t), 0.5 * X(x) * (1. + t)});
  }
  double laplacian(const dealii::Point<2> &p, double t) const override
  {
    const double x = p[0], E = std::exp((x - 1.) / eps);
    return (-2. * E / eps - x * E / (eps * eps)) * (1. + 0.5 * p[1]) * (1. + t);
  }

private:
  double eps;
  double X(double x) const { return x * (1. - std::exp((x - 1.) / eps)); }
};

double sin_pi(double x)
{
  return std::sin(pi * x);
}
double dsin_pi(double x)
{
  return pi * std::cos(pi * x);
}
double ddsin_pi(double x)
{
  return -pi * pi * std::sin(pi * x);
}
void sin_pi_jet(double x, double &f, double &df, double &ddf)
{
  const double s = std::sin(pi * x), c = std::cos(pi * x);
  f = s;
  df = pi * c;
  ddf = -pi * pi * s;
}
double bubble(double x)
{
  return 4. * x * (1. - x);
}
double dbubble(double x)
{
  return 4. - 8. * x;
}
double ddbubble(double)
{
  return -8.;
}
double quad_neg(double x)
{
  return x * x - x;
} // (x^2 - x)
double dquad_neg(double x)
{
  return 2. * x - 1.;
}
double ddquad_neg(double)
{
  return 2.;
}
double decay(double t)
{
  return std::exp(-t) * (1. + t * t);
}
double ddecay(double t)
{
  return std::exp(-t) * (-1. + 2. * t - t * t);
}
double heat_poly_t(double t)
{
  return -t / 4.;
}
double heat_poly_dt(double)
{
  return -0.25;
}

void unit_square(dealii::Triangulation<2, 2> &tria)
{
  dealii::GridGenerator::hyper_cube(tria, 0., 1.);
}
} // namespace

double SeparableSolution::space_value(const dealii::Point<2> &p) const
{
  return X.f(p[0]) * Y.f(p[1]);
}
dealii::Tensor<1, 2> SeparableSolution::space_gradient(const dealii::Point<2> &p) const
{
  dealii::Tensor<1, 2> g;
  g[0] = X.df(p[0]) * Y.f(p[1]);
  g[1] = X.f(p[0]) * Y.df(p[1]);
  return g;
}
double SeparableSolution::space_laplacian(const dealii::Point<2> &p) const
{
  return X.ddf(p[0]) * Y.f(p[1]) + X.f(p[0]) * Y.ddf(p[1]);
}
void SeparableSolution::space_jet(const dealii::Point<2> &p, double &value,
                                  dealii::Tensor<1, 2> &gradient, double &laplacian) const
{
  const auto jet = [](const Factor &F, double s, double &f, double &df, double &ddf)
  {
    if (F.jet)
      F.jet(s, f, df, ddf);
    else
    {
      f = F.f(s);
      df = F.df(s);
      ddf = F.ddf(s);
    }
  };
  double x, dx, ddx, y, dy, ddy;
  jet(X, p[0], x, dx, ddx);
  jet(Y, p[1], y, dy, ddy);
  value = x * y;
  gradient[0] = dx * y;
  gradient[1] = x * dy;
  laplacian = ddx * y + x * ddy;
}
double SeparableSolution::value(const dealii::Point<2> &p, double t) const
{
  return space_value(p) * T(t);
}
dealii::Tensor<1, 2> SeparableSolution::gradient(const dealii::Point<2> &p,
                                                 double t) const
{
  return space_gradient(p) * T(t);
}
double SeparableSolution::laplacian(const dealii::Point<2> &p, double t) const
{
  return space_laplacian(p) * T(t);
}
double SeparableSolution::time_derivative(const dealii::Point<2> &p, double t) const
{
  return X.f(p[0]) * Y.f(p[1]) * dT(t);
}

MovingHump::MovingHump(double eps, const std::string &variant)
{
  require_variant("moving_hump", variant, {""});
  epsilon = eps;
  exact_solution = std::make_unique<HumpSolution>(eps);
}
void MovingHump::make_coarse_grid(dealii::Triangulation<2, 2> &tria) const
{
  unit_square(tria);
}
dealii::Tensor<1, 2> MovingHump::convection(const dealii::Point<2> &, double) const
{
  return dealii::Tensor<1, 2>({2., 3.});
}

std::vector<GoalSpec> MovingHump::default_goals(double radius) const
{
  const double d = 0.25 / std::sqrt(2.);
  GoalSpec g1, g2;
  g1.name = "u_xe1_T";
  g1.location = {0.5 - d, 0.5 - d};
  g2.name = "u_xe2_T";
  g2.location = {0.5 + d, 0.5 + d};
  g1.radius = g2.radius = radius;
  return {g1, g2};
}

BoundaryLayer::BoundaryLayer(double eps, const std::string &variant)
{
  require_variant("boundary_layer", variant, {""});
  epsilon = eps;
  exact_solution = std::make_unique<LayerSolution>(eps);
  dirichlet_ids = {0, 1}; // x = 0, x = 1
  neumann_ids = {2, 3};   // y = 0, y = 1: eps du/dn from u
}
void BoundaryLayer::make_coarse_grid(dealii::Triangulation<2, 2> &tria) const
{
  dealii::GridGenerator::hyper_cube(tria, 0., 1., true);
}
std::vector<GoalSpec> BoundaryLayer::default_goals(double) const
{
  GoalSpec g;
  g.name = "mean_T";
  g.kind = "mean";
  g.location = {0.5, 0., 1., 1.}; // x0, y0, x1, y1
  return {g};
}

Manufactured::Manufactured(double eps, const std::string &variant)
{
  require_variant("manufactured", variant, {"", "constant", "rotating", "poly_space"});
  epsilon = eps;
  rotating = (variant == "rotating" || variant == "poly_space");
  const SeparableSolution::Factor s{sin_pi, dsin_pi, ddsin_pi, sin_pi_jet},
      b{bubble, dbubble, ddbubble};
  if (variant == "poly_space")
    exact_solution = std::make_unique<SeparableSolution>(b, b, decay, ddecay);
  else
    exact_solution = std::make_unique<SeparableSolution>(s, s, decay, ddecay);
}
void Manufactured::make_coarse_grid(dealii::Triangulation<2, 2> &tria) const
{
  unit_square(tria);
}
dealii::Tensor<1, 2> Manufactured::convection(const dealii::Point<2> &p, double t) const
{
  if (rotating)
    return dealii::Tensor<1, 2>({-(p[1] - 0.5) * (1. + t), (p[0] - 0.5) * (1. + t)});
  return dealii::Tensor<1, 2>({1., 0.5});
}
double Manufactured::reaction(const dealii::Point<2> &, double t) const
{
  return rotating ? 1. + t : 1.;
}

Heat::Heat(double eps, const std::string &variant)
{
  require_variant("heat", variant, {"", "poly", "trig"});
  epsilon = eps;
  if (variant == "trig")
  {
    const SeparableSolution::Factor s{sin_pi, dsin_pi, ddsin_pi, sin_pi_jet};
    exact_solution = std::make_unique<SeparableSolution>(s, s, sin_pi, dsin_pi);
  }
  else
  {
    const SeparableSolution::Factor q{quad_neg, dquad_neg, ddquad_neg};
    exact_solution = std::make_unique<SeparableSolution>(q, q, heat_poly_t, heat_poly_dt);
  }
}
void Heat::make_coarse_grid(dealii::Triangulation<2, 2> &tria) const
{
  unit_square(tria);
}
Hemker::Hemker(double eps, const std::string &variant)
{
  require_variant("hemker", variant, {""});
  epsilon = eps;
  dirichlet_ids = {0, 1};
  neumann_ids = {2};
}

void Hemker::make_coarse_grid(dealii::Triangulation<2, 2> &tria) const
{
  using namespace dealii;
  // The square (-3,3)^2 around the hole in 8 cells, merged with (3,8)x(-3,3) in 2 cells.
  Triangulation<2> hole, padding;
  GridGenerator::hyper_cube_with_cylindrical_hole(hole, 1., 3.);
  GridGenerator::subdivided_hyper_rectangle(padding, {1u, 2u}, Point<2>(3., -3.),
                                            Point<2>(8., 3.));
  GridGenerator::merge_triangulations(hole, padding, tria);
  tria.reset_all_manifolds();
  tria.set_all_manifold_ids(numbers::flat_manifold_id);
  for (const auto &cell : tria.active_cell_iterators())
  {
    if (cell->center()[0] < 3.)
      cell->set_all_manifold_ids(1);
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
      {
        const Point<2> c = face->center();
        if (c.norm() < 2.)
        {
          face->set_boundary_id(1);
          face->set_manifold_id(0);
        }
        else
          face->set_boundary_id(std::abs(c[0] + 3.) < 1e-12 ? 0 : 2);
      }
  }
  tria.set_manifold(0, PolarManifold<2>(Point<2>()));
  TransfiniteInterpolationManifold<2> transfinite;
  transfinite.initialize(tria);
  tria.set_manifold(1, transfinite);
}

double Hemker::dirichlet_value(const dealii::Point<2> &x, double) const
{
  return x.norm() < 2. ? 1. : 0.;
}

bool Hemker::contains(const dealii::Point<2> &x) const
{
  return Scene<2>::contains(x) && x.norm() >= 1. - 1e-12;
}

bool Hemker::contains_box(const dealii::Point<2> &lo, const dealii::Point<2> &hi) const
{
  // the point of the box closest to the centre of the hole must not lie in the hole
  const dealii::Point<2> nearest(std::clamp(0., lo[0], hi[0]), std::clamp(0., lo[1], hi[1]));
  return Scene<2>::contains_box(lo, hi) && nearest.norm() >= 1. - 1e-12;
}

std::vector<GoalSpec> Hemker::default_goals(double radius) const
{
  const double a = 1. / std::sqrt(2.);
  GoalSpec g1, g2;
  g1.name = "u_xe1_I";
  g1.location = {4., 1.};
  g2.name = "u_xe2_I";
  g2.location = {-a - 1e-6, a + 1e-6};
  for (GoalSpec *g : {&g1, &g2})
  {
    g->radius = radius;
    g->over_time = true;
  }
  return {g1, g2};
}

ProbeSpec<2> Hemker::probes() const
{
  const double a = 1. / std::sqrt(2.);
  const dealii::Point<2> x_gamma(-a, a), normal(-a, a);
  ProbeSpec<2> spec;
  spec.cut_lines = {{"x4", dealii::Point<2>(4., -3.), dealii::Point<2>(4., 3.)},
                    {"normal", x_gamma, x_gamma + 2. * normal},
                    {"top", dealii::Point<2>(0., 1.), dealii::Point<2>(0., 1.5)}};
  spec.has_layer = true;
  spec.layer_ray = spec.cut_lines[1];
  spec.u_min = 0.;
  spec.u_max = 1.;
  spec.has_strip = true;
  spec.strip = {{-1.5, 1.5}};
  // the goals' domain of influence: the upper half from just upstream of the circle to
  // beyond x_e1 (the upper interior layer starts at the circle's top, (0, 1))
  spec.has_box = true;
  spec.box = {{-1.5, 4.5, 0., 3.}};
  return spec;
}
} // namespace anisodwr
