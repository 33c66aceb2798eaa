#pragma once
// The scene defined in the config (scene.name = custom): the domain from a deal.II grid
// generator or a Gmsh file, coefficients and data as expressions in x, y, t
// (lib/scene/expression.h), boundary conditions by boundary id, an optional exact
// solution checked against the data, and default goals (README, "Your own problem").
#include "scene/expression.h"
#include "scene/scene.h"

#include <map>
#include <memory>

namespace anisodwr
{
/// Where the data of a scene are compared with its exact solution: points of the domain
/// and points on the boundary with their outward normal and boundary id.
struct SamplePoints
{
  struct OnBoundary
  {
    dealii::Point<2> x;
    dealii::Tensor<1, 2> normal;
    dealii::types::boundary_id id;
  };
  std::vector<dealii::Point<2>> interior;
  std::vector<OnBoundary> boundary;
  /// sample times in (0, T]
  std::vector<double> times;
  /// the size of the domain (step sizes of the difference quotients are fractions of it)
  double length = 1.;
};

/// Checks the scene's data against its exact solution u at the sample points: the PDE
/// residual u_t - eps Lap u + b.grad u + alpha u - f (derivatives of u by fourth-order
/// central differences, the smallest residual over the steps 1e-2 ... 1e-5 of the
/// domain's size and of T), u_0 - u(., 0), g_D - u and g_N - eps grad u.n. A residual
/// larger than `tolerance` times the scale of its check (the largest term of the PDE,
/// max |u|, max |eps grad u.n| + eps max|u| / length over the samples) throws InputError
/// "<where>: key '<key>' does not match scene.exact_solution: ... at (x, y, t) = ...".
/// `keys` names the keys of f, u_0 and the boundary data and where each came from
/// (a message starts with the source of its key; `where` if not given).
struct DataKeys
{
  std::string rhs = "scene.rhs", initial_value = "scene.initial_value",
              dirichlet = "scene.dirichlet", neumann = "scene.neumann";
  std::map<std::string, std::string> sources;
};
void check_against_exact(const Scene<2> &scene, const SamplePoints &points,
                         double tolerance, const std::string &where,
                         const DataKeys &keys = {});

class CustomScene : public Scene<2>
{
public:
  /// Builds the domain, parses every expression and checks the boundary ids and (with
  /// an exact solution) the data; InputError naming the key on any problem.
  explicit CustomScene(const SceneOptions &options);
  ~CustomScene() override;

  std::string name() const override { return "custom"; }
  void make_coarse_grid(dealii::Triangulation<2, 2> &tria) const override;
  dealii::Tensor<1, 2> convection(const dealii::Point<2> &x, double t) const override;
  double reaction(const dealii::Point<2> &x, double t) const override;
  /// True if t appears in b or alpha.
  bool coefficients_depend_on_time() const override { return time_dependent; }
  double rhs(const dealii::Point<2> &x, double t) const override;
  /// f as a_k(t) g_k(x) where that reproduces f to 1e-11 of max |f| at the sample
  /// points and on a 4 x 4 grid in every cell of the refined copy of the domain, and b
  /// and alpha do not depend on t (lib/scene/separable.h); the loads are then assembled
  /// once per mesh.
  bool separable_rhs(std::vector<LoadTerm<2>> &terms) const override
  {
    terms = load_terms;
    return separable;
  }
  double initial_value(const dealii::Point<2> &x) const override;
  /// The data of the boundary id the point lies on are chosen by boundary_value and
  /// boundary_flux; these two take the first Dirichlet / Neumann id's data.
  double dirichlet_value(const dealii::Point<2> &x, double t) const override;
  double neumann_value(const dealii::Point<2> &x, const dealii::Tensor<1, 2> &n,
                       double t) const override;
  double boundary_value(const dealii::Point<2> &x, double t,
                        dealii::types::boundary_id id) const override;
  double boundary_flux(const dealii::Point<2> &x, const dealii::Tensor<1, 2> &n, double t,
                       dealii::types::boundary_id id) const override;

  /// The point goal at the centre of the bounding box (where scene.goals is empty).
  std::vector<GoalSpec> default_goals(double radius) const override;
  /// scene.goals and scene.goals_over_time.
  GoalText goal_text() const override { return goals; }
  std::array<dealii::Point<2>, 2> bounding_box() const override;
  std::string domain_text() const override { return domain; }
  /// In the union of the cells of the coarse mesh refined three times.
  bool contains(const dealii::Point<2> &x) const override;
  /// Both corners in the domain and no boundary segment through the box.
  bool contains_box(const dealii::Point<2> &lo,
                    const dealii::Point<2> &hi) const override;

  /// The points at which the data are checked against the exact solution.
  SamplePoints sample_points() const;
  /// InputError naming the key, the expression and the point where f, alpha, b, u_0,
  /// g_D or g_N is NaN or infinite at a vertex or cell centre of the refined copy of
  /// the domain (boundary data: at its boundary faces' vertices and centres) at t = 0,
  /// T/4, ..., T.
  void check_data_finite(const SceneOptions &o) const;

private:
  struct Geometry;
  std::unique_ptr<Geometry> geometry;
  std::string domain;
  Expression b[2], alpha, f, u0;
  std::map<dealii::types::boundary_id, Expression> g_dirichlet, g_neumann;
  GoalText goals;
  bool time_dependent = false;
  std::vector<LoadTerm<2>> load_terms;
  bool separable = false;

  void read_boundary_data(const SceneOptions &o, const Constants &constants);
};
} // namespace anisodwr
