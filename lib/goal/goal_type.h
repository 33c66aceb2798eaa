#pragma once
// The goal kinds (goal.kind; doc/method.md §4), in the manner of deal.II step-14's
// DualFunctional: one class per kind owns the parsing of its locations, the cells it
// meets, its cell vectors with their sub-cell quadrature, its exact value and the check
// that a mesh resolves it. The registry (goal_registry.cc) lists every kind; the key
// goal.kind, its documentation and the tests iterate it.
#include "scene/goal_spec.h"

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace dealii
{
template <int dim, int spacedim> class Mapping;
template <int dim, int spacedim> class FiniteElement;
} // namespace dealii

namespace anisodwr
{
template <int dim> class Scene;
template <int dim> class Space;
namespace nested
{
struct NestedIntegrals;
}

/// One goal (weight 1) evaluated cell by cell for one finite element.
template <int dim> class GoalPart
{
public:
  virtual ~GoalPart() = default;
  /// Adds `weight` j(phi_l) to j(l) for the shape functions phi_l of `cell` (j has the
  /// cell's size). Returns false if j(phi) vanishes on the cell.
  virtual bool
  add_cell_vector(const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
                  double weight, dealii::Vector<double> &j) const = 0;
};

/// A goal kind.
class GoalType
{
public:
  virtual ~GoalType() = default;
  /// Its value of goal.kind and of GoalSpec::kind.
  virtual std::string name() const = 0;
  /// One line for the documentation of goal.kind.
  virtual std::string doc() const = 0;
  /// What one location of goal.locations is, in messages: "point", "rectangle".
  virtual std::string noun() const = 0;
  /// The syntax of one location ("x,y") and an example inside the unit square.
  virtual std::string syntax() const = 0;
  virtual std::string example() const = 0;
  /// How many numbers one location has (0: one or more).
  virtual unsigned int n_numbers() const = 0;
  /// Whether goal.radius applies to the kind.
  virtual bool has_radius() const { return false; }

  /// Sets the location of `g` from the numbers of one location. InputError, with
  /// `bad` ("<source>: invalid point '1,2' in key 'goal.locations'; ") in front, if
  /// they do not describe a location of the kind inside the scene's domain.
  virtual void set_location(const std::vector<double> &numbers, const Scene<2> &scene,
                            const std::string &bad, GoalSpec &g) const = 0;

  /// The part of J(u) = int_I j_t(u(t)) dt + j_T(u(T)) + c of goal `g` over I
  /// (over_time: j_t) or at T (j_T), evaluated cell by cell for `fe` on `tria`; null
  /// if the goal has no such part (a point or mean goal has the part of its
  /// GoalSpec::over_time only).
  virtual std::unique_ptr<GoalPart<2>>
  part(const GoalSpec &g, const Scene<2> &scene, const dealii::Mapping<2, 2> &mapping,
       const dealii::FiniteElement<2, 2> &fe, const dealii::Triangulation<2> &tria,
       bool over_time) const = 0;
  /// The constant c of an affine goal on the mesh of `space` (0 for a linear one).
  virtual double offset(const Space<2> &, const GoalSpec &) const { return 0.; }

  /// j(u(t)) of the scene's exact solution u, by the nested integrals `n` (their
  /// outer and inner integrals over the goal's support clipped to the scene's box).
  virtual double exact_value(const Scene<2> &scene, const GoalSpec &g, double t,
                             nested::NestedIntegrals &n) const = 0;

  /// Whether the integral w of the goal's weight function by its quadrature on a mesh
  /// is close enough to the exact one for the mesh to resolve the goal.
  virtual bool weight_accepted(const GoalSpec &g, const Scene<2> &scene,
                               double w) const = 0;
  /// The message of the InputError for a goal that the mesh of `space` does not
  /// resolve (`integrates`: what its weight integrates to), naming the key, its source
  /// and the smallest size accepted there.
  virtual std::string unresolved(const Space<2> &space, const GoalSpec &g,
                                 const GoalInput &in, const Scene<2> &scene,
                                 const std::string &integrates) const = 0;
};

/// Every goal kind, in the order of the documentation.
const std::vector<const GoalType *> &goal_types();
/// The kind named `kind`; InputError naming the kinds if there is none.
const GoalType &goal_type(const std::string &kind);
/// The names of goal.kind: "scene" and every kind, joined by `separator`.
std::string goal_kind_choices(const std::string &separator);
/// The documentation of goal.kind, from the kinds' one-liners.
std::string goal_kind_doc();
/// The documentation of goal.locations, from the kinds' syntax.
std::string goal_locations_doc();

/// J(1) of the goal's spatial part, j(1) = the sum of its goal vector (the shape
/// functions sum to 1): the integral of its weight function by its quadrature on the
/// mesh of `space`.
double goal_of_one(const Space<2> &space, const GoalSpec &g);
/// goal_of_one (in w), and whether the goal's kind accepts it.
bool goal_weight_resolved(const Space<2> &space, const GoalSpec &g,
                          const Scene<2> &scene, double &w);
/// v with 6 significant digits (for messages).
std::string six_digits(double v);
} // namespace anisodwr
