#pragma once
// A scene: geometry, coefficients, data and (where known) the exact solution of
//   d_t u - eps Lap u + b.grad u + alpha u = f.
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include "goal/goal_spec.h"

#include <memory>
#include <set>
#include <string>

namespace dealii
{
template <int dim, int spacedim> class Triangulation;
}

namespace anisodwr
{
struct Parameters;

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
  virtual double initial_value(const dealii::Point<dim> &x) const;
  virtual double dirichlet_value(const dealii::Point<dim> &x, double t) const;
  /// eps grad u . n on the Neumann boundary.
  virtual double neumann_value(const dealii::Point<dim> &x,
                               const dealii::Tensor<1, dim> &n, double t) const;

  /// The scene's goal functionals (SCENES.md); `radius` is the mollifier radius of
  /// point goals. Default: the value at the domain's centre (0.5, 0.5) at T.
  virtual std::vector<GoalSpec> default_goals(double radius) const;

  /// nullptr if the scene has no exact solution.
  const ExactSolution<dim> *exact() const { return exact_solution.get(); }

  double epsilon = 1.;
  double end_time = 1.;
  std::set<dealii::types::boundary_id> dirichlet_ids{0};
  std::set<dealii::types::boundary_id> neumann_ids;

protected:
  std::unique_ptr<ExactSolution<dim>> exact_solution;
};

/// Builds the scene named in the parameters; InputError on an unknown name/variant.
template <int dim> std::unique_ptr<Scene<dim>> create_scene(const Parameters &prm);
} // namespace anisodwr
