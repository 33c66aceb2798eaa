#pragma once
// One spatial finite element space on a (possibly anisotropically refined) mesh:
// FE_Q(p), DoFs, hanging-node + Dirichlet constraints, the sparsity pattern, and
// the assembly of the SUPG spatial matrices and load vectors of doc/method.md §2-3.
#include "space/weak_form.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <functional>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "scene/scene.h"
#include "space/stabilization.h"

namespace anisodwr
{
/// Spatial matrices at one time t (doc/method.md §2), unconstrained (M, A) and condensed
/// with the homogeneous constraints (Mc = C^T M C, Ac = C^T A C, with a positive diagonal
/// on constrained rows). All four share Space::sparsity().
struct SpatialMatrices
{
  dealii::SparseMatrix<double> M, A, Mc, Ac;
};

template <int dim> class Space
{
public:
  /// SUPG: delta_K = delta0 h_K with h_K = |K|^{1/dim} (doc/method.md §3), or, with
  /// SupgLength::streamline, h_K = the length of K along b (for anisotropic cells); if
  /// supg_tau_factor > 0, delta_K <= supg_tau_factor * tau_n on a slab of length tau_n
  /// (the stability bound of SUPG with the time derivative in the test function).
  /// The cells are mapped by MappingQ(mapping_degree) through the triangulation's
  /// manifolds: 1 gives straight edges (the polygon through the vertices on a curved
  /// boundary), 2 and more follow a curved boundary between the vertices.
  Space(const Scene<dim> &scene, const dealii::Triangulation<dim> &tria,
        unsigned int degree, const Stabilization &stabilization,
        unsigned int mapping_degree = 1);

  /// Distributes DoFs, builds constraints and the sparsity pattern (call after
  /// refinement).
  void setup();
  /// Which boundary face (cell, face number) of an outflow Dirichlet part (outflow_speed()
  /// > 0 at all three times) leaves its DoFs unconstrained.
  using FaceRule = std::function<bool(const dealii::CellAccessor<dim, dim> &, unsigned int)>;
  /// Leave the DoFs of the outflow Dirichlet faces that `rule` selects unconstrained: the
  /// weak form then imposes eps d_n v + (b.n) v = 0 there on the transposed problem,
  /// i.e. v = O(eps) on its inflow boundary (the adjoint's natural inflow condition,
  /// doc/method.md §5). A DoF that is also on another Dirichlet face stays constrained.
  /// Set before setup(); empty: every Dirichlet DoF constrained.
  void set_natural_outflow(FaceRule rule) { natural_rule = std::move(rule); }
  /// Whether setup() left a Dirichlet DoF unconstrained.
  bool has_natural_outflow() const { return natural_outflow; }
  /// setup() numbers the DoFs downstream along b (the scene's convection at the centre
  /// of its bounding box at t = 0): ILU and Gauss-Seidel then sweep with the flow, which
  /// makes them nearly exact for convection-dominated slab matrices. No effect if b = 0.
  void set_downstream_numbering(bool on)
  {
    downstream = [on](dealii::types::global_dof_index) { return on; };
  }
  /// The same, decided by `rule` from the number of DoFs once they are distributed.
  void set_downstream_numbering(std::function<bool(dealii::types::global_dof_index)> rule)
  {
    downstream = std::move(rule);
  }

  unsigned int degree() const { return fe.degree; }
  dealii::types::global_dof_index n_dofs() const { return dofs.n_dofs(); }
  const dealii::DoFHandler<dim> &dof_handler() const { return dofs; }
  const dealii::Mapping<dim> &mapping() const { return map; }
  unsigned int mapping_degree() const { return map.get_degree(); }
  const dealii::FiniteElement<dim> &finite_element() const { return fe; }
  /// Hanging nodes + homogeneous Dirichlet.
  const dealii::AffineConstraints<double> &constraints() const { return homogeneous; }
  const dealii::SparsityPattern &sparsity() const { return pattern; }
  /// The Dirichlet values u_D(., t) by DoF: the DoFs of every Dirichlet face (at a DoF
  /// of two boundary ids the first id's value), the hanging nodes excepted.
  std::map<dealii::types::global_dof_index, double> dirichlet_values(double t) const;
  /// Sets v's constrained entries for the Dirichlet values `values` (dirichlet_values):
  /// those at the Dirichlet DoFs, then the hanging nodes' from their parents; the other
  /// entries stay. (What distribute() of the hanging-node and Dirichlet constraints does,
  /// without building them for each time.)
  void distribute_dirichlet(const std::map<dealii::types::global_dof_index, double> &values,
                            dealii::Vector<double> &v) const;

  /// M(t), A(t) and their condensed forms on a slab of length tau (delta_K's bound).
  void assemble_matrices(double t, double tau, SpatialMatrices &m) const;
  /// The loads F_i(t_k) = (f(t_k), phi_i + delta_K b(t_k).grad phi_i) +
  /// (u_N(t_k), phi_i)_{Gamma_N} for several times of one slab. If the scene's f is a
  /// sum of products a_j(t) g_j(x) (Scene::separable_rhs), the vectors
  /// (g_j, phi_i + delta_K b.grad phi_i) are assembled once per mesh (and slab length,
  /// if delta_K depends on it) and combined per time; otherwise one pass over the cells
  /// evaluates f at every time.
  void assemble_loads(const std::vector<double> &times, double tau,
                      std::vector<dealii::Vector<double>> &F) const;
  /// (u_0, phi_i + delta_K b(0).grad phi_i): the SUPG initial term (tau: the first
  /// slab's length).
  void assemble_initial(double tau, dealii::Vector<double> &U0) const;

  /// SUPG parameter delta_K of a cell on a slab of length tau.
  double delta(const typename dealii::Triangulation<dim>::cell_iterator &cell,
               double tau) const
  {
    return bounded_delta(unbounded_delta(cell), tau);
  }
  /// delta0 h_K, before the bound by tau_n.
  double
  unbounded_delta(const typename dealii::Triangulation<dim>::cell_iterator &cell) const;
  /// min(d, supg_tau_factor * tau) (d if supg_tau_factor == 0).
  double bounded_delta(double d, double tau) const
  {
    const double f = stab.supg_tau_factor;
    return f > 0 ? std::min(d, f * tau) : d;
  }
  /// The artificial diffusion of the stabilization terms beside SUPG on a cell
  /// (stabilization_terms.h): D_K summed over the active terms, and whether any term acts
  /// on the cell (D_K != 0). Assembly and estimator alike take it from here.
  struct CellDiffusion
  {
    dealii::Tensor<2, dim> D;
    bool active = false;
    /// The integrand (D_K grad u, grad v) (weak_form::cell_diffusion); 0 without work
    /// where no term acts.
    double form(const dealii::Tensor<1, dim> &grad_u,
                const dealii::Tensor<1, dim> &grad_v) const
    {
      return active ? weak_form::cell_diffusion(D, grad_u, grad_v) : 0.;
    }
  };
  CellDiffusion
  cell_diffusion(const typename dealii::Triangulation<dim>::cell_iterator &cell) const;
  /// A factor s_K in [0, 1] on each active cell's stabilization terms
  /// (StabilizationCell::switch_factor), by active cell index
  /// (Stabilization::crosswind_form = residual: crosswind_scale() of a previous
  /// solution). Empty: 1 on every cell. Set before the first assembly.
  void set_crosswind_scale(std::vector<double> scale) { cw_scale = std::move(scale); }
  /// Whether delta_K (and so M, A and the loads) depends on the slab length.
  bool delta_depends_on_tau() const
  {
    return stab.supg_tau_factor > 0 && stab.delta0 > 0;
  }

  const Scene<dim> &scene;

private:
  /// The length of `cell` along the unit vector `beta` through its centre.
  double length_along(const typename dealii::Triangulation<dim>::cell_iterator &cell,
                      const dealii::Tensor<1, dim> &beta) const;
  const Stabilization stab;
  FaceRule natural_rule;
  bool natural_outflow = false;
  std::vector<double> cw_scale;
  std::function<bool(dealii::types::global_dof_index)> downstream;
  dealii::FE_Q<dim> fe;
  dealii::MappingQ<dim> map;
  dealii::DoFHandler<dim> dofs;
  dealii::AffineConstraints<double> homogeneous;
  dealii::AffineConstraints<double> hanging; ///< the hanging nodes alone
  dealii::SparsityPattern pattern;

  /// sum_k f_k(x) (phi_i + delta_K b_k(x).grad phi_i) over the cells, one vector per
  /// k; f(x, out) sets out[k] = f_k(x) for all k at once.
  void assemble_volume_loads(
      unsigned int n_sources, double tau,
      const std::function<void(const dealii::Point<dim> &, double *)> &f,
      const std::function<dealii::Tensor<1, dim>(const dealii::Point<dim> &,
                                                 unsigned int)> &b,
      std::vector<dealii::Vector<double>> &F) const;
  /// Adds (u_N(t_k), phi_i)_{Gamma_N} to F[k].
  void add_neumann_loads(const std::vector<double> &times,
                         std::vector<dealii::Vector<double>> &F) const;
  /// The spatial parts of separable loads, by slab length (one entry if delta_K does
  /// not depend on it); cleared by setup().
  mutable std::map<double, std::vector<dealii::Vector<double>>> load_terms;
  mutable std::mutex load_terms_mutex;
};
/// The thickness of `cell` across its face `f`: the distance of the centres of that face
/// and the opposite one.
double thickness_across(const dealii::CellAccessor<2, 2> &cell, unsigned int f);
/// The smallest b.n over t = 0, T/2, T at the centre of the boundary face `f` of `cell`
/// (n the outward normal of the straight face through its vertices), and the largest:
/// the face is an outflow face at all three times if min > 0, at one of them if max > 0.
std::pair<double, double>
outflow_speed(const dealii::CellAccessor<2, 2> &cell, unsigned int f,
              const Scene<2> &scene);

/// discretization.mapping_degree = 0 (auto): p (isoparametric) if a cell, face or line
/// of `tria` carries a manifold other than the flat one (a curved boundary or interior),
/// else 1.
template <int dim>
unsigned int auto_mapping_degree(const dealii::Triangulation<dim> &tria, unsigned int p);

} // namespace anisodwr
