#pragma once
// The benchmark scenes of doc/method.md §10 (2D).
#include "scene/scene.h"

namespace anisodwr
{
/// Hump with a circular interior layer (John, Maubach & Tobiska 1997), b = (2,3), alpha
/// = 1.
class MovingHump : public Scene<2>
{
public:
  MovingHump(double epsilon, const std::string &variant);
  std::string name() const override { return "moving_hump"; }
  void make_coarse_grid(dealii::Triangulation<2, 2> &tria) const override;
  dealii::Tensor<1, 2> convection(const dealii::Point<2> &, double) const override;
  double reaction(const dealii::Point<2> &, double) const override { return 1.; }
  bool coefficients_depend_on_time() const override { return false; }
  /// J_1 = u(x_e1, T), J_2 = u(x_e2, T), mollified, x_e1,2 = (1/2 -+ r0/sqrt2, ...).
  std::vector<GoalSpec> default_goals(double radius) const override;
};

/// Exponential outflow layer at x = 1 (aligned with the y axis), for anisotropy:
///   u = x (1 - e^{(x-1)/eps}) (1 + y/2) (1 + t),  b = (1, 0), alpha = 1,
/// Dirichlet data from u on x = 0, 1, Neumann data eps du/dn on y = 0, 1 (so that the
/// adjoint has no wall layers either); u is linear in y, so the error sits in the layer.
/// Goal: mean of u(T) over (0.5,1) x (0,1).
class BoundaryLayer : public Scene<2>
{
public:
  BoundaryLayer(double epsilon, const std::string &variant);
  std::string name() const override { return "boundary_layer"; }
  void make_coarse_grid(dealii::Triangulation<2, 2> &tria) const override;
  dealii::Tensor<1, 2> convection(const dealii::Point<2> &, double) const override
  {
    return dealii::Tensor<1, 2>({1., 0.});
  }
  double reaction(const dealii::Point<2> &, double) const override { return 1.; }
  bool coefficients_depend_on_time() const override { return false; }
  std::vector<GoalSpec> default_goals(double radius) const override;
};

/// Smooth solutions on (0,1)^2 for convergence studies.
///  constant:   u = sin(pi x) sin(pi y) e^{-t} (1+t^2), b = (1, 0.5), alpha = 1
///  rotating:   same u, b = (-y+1/2, x-1/2)(1+t), alpha = 1 + t
///  poly_space: u = 16 x(1-x) y(1-y) e^{-t}(1+t^2) (in Q2), rotating b and alpha
class Manufactured : public Scene<2>
{
public:
  Manufactured(double epsilon, const std::string &variant);
  std::string name() const override { return "manufactured"; }
  void make_coarse_grid(dealii::Triangulation<2, 2> &tria) const override;
  dealii::Tensor<1, 2> convection(const dealii::Point<2> &, double) const override;
  double reaction(const dealii::Point<2> &, double) const override;
  bool coefficients_depend_on_time() const override { return rotating; }
  void rhs_at_times(const dealii::Point<2> &x, const std::vector<double> &times,
                    double *out) const override
  {
    exact_rhs_at_times(x, times, out);
  }

private:
  bool rotating = false;
};

/// Pure diffusion (b = 0, alpha = 0) on (0,1)^2.
///  poly: u = -(x^2-x)(y^2-y) t / 4;  trig: u = sin(pi x) sin(pi y) sin(pi t).
class Heat : public Scene<2>
{
public:
  Heat(double epsilon, const std::string &variant);
  std::string name() const override { return "heat"; }
  void make_coarse_grid(dealii::Triangulation<2, 2> &tria) const override;
  dealii::Tensor<1, 2> convection(const dealii::Point<2> &, double) const override
  {
    return {};
  }
  double reaction(const dealii::Point<2> &, double) const override { return 0.; }
  bool coefficients_depend_on_time() const override { return false; }
};

/// u(x,y,t) = X(x) Y(y) T(t) with 1D factors and their first two derivatives.
class SeparableSolution : public ExactSolution<2>
{
public:
  struct Factor
  {
    double (*f)(double);
    double (*df)(double);
    double (*ddf)(double);
    /// f, f', f'' at once (optional; space_jet uses it where the three share work)
    void (*jet)(double, double &, double &, double &) = nullptr;
  };
  SeparableSolution(Factor X, Factor Y, double (*T)(double), double (*dT)(double))
      : X(X), Y(Y), T(T), dT(dT)
  {
  }
  double value(const dealii::Point<2> &p, double t) const override;
  dealii::Tensor<1, 2> gradient(const dealii::Point<2> &p, double t) const override;
  double laplacian(const dealii::Point<2> &p, double t) const override;
  double time_derivative(const dealii::Point<2> &p, double t) const override;

