#include "goal/goal.h"

#include "time/slab_vector.h"

namespace anisodwr
{
using namespace dealii;

template <int dim>
LocalGoal<dim>::LocalGoal(const Scene<dim> &scene, const Mapping<dim> &mapping,
                          const FiniteElement<dim> &fe, const Triangulation<dim> &tria,
                          const std::vector<GoalSpec> &goals, bool over_time)
    : fe(fe)
{
  static_assert(dim == 2, "the goal kinds are implemented in 2D");
  for (const auto &goal : goals)
    if (auto part = goal_type(goal.kind).part(goal, scene, mapping, fe, tria, over_time))
      parts.emplace_back(std::move(part), goal.weight);
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
bool assemble_goal_vector(const Space<dim> &space, const GoalSpec &goal, bool over_time,
                          Vector<double> &j)
{
  const LocalGoal<dim> local(space.scene, space.mapping(), space.finite_element(),
                             space.dof_handler().get_triangulation(), {unweighted(goal)},
                             over_time);
  j.reinit(space.n_dofs());
  if (local.empty())
    return false;
  Vector<double> jc;
  std::vector<types::global_dof_index> idx(space.finite_element().n_dofs_per_cell());
  for (const auto &cell : space.dof_handler().active_cell_iterators())
    if (local.cell_vector(cell, jc))
    {
      cell->get_dof_indices(idx);
      for (unsigned int i = 0; i < idx.size(); ++i)
        j(idx[i]) += jc(i);
    }
  return true;
}

template <int dim>
void assemble_goal_vector(const Space<dim> &space, const GoalSpec &goal,
                          Vector<double> &j)
{
  assemble_goal_vector(space, goal, goal.over_time, j);
}

template <int dim>
GoalVectors assemble_goal_vectors(const Space<dim> &space,
                                  const std::vector<GoalSpec> &goals)
{
  GoalVectors g;
  Vector<double> j;
  for (const auto &goal : goals)
  {
    for (const bool over_time : {true, false})
      if (assemble_goal_vector(space, goal, over_time, j))
      {
        Vector<double> &target = over_time ? g.over_time : g.at_end;
        if (target.size() == 0)
          target.reinit(space.n_dofs());
        target.add(goal.weight, j);
      }
    g.offset += goal.weight * goal_type(goal.kind).offset(space, unweighted(goal));
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
  double J = j.offset;
  Vector<double> rhs;
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    slab_goal_rhs(j, mesh, basis, n, rhs);
    J += rhs * U[n];
  }
  return J;
}

template class LocalGoal<2>;
template bool assemble_goal_vector<2>(const Space<2> &, const GoalSpec &, bool,
                                      Vector<double> &);
template void assemble_goal_vector<2>(const Space<2> &, const GoalSpec &,
                                      Vector<double> &);
template GoalVectors assemble_goal_vectors<2>(const Space<2> &,
                                              const std::vector<GoalSpec> &);
} // namespace anisodwr
