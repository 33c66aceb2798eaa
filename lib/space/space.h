#pragma once
// One spatial finite element space on a (possibly anisotropically refined) mesh:
// FE_Q(p), DoFs, hanging-node + Dirichlet constraints, the sparsity pattern, and
// the assembly of the SUPG spatial matrices and load vectors of SPEC §2.
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include "scene/scene.h"

namespace anisodwr
{
/// Spatial matrices at one time t (SPEC §2), unconstrained (M, A) and condensed with
/// the homogeneous constraints (Mc = C^T M C, Ac = C^T A C, with a positive diagonal on
/// constrained rows). All four share Space::sparsity().
struct SpatialMatrices
{
  dealii::SparseMatrix<double> M, A, Mc, Ac;
};

template <int dim> class Space
{
public:
  /// SUPG: delta_K = delta0 h_K with h_K = |K|^{1/dim} (SPEC §2), or, if
  /// `streamline_length`, h_K = the length of K along b (for anisotropic cells).
  Space(const Scene<dim> &scene, const dealii::Triangulation<dim> &tria,
        unsigned int degree, double delta0, bool streamline_length = false);

  /// Distributes DoFs, builds constraints and the sparsity pattern (call after
  /// refinement).
  void setup();

  unsigned int degree() const { return fe.degree; }
  dealii::types::global_dof_index n_dofs() const { return dofs.n_dofs(); }
  const dealii::DoFHandler<dim> &dof_handler() const { return dofs; }
  const dealii::Mapping<dim> &mapping() const { return map; }
  const dealii::FiniteElement<dim> &finite_element() const { return fe; }
  /// Hanging nodes + homogeneous Dirichlet.
  const dealii::AffineConstraints<double> &constraints() const { return homogeneous; }
  const dealii::SparsityPattern &sparsity() const { return pattern; }
  /// Hanging nodes + Dirichlet values u_D(., t).
  void make_dirichlet_constraints(double t, dealii::AffineConstraints<double> &c) const;

  /// M(t), A(t) and their condensed forms.
  void assemble_matrices(double t, SpatialMatrices &m) const;
  /// F_i(t) = (f(t), phi_i + delta_K b(t).grad phi_i) + (u_N(t), phi_i)_{Gamma_N}.
  void assemble_load(double t, dealii::Vector<double> &F) const;
  /// (u_0, phi_i + delta_K b(0).grad phi_i): the SUPG initial term.
  void assemble_initial(dealii::Vector<double> &U0) const;

  /// L2 norm of u(t) - u_h over the domain (u_h a full, constraint-distributed vector).
  double l2_error(const dealii::Vector<double> &uh, double t) const;

  /// SUPG parameter delta_K of a cell.
  double delta(const typename dealii::Triangulation<dim>::cell_iterator &cell) const;

  const Scene<dim> &scene;

private:
  double delta0;
  bool streamline_length;
  dealii::FE_Q<dim> fe;
  dealii::MappingQ<dim> map;
  dealii::DoFHandler<dim> dofs;
  dealii::AffineConstraints<double> homogeneous;
  dealii::SparsityPattern pattern;
};
} // namespace anisodwr