  bool separable() const override { return true; }
  double time_factor(double t, unsigned int derivative) const override
  {
    return derivative == 0 ? T(t) : dT(t);
  }
  double space_value(const dealii::Point<2> &p) const override;
  dealii::Tensor<1, 2> space_gradient(const dealii::Point<2> &p) const override;
  double space_laplacian(const dealii::Point<2> &p) const override;
  void space_jet(const dealii::Point<2> &p, double &value, dealii::Tensor<1, 2> &gradient,
                 double &laplacian) const override;

private:
  Factor X, Y;
  double (*T)(double);
  double (*dT)(double);
};
/// Nonstationary Hemker problem (doc/method.md §10): flow b = (1, 0) past the unit
/// circle in (-3,8)x(-3,3), u = 1 on the circle, u = 0 at the inflow x = -3, homogeneous
/// Neumann elsewhere, u_0 = 0, f = 0, alpha = 0; no exact solution. Boundary ids:
/// 0 inflow, 1 circle (Dirichlet), 2 the rest (Neumann). The circle carries a
/// PolarManifold (manifold id 0), the cells of the square (-3,3)^2 a
/// TransfiniteInterpolationManifold (id 1); the FE map is
/// MappingQ(discretization.mapping_degree), auto p: at p = 1 the discrete boundary is the
/// polygon through the refined vertices on the circle.
class Hemker : public Scene<2>
{
public:
  Hemker(double epsilon, const std::string &variant);
  std::string name() const override { return "hemker"; }
  void make_coarse_grid(dealii::Triangulation<2, 2> &tria) const override;
  dealii::Tensor<1, 2> convection(const dealii::Point<2> &, double) const override
  {
    return dealii::Tensor<1, 2>({1., 0.});
  }
  double reaction(const dealii::Point<2> &, double) const override { return 0.; }
  bool coefficients_depend_on_time() const override { return false; }
  double rhs(const dealii::Point<2> &, double) const override { return 0.; }
  bool separable_rhs(std::vector<LoadTerm<2>> &terms) const override
  {
    terms.clear(); // f = 0: no terms
    return true;
  }
  double initial_value(const dealii::Point<2> &) const override { return 0.; }
  /// 1 on the circle (|x| < 2), 0 at the inflow.
  double dirichlet_value(const dealii::Point<2> &x, double t) const override;
  double neumann_value(const dealii::Point<2> &, const dealii::Tensor<1, 2> &,
                       double) const override
  {
    return 0.;
  }
  /// (-3, 8) x (-3, 3) without the open unit disc.
  std::array<dealii::Point<2>, 2> bounding_box() const override
  {
    return {{dealii::Point<2>(-3., -3.), dealii::Point<2>(8., 3.)}};
  }
  std::string domain_text() const override
  {
    return "[-3,8]x[-3,3] without the open unit disc";
  }
  bool contains(const dealii::Point<2> &x) const override;
  bool contains_box(const dealii::Point<2> &lo, const dealii::Point<2> &hi) const override;
  /// J_1 = int_I u(x_e1, t) dt, J_2 = int_I u(x_e2, t) dt (mollified), x_e1 = (4, 1),
  /// x_e2 = (-2^{-1/2} - 1e-6, 2^{-1/2} + 1e-6).
  std::vector<GoalSpec> default_goals(double radius) const override;
  /// Cut lines x = 4 and along the normal at x_Gamma = (-2^{-1/2}, 2^{-1/2}), the layer
  /// width there, bounds [0, 1], strip -1.5 < x < 1.5.
  ProbeSpec<2> probes() const override;
};
} // namespace anisodwr
