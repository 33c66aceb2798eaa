#include "adaptivity/hanging_defect.h"

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_tools.h>
#include <deal.II/lac/affine_constraints.h>

#include <cmath>
#include <limits>

namespace anisodwr
{
using namespace dealii;

namespace
{
constexpr unsigned int none = std::numeric_limits<unsigned int>::max();

/// The direction in which the masters of constrained DoF i lie (the largest coordinate
/// distance to them: along the coarse face).
template <int dim>
unsigned char direction_of(types::global_dof_index i, const AffineConstraints<double> &c,
                           const std::vector<Point<dim>> &points)
{
  Tensor<1, dim> reach;
  for (const auto &[m, w] : *c.get_constraint_entries(i))
    for (unsigned int d = 0; d < dim; ++d)
      reach[d] = std::max(reach[d], std::abs(points[m][d] - points[i][d]));
  unsigned char along = 0;
  for (unsigned int d = 1; d < dim; ++d)
    if (reach[d] > reach[along])
      along = d;
  return along;
}

/// The primal and adjoint DoFs of a cell that holds a DoF whose z value is needed, and
/// the local indices of those DoFs.
struct CellDofs
{
  std::vector<types::global_dof_index> p, q;
  std::vector<unsigned int> rows;
};

template <int dim>
std::vector<CellDofs> cells_holding(const Space<dim> &primal, const Space<dim> &adjoint,
                                    const std::vector<bool> &needed)
{
  const auto &dofs = primal.dof_handler();
  const auto &tria = dofs.get_triangulation();
  std::vector<CellDofs> cells;
  std::vector<types::global_dof_index> p(primal.finite_element().n_dofs_per_cell()),
      q(adjoint.finite_element().n_dofs_per_cell());
  for (const auto &cell : dofs.active_cell_iterators())
  {
    cell->get_dof_indices(p);
    CellDofs c;
    for (unsigned int j = 0; j < p.size(); ++j)
      if (needed[p[j]])
        c.rows.push_back(j);
    if (c.rows.empty())
      continue;
    typename DoFHandler<dim>::active_cell_iterator cq(&tria, cell->level(), cell->index(),
                                                      &adjoint.dof_handler());
    cq->get_dof_indices(q);
    c.p = p;
    c.q = q;
    cells.push_back(std::move(c));
  }
  return cells;
}
} // namespace

template <int dim>
HangingDefect<dim>::HangingDefect(const Space<dim> &primal, const Space<dim> &adjoint,
                                  const std::vector<Vector<double>> &Z,
                                  unsigned int n_nodes)
    : n_nodes(n_nodes)
{
  const auto &dofs = primal.dof_handler();
  AffineConstraints<double> hanging;
  DoFTools::make_hanging_node_constraints(dofs, hanging);
  hanging.close();
  if (hanging.n_constraints() == 0)
    return;
  std::vector<Point<dim>> points(dofs.n_dofs());
  DoFTools::map_dofs_to_support_points(primal.mapping(), dofs, points);

  // the constrained DoFs (slots) with their directions, and the DoFs whose z values are
  // needed (constrained or master)
  slot_of.assign(dofs.n_dofs(), none);
  std::vector<types::global_dof_index> constrained;
  std::vector<bool> needed(dofs.n_dofs(), false);
  for (types::global_dof_index i = 0; i < dofs.n_dofs(); ++i)
    if (const auto *entries = hanging.get_constraint_entries(i))
    {
      slot_of[i] = constrained.size();
      constrained.push_back(i);
      directions.push_back(direction_of(i, hanging, points));
      needed[i] = true;
      for (const auto &[m, w] : *entries)
        needed[m] = true;
    }

  // z at the primal's nodes, cell by cell (z is continuous: every cell gives a node the
  // same value), on the cells that hold a needed DoF; then each slot's defect
  FullMatrix<double> to_primal(primal.finite_element().n_dofs_per_cell(),
                               adjoint.finite_element().n_dofs_per_cell());
  FETools::get_interpolation_matrix(adjoint.finite_element(), primal.finite_element(),
                                    to_primal);
  std::vector<types::global_dof_index> dirichlet_masters;
  if (adjoint.has_natural_outflow())
    for (types::global_dof_index i = 0; i < dofs.n_dofs(); ++i)
      if (needed[i] && !hanging.is_constrained(i) && primal.constraints().is_constrained(i))
        dirichlet_masters.push_back(i);
  const auto cells = cells_holding(primal, adjoint, needed);
  std::vector<double> z(dofs.n_dofs());
  defect.assign(Z.size(), std::vector<double>(constrained.size() * n_nodes));
  for (unsigned int n = 0; n < Z.size(); ++n)
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      for (const auto &c : cells)
        for (const unsigned int j : c.rows)
        {
          double s = 0;
          for (unsigned int l = 0; l < c.q.size(); ++l)
            s += to_primal(j, l) * Z[n][c.q[l] * n_nodes + k];
          z[c.p[j]] = s;
        }
      // a natural-outflow adjoint does not vanish on Gamma_D, I_h z does (a master there
      // is a Dirichlet DoF of the primal)
      for (const auto m : dirichlet_masters)
        z[m] = 0.;
      for (unsigned int s = 0; s < constrained.size(); ++s)
      {
        double d = z[constrained[s]];
        for (const auto &[m, w] : *hanging.get_constraint_entries(constrained[s]))
          d -= w * z[m];
        defect[n][s * n_nodes + k] = d;
      }
    }
}

template <int dim>
void HangingDefect<dim>::cell_slots(
    const std::vector<types::global_dof_index> &primal_dofs,
    std::vector<std::pair<unsigned int, unsigned int>> &slots) const
{
  slots.clear();
  if (slot_of.empty())
    return;
  for (unsigned int j = 0; j < primal_dofs.size(); ++j)
    if (slot_of[primal_dofs[j]] != none)
      slots.emplace_back(j, slot_of[primal_dofs[j]]);
}

template class HangingDefect<2>;
} // namespace anisodwr
