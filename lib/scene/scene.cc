#include "scene/scene.h"

#include "base/errors.h"
#include "scene/scene_registry.h"

#include <deal.II/grid/tria_accessor.h>

namespace anisodwr
{
namespace
{
template <int dim>
const ExactSolution<dim> &require_exact(const ExactSolution<dim> *u, const char *what)
{
  if (!u)
    throw std::logic_error(
        std::string("scene has no exact solution and does not override ") + what);
  return *u;
}
/// f = S T' - eps Lap S T + b.grad S T + alpha S T at (x, t) for a separable exact
/// solution u = T(t) S(x), from S, grad S, Lap S at x.
template <int dim>
double separable_rhs_at(const Scene<dim> &scene, const ExactSolution<dim> &u,
                        const dealii::Point<dim> &x, double t, double S,
                        const dealii::Tensor<1, dim> &grad, double lap)
{
  const double T = u.time_factor(t, 0), dT = u.time_factor(t, 1);
  return S * dT - scene.epsilon * (lap * T) + scene.convection(x, t) * (grad * T) +
         scene.reaction(x, t) * (S * T);
}
} // namespace

template <int dim> double Scene<dim>::rhs(const dealii::Point<dim> &x, double t) const
{
  const auto &u = require_exact(exact(), "rhs()");
  if (u.separable()) // the factors once each (the same products as below)
  {
    double S, lap;
    dealii::Tensor<1, dim> grad;
    u.space_jet(x, S, grad, lap);
    return separable_rhs_at(*this, u, x, t, S, grad, lap);
  }
  return u.time_derivative(x, t) - epsilon * u.laplacian(x, t) +
         convection(x, t) * u.gradient(x, t) + reaction(x, t) * u.value(x, t);
}

template <int dim>
void Scene<dim>::rhs_at_times(const dealii::Point<dim> &x, const std::vector<double> &times,
                              double *out) const
{
  for (std::size_t k = 0; k < times.size(); ++k)
    out[k] = rhs(x, times[k]);
}

template <int dim>
void Scene<dim>::exact_rhs_at_times(const dealii::Point<dim> &x,
                                    const std::vector<double> &times, double *out) const
{
  const auto &u = require_exact(exact(), "rhs()");
  if (!u.separable())
  {
    Scene<dim>::rhs_at_times(x, times, out);
    return;
  }
  double S, lap;
  dealii::Tensor<1, dim> grad;
  u.space_jet(x, S, grad, lap);
  for (std::size_t k = 0; k < times.size(); ++k)
    out[k] = separable_rhs_at(*this, u, x, times[k], S, grad, lap);
}

template <int dim>
bool Scene<dim>::separable_rhs(std::vector<LoadTerm<dim>> &terms) const
{
  terms.clear();
  const ExactSolution<dim> *u = exact();
  if (!u || !u->separable() || coefficients_depend_on_time())
    return false;
  terms.push_back({[u](double t) { return u->time_factor(t, 1); },
                   [u](const dealii::Point<dim> &x) { return u->space_value(x); }});
  terms.push_back({[u](double t) { return u->time_factor(t, 0); },
                   [this, u](const dealii::Point<dim> &x)
                   {
                     return -epsilon * u->space_laplacian(x) +
                            convection(x, 0.) * u->space_gradient(x) +
                            reaction(x, 0.) * u->space_value(x);
                   }});
  return true;
}

template <int dim> double Scene<dim>::initial_value(const dealii::Point<dim> &x) const
{
  return require_exact(exact(), "initial_value()").value(x, 0.);
}

template <int dim>
double Scene<dim>::dirichlet_value(const dealii::Point<dim> &x, double t) const
{
  return require_exact(exact(), "dirichlet_value()").value(x, t);
}

template <int dim>
double Scene<dim>::neumann_value(const dealii::Point<dim> &x,
                                 const dealii::Tensor<1, dim> &n, double t) const
{
  return epsilon * (require_exact(exact(), "neumann_value()").gradient(x, t) * n);
}

template <int dim> std::vector<GoalSpec> Scene<dim>::default_goals(double radius) const
{
  GoalSpec g;
  g.name = "u_center_T";
  g.location.assign(dim, 0.5);
  g.radius = radius;
  return {g};
}

template <int dim>
std::array<dealii::Point<dim>, 2> Scene<dim>::bounding_box() const
{
  dealii::Point<dim> hi;
  for (unsigned int d = 0; d < dim; ++d)
    hi[d] = 1.;
  return {{dealii::Point<dim>(), hi}};
}

template <int dim> bool Scene<dim>::contains(const dealii::Point<dim> &x) const
{
  const auto box = bounding_box();
  const double tol = 1e-12 * box[0].distance(box[1]);
  for (unsigned int d = 0; d < dim; ++d)
    if (!(x[d] >= box[0][d] - tol && x[d] <= box[1][d] + tol)) // false for NaN
      return false;
  return true;
}

template <int dim>
bool Scene<dim>::contains_box(const dealii::Point<dim> &lo, const dealii::Point<dim> &hi) const
{
  return contains(lo) && contains(hi);
}

template <int dim> std::unique_ptr<Scene<dim>> create_scene(const SceneOptions &o)
{
  static_assert(dim == 2, "the scene registry holds 2D scenes");
  const SceneEntry *entry = find_scene(o.name);
  if (!entry) // Parameters checks scene.name against the registry
    throw InputError(o.source("scene.name") + ": invalid value '" + o.name +
                     "' for key 'scene.name'; expected one of: " + scene_names(", "));
  std::unique_ptr<Scene<dim>> scene;
  try
  {
    scene = entry->make(o);
    scene->end_time = o.end_time;
  }
  catch (const InputError &e)
  {
    const std::string what = e.what();
    // the scenes' variant errors do not know where the variant came from
    if (what.rfind("invalid value '" + o.variant + "' for key 'scene.variant'", 0) == 0)
      throw InputError(o.variant_source + ": " + what);
    throw;
  }
  return scene;
}

dealii::Tensor<1, 2> outward_normal(const dealii::CellAccessor<2, 2> &cell, unsigned int f)
{
  const auto face = cell.face(f);
  const dealii::Tensor<1, 2> e = face->vertex(1) - face->vertex(0);
  dealii::Tensor<1, 2> n({e[1], -e[0]});
  if (n * (face->center() - cell.center()) < 0)
    n = -n;
  return n / n.norm();
}

template class Scene<2>;
template std::unique_ptr<Scene<2>> create_scene<2>(const SceneOptions &);
} // namespace anisodwr
