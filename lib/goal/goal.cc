#include "goal/goal.h"

#include "time/slab_vector.h"

namespace anisodwr
{
using namespace dealii;

template <int dim>
LocalGoal<dim>::LocalGoal(const Mapping<dim> &mapping, const FiniteElement<dim> &fe,
                          const Triangulation<dim> &tria,
                          const std::vector<GoalSpec> &goals, bool over_time)
    : fe(fe)
{
  static_assert(dim == 2, "the goal kinds are implemented in 2D");
  for (const auto &goal : goals)
    if (goal.over_time == over_time)
      parts.emplace_back(goal_type(goal.kind).part(goal, mapping, fe, tria), goal.weight);
}

template <int dim>
bool LocalGoal<dim>::cell_vector(
    const typename Triangulation<dim>::active_cell_iterator &cell,
    Vector<double> &j) const
{
  j.reinit(fe.n_dofs_per_cell());
  bool nonzero = false;
  for (const auto &[part, weight] : parts)
    nonzero |= part->add_cell_vector(cell, weight, j);
  return nonzero;
}

template <int dim>
void assemble_goal_vector(const Space<dim> &space, const GoalSpec &goal,
                          Vector<double> &j)
{
  GoalSpec unit = goal;
  unit.weight = 1;
  const LocalGoal<dim> local(space.mapping(), space.finite_element(),
                             space.dof_handler().get_triangulation(), {unit},
                             goal.over_time);
  j.reinit(space.n_dofs());
  Vector<double> jc;
  std::vector<types::global_dof_index> idx(space.finite_element().n_dofs_per_cell());
  for (const auto &cell : space.dof_handler().active_cell_iterators())
    if (local.cell_vector(cell, jc))
    {
      cell->get_dof_indices(idx);
      for (unsigned int i = 0; i < idx.size(); ++i)
        j(idx[i]) += jc(i);
    }
}

template <int dim>
GoalVectors assemble_goal_vectors(const Space<dim> &space,
                                  const std::vector<GoalSpec> &goals)
{
  GoalVectors g;
  Vector<double> j;
  for (const auto &goal : goals)
  {
    assemble_goal_vector(space, goal, j);
    Vector<double> &target = goal.over_time ? g.over_time : g.at_end;
    if (target.size() == 0)
      target.reinit(space.n_dofs());
    target.add(goal.weight, j);
  }
  return g;
}

namespace
{
/// int_0^1 l_k ds = row sums of the temporal mass matrix.
std::vector<double> basis_integrals(const TemporalBasis &basis)
{
  std::vector<double> s(basis.n_dofs(), 0.);
  for (unsigned int k = 0; k < basis.n_dofs(); ++k)
    for (unsigned int l = 0; l < basis.n_dofs(); ++l)
      s[k] += basis.mass()(k, l);
  return s;
}
} // namespace

void slab_goal_rhs(const GoalVectors &j, const TimeMesh &mesh, const TemporalBasis &basis,
                   unsigned int n, Vector<double> &rhs)
{
  const unsigned int m = basis.n_dofs();
  const auto nd = j.over_time.size() ? j.over_time.size() : j.at_end.size();
  rhs.reinit(nd * m);
  if (j.over_time.size())
    add_kron_vector(mesh.tau(n), basis_integrals(basis), j.over_time, rhs);
  if (j.at_end.size() && n + 1 == mesh.n_slabs())
    add_kron_vector(1., basis.right_trace(), j.at_end, rhs);
}

double evaluate_goal(const GoalVectors &j, const TimeMesh &mesh,
                     const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  double J = 0;
  Vector<double> rhs;
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    slab_goal_rhs(j, mesh, basis, n, rhs);
    J += rhs * U[n];
  }
  return J;
}

template class LocalGoal<2>;
template void assemble_goal_vector<2>(const Space<2> &, const GoalSpec &,
                                      Vector<double> &);
template GoalVectors assemble_goal_vectors<2>(const Space<2> &,
                                              const std::vector<GoalSpec> &);
} // namespace anisodwr
