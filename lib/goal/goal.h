#pragma once
// Linear goal functionals J(u) = int_I j_t(u(t)) dt + j_T(u(T)) (doc/method.md §4) and
// the mollifier delta_{s,c}(x) = C exp(1 - 1/(1 - |x-c|^2/s^2)) with int delta = 1.
#include "scene/goal_spec.h"
#include "goal/goal_type.h"
#include "space/space.h"
#include "time/temporal_basis.h"
#include "time/time_mesh.h"

#include <deal.II/fe/mapping.h>

#include <memory>
#include <string>
#include <vector>

namespace anisodwr
{
/// C such that the mollifier of radius s integrates to 1 over R^dim (computed by
/// quadrature of the radial profile, not hard-coded).
double mollifier_constant(unsigned int dim, double s);

template <int dim>
double mollifier(const dealii::Point<dim> &x, const dealii::Point<dim> &c, double s,
                 double C);

/// Cell-local goal vectors j_l = sum_g w_g j_g(phi_l) of one part (over time or at T)
/// of a set of goals, for any element on the triangulation (the estimator evaluates
/// J'(w) cell by cell with it).
template <int dim> class LocalGoal
{
public:
  LocalGoal(const Scene<dim> &scene, const dealii::Mapping<dim> &mapping,
            const dealii::FiniteElement<dim> &fe, const dealii::Triangulation<dim> &tria,
            const std::vector<GoalSpec> &goals, bool over_time);
  bool empty() const { return parts.empty(); }
  /// j on `cell` (zero outside the goals' support). Returns false if j is zero.
  bool cell_vector(const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
                   dealii::Vector<double> &j) const;

private:
  const dealii::FiniteElement<dim> &fe;
  /// each goal's part and weight
  std::vector<std::pair<std::shared_ptr<const GoalPart<dim>>, double>> parts;
};

/// j_i = j(phi_i) for the spatial functional of the goal's part over I (over_time) or
/// at T (weight not applied). Returns false, with j zero, if the goal has no such part.
template <int dim>
bool assemble_goal_vector(const Space<dim> &space, const GoalSpec &goal, bool over_time,
                          dealii::Vector<double> &j);
/// The same for the part of the goal's own GoalSpec::over_time.
template <int dim>
void assemble_goal_vector(const Space<dim> &space, const GoalSpec &goal,
                          dealii::Vector<double> &j);

/// The split of a (weighted sum of) goal(s) into its time-integrated and end-time parts
/// and the constant of the affine ones: J(u) = int_I j_t(u) dt + j_T(u(T)) + offset.
struct GoalVectors
{
  dealii::Vector<double> over_time, at_end; ///< empty if the part is absent
  double offset = 0;
};

template <int dim>
GoalVectors assemble_goal_vectors(const Space<dim> &space,
                                  const std::vector<GoalSpec> &goals);

/// J(u_h) for slab coefficient vectors U (interleaved).
double evaluate_goal(const GoalVectors &j, const TimeMesh &mesh,
                     const TemporalBasis &basis,
                     const std::vector<dealii::Vector<double>> &U);

/// J(u) of one goal (weight not applied) for the scene's exact solution u, by globally
/// adaptive nested Gauss quadrature in space over the goal's support clipped to the
/// scene's box (tolerance `tol` relative to the integral of |integrand|; the cost
/// grows with the logarithm of the layer width and is bounded by a work limit) and
/// composite Gauss in time for goals over I. If the tolerance is not reached, a value
/// still accurate to 1e-8 is returned with a warning on stderr; otherwise, or if the
/// value is not finite, or the scene has no exact solution: InputError.
template <int dim>
double exact_goal(const Scene<dim> &scene, const GoalSpec &goal, double tol = 1e-13);

/// Adjoint right-hand side of slab n: int_{I_n} l_k j_t dt (+ y_k j_T on the last slab).
void slab_goal_rhs(const GoalVectors &j, const TimeMesh &mesh, const TemporalBasis &basis,
                   unsigned int n, dealii::Vector<double> &rhs);
} // namespace anisodwr
