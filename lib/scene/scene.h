#pragma once
// A scene: geometry, coefficients, data and (where known) the exact solution of
//   d_t u - eps Lap u + b.grad u + alpha u = f.
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include "scene/goal_spec.h"
#include "scene/scene_options.h"

#include <array>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace dealii
{
template <int dim, int spacedim> class Triangulation;
template <int dim, int spacedim> class CellAccessor;
} // namespace dealii

namespace anisodwr
{
/// The unit normal of the straight face f of `cell` (through its vertices), pointing out
/// of the cell.
dealii::Tensor<1, 2> outward_normal(const dealii::CellAccessor<2, 2> &cell, unsigned int f);

/// Exact solution with analytic derivatives (no finite differences).
template <int dim> class ExactSolution
{
public:
  virtual ~ExactSolution() = default;
  virtual double value(const dealii::Point<dim> &x, double t) const = 0;
  virtual dealii::Tensor<1, dim> gradient(const dealii::Point<dim> &x,
                                          double t) const = 0;
  virtual double laplacian(const dealii::Point<dim> &x, double t) const = 0;
  virtual double time_derivative(const dealii::Point<dim> &x, double t) const = 0;

  /// True if u(x,t) = T(t) S(x); then time_factor() and the space_* functions give T,
  /// T' and S, grad S, Lap S, so that loads and errors need S only once per mesh.
  virtual bool separable() const { return false; }
  /// T(t) (derivative 0) or T'(t) (derivative 1). Only if separable().
  virtual double time_factor(double, unsigned int) const { throw not_separable(); }
  virtual double space_value(const dealii::Point<dim> &) const { throw not_separable(); }
  virtual dealii::Tensor<1, dim> space_gradient(const dealii::Point<dim> &) const
  {
    throw not_separable();
  }
  virtual double space_laplacian(const dealii::Point<dim> &) const { throw not_separable(); }
  /// S, grad S and Lap S at once (Scene::rhs at every quadrature point of a load with
  /// coefficients that depend on t); override where the three share their work.
  virtual void space_jet(const dealii::Point<dim> &x, double &value,
                         dealii::Tensor<1, dim> &gradient, double &laplacian) const
  {
    value = space_value(x);
    gradient = space_gradient(x);
    laplacian = space_laplacian(x);
  }

private:
  static std::logic_error not_separable()
  {
    return std::logic_error("ExactSolution: space/time factors of a non-separable solution");
  }
};

/// One product a(t) g(x) of a load f(x,t) = sum_k a_k(t) g_k(x).
template <int dim> struct LoadTerm
{
  std::function<double(double)> a;
  std::function<double(const dealii::Point<dim> &)> g;
};

/// Derived outputs of u_h(T) a scene asks for (doc/method.md §10, hemker): cut lines
/// sampled to CSV, the width of a layer along a ray, over- and undershoots.
template <int dim> struct ProbeSpec
{
  struct Line
  {
    std::string name;
    dealii::Point<dim> start, end;
  };
  std::vector<Line> cut_lines;
  /// Layer width |x_1 - x_0| along `layer_ray` (start on the wall, end outside), with
  /// u(x_1) = layer_levels[1], u(x_0) = layer_levels[0], first crossings from the start.
  bool has_layer = false;
  Line layer_ray;
  std::array<double, 2> layer_levels{{0.1, 0.9}};
  /// Bounds of the exact solution for over-/undershoots: u_min <= u <= u_max. NaN:
  /// taken from the exact solution at the same sample points.
  double u_min = std::numeric_limits<double>::quiet_NaN(),
         u_max = std::numeric_limits<double>::quiet_NaN();
  /// Over-/undershoots are also reported in the strip strip[0] < x_0 < strip[1].
  bool has_strip = false;
  std::array<double, 2> strip{{0., 0.}};
  /// ... and in the box box[0] < x_0 < box[1], box[2] < x_1 < box[3] (the goals'
  /// domain of influence; probes.csv overshoot_goals, undershoot_goals).
  bool has_box = false;
  std::array<double, 4> box{{0., 0., 0., 0.}};
};

template <int dim> class Scene
{
public:
  virtual ~Scene() = default;

  virtual std::string name() const = 0;
  virtual void make_coarse_grid(dealii::Triangulation<dim, dim> &tria) const = 0;

  virtual dealii::Tensor<1, dim> convection(const dealii::Point<dim> &x,
                                            double t) const = 0;
  virtual double reaction(const dealii::Point<dim> &x, double t) const = 0;
  /// True if b or alpha depend on t (the slab matrix is then a sum over
  /// temporal quadrature points and is rebuilt on every slab).
  virtual bool coefficients_depend_on_time() const = 0;

  /// Data. The defaults derive them from the exact solution.
  virtual double rhs(const dealii::Point<dim> &x, double t) const;
  /// f as a sum of products a_k(t) g_k(x) (the loads are then assembled once per mesh
  /// and combined per time); false if f is not known to be of that form. The default
  /// derives f = T' S + T (-eps Lap S + b.grad S + alpha S) from a separable exact
  /// solution when b and alpha do not depend on t. A scene that overrides rhs()
  /// overrides this too.
  virtual bool separable_rhs(std::vector<LoadTerm<dim>> &terms) const;
  /// out[k] = rhs(x, times[k]) for every k: the loads and the estimator ask for f at a
  /// point at all temporal quadrature points of a slab at once. The default calls rhs()
  /// per time; a scene whose f is the default rhs() may forward to exact_rhs_at_times.
  virtual void rhs_at_times(const dealii::Point<dim> &x, const std::vector<double> &times,
                            double *out) const;
  virtual double initial_value(const dealii::Point<dim> &x) const;
  virtual double dirichlet_value(const dealii::Point<dim> &x, double t) const;
  /// eps grad u . n on the Neumann boundary.
  virtual double neumann_value(const dealii::Point<dim> &x,
                               const dealii::Tensor<1, dim> &n, double t) const;
  /// The Dirichlet and Neumann data on the boundary part `id` (what the assembly
  /// calls). Default: dirichlet_value(x, t) and neumann_value(x, n, t), the same on
  /// every part.
  virtual double boundary_value(const dealii::Point<dim> &x, double t,
                                dealii::types::boundary_id) const
  {
    return dirichlet_value(x, t);
  }
  virtual double boundary_flux(const dealii::Point<dim> &x, const dealii::Tensor<1, dim> &n,
                               double t, dealii::types::boundary_id) const
  {
    return neumann_value(x, n, t);
  }

  /// The scene's goal functionals (doc/method.md §10); `radius` is the mollifier radius
  /// of point goals. Default: the value at the domain's centre (0.5, 0.5) at T.
  virtual std::vector<GoalSpec> default_goals(double radius) const;

  /// Goals the scene's input states as text, "[name =] kind numbers; ...", which the
  /// goal layer parses (goal/goal_input.h, make_goals) in place of default_goals: a
  /// custom scene's scene.goals. Empty items: none (default_goals applies).
  struct GoalText
  {
    std::string items;
    bool over_time = false;
  };
  virtual GoalText goal_text() const { return {}; }

  /// The smallest axis-parallel box holding the domain: {lower-left, upper-right}.
  /// Default: the unit square/cube.
  virtual std::array<dealii::Point<dim>, 2> bounding_box() const;
  /// The domain in words, for messages. Default: "[0,1]^2".
  virtual std::string domain_text() const { return "[0,1]^2"; }
  /// True if x lies in the closed domain (up to 1e-12 of its size). Default: in the
  /// bounding box.
  virtual bool contains(const dealii::Point<dim> &x) const;
  /// True if the closed box [lo, hi] lies in the closed domain. Default: both corners
  /// in the bounding box (convex domains).
  virtual bool contains_box(const dealii::Point<dim> &lo, const dealii::Point<dim> &hi) const;

  /// Derived outputs at T (default: over-/undershoots against the exact solution).
  virtual ProbeSpec<dim> probes() const { return {}; }

  /// nullptr if the scene has no exact solution.
  const ExactSolution<dim> *exact() const { return exact_solution.get(); }

  double epsilon = 1.;
  double end_time = 1.;
  std::set<dealii::types::boundary_id> dirichlet_ids{0};
  std::set<dealii::types::boundary_id> neumann_ids;

protected:
  /// rhs_at_times for the default rhs() (f from the exact solution): a separable
  /// solution's S, grad S and Lap S once for all times.
  void exact_rhs_at_times(const dealii::Point<dim> &x, const std::vector<double> &times,
                          double *out) const;

  std::unique_ptr<ExactSolution<dim>> exact_solution;
};

/// Builds the scene named in the options; InputError on an unknown variant.
template <int dim> std::unique_ptr<Scene<dim>> create_scene(const SceneOptions &options);
} // namespace anisodwr
