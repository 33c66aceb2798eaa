#pragma once
// The cell integrals of the DWR estimator (doc/method.md §6) on one cell and one slab,
// as linear functionals on W-local coefficients (internal to lib/adaptivity/; see
// estimator.h).
//   cell_kernel.cc               the cell, its faces and neighbours (hanging nodes)
//   cell_functionals.cc          rho(u), S(u), A(.)(z), S'(., z) and J' on the cell
//   cell_matrices.cc             rho, S, A, S' as matrices (coefficients constant in t)
//   slab_functions.cc            slab functions in W-local coefficients
#include "space/space.h"
#include "space/weak_form.h"
#include "time/temporal_basis.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <initializer_list>
#include <unordered_map>
#include <vector>

namespace anisodwr
{
struct DataQuadrature; // adaptivity/estimator.h

/// Linear functionals on W-local coefficients at the r+2 temporal Gauss points of a
/// slab and at t_{n-1}^+:
///   value(v) = sum_m (val[m] . v(g_m) + dt[m] . d_t v(g_m)) + jump . w(t_{n-1}^+)
/// (for rho and S the "jump" slot multiplies the weight at t_{n-1}^+; for A and S' it
/// multiplies the jump v^+ - v^- of the primal-slot function).
struct SlabFunctional
{
  std::vector<dealii::Vector<double>> val, dt;
  dealii::Vector<double> jump;
  /// Zeroes the functional; reallocates only when the sizes change.
  void reset(unsigned int n_points, unsigned int n);
};

/// A function of time on one slab in W-local coefficients: values and time
/// derivatives at the Gauss points, the value at t_{n-1}^+ and (for jumps) at t_{n-1}^-.
struct SlabFunction
{
  std::vector<dealii::Vector<double>> val, dt;
  dealii::Vector<double> plus, minus;
};

/// F(v); with jump_of_v the jump slot takes v^+ - v^- (v.minus, where given).
double apply(const SlabFunctional &F, const SlabFunction &v, bool jump_of_v);

/// The cell integrals of doc/method.md §6 on one cell and one slab.
template <int dim> class CellKernel
{
public:
  using cell_iterator = typename dealii::DoFHandler<dim>::active_cell_iterator;

  /// data: the data rule (DataQuadrature::copies) and whether load_quadrature_error
  /// is wanted (DataQuadrature::error_term; only then the primal's rule is set up)
  CellKernel(const Space<dim> &primal, const dealii::FE_Q<dim> &fe_w,
             const TemporalBasis &basis, const DataQuadrature &data);

  /// DataQuadrature::error_term: load_quadrature_error may be called
  bool data_quadrature_error() const { return data_error; }

  unsigned int n_points() const { return g.size(); }
  double point(unsigned int m) const { return g[m]; }
  const std::vector<double> &values_at(unsigned int m) const { return ell[m]; }
  const std::vector<double> &derivatives_at(unsigned int m) const { return dell[m]; }

  /// The cell, its face pieces (boundary, same-level, finer and coarser neighbours) and,
  /// for coefficients constant in time, its adjoint cell matrices.
  void reinit(const cell_iterator &cell);

  const std::vector<dealii::types::global_dof_index> &dof_indices() const { return idx; }

  /// rho(u)(.) and S(u)(.) on slab (t0, t0+tau] for u = U_n (interleaved), with
  /// u(t_{n-1}^-) from U_prev's last node or, if null, from u_0.
  void primal_functionals(double t0, double tau, const dealii::Vector<double> &Un,
                          const dealii::Vector<double> *Uprev, SlabFunctional &rho,
                          SlabFunctional &supg) const;

  /// A(.)(zt) (supg == false) or S'(., y = zt) (supg == true) on the slab, for zt given
  /// by its W-local nodal vectors and as their slab function (values at the Gauss points
  /// and at t_{n-1}^+); coefficients constant in time use the nodal vectors, others zt.
  void adjoint_functional(double t0, double tau,
                          const std::vector<dealii::Vector<double>> &nodal,
                          const SlabFunction &zt, bool supg, SlabFunctional &A) const;

  /// One adjoint_functional call's arguments.
  struct AdjointRequest
  {
    const std::vector<dealii::Vector<double>> *nodal;
    const SlabFunction *zt;
    bool supg;
    SlabFunctional *A;
  };
  /// Several adjoint_functional calls of one slab at once: where the coefficients depend
  /// on time, one pass over the points evaluates them once for all requests (and zt once
  /// for consecutive requests of the same zt). At most 3 requests.
  void adjoint_functionals(double t0, double tau,
                           std::initializer_list<AdjointRequest> requests) const;

  /// The Dirichlet data's share of the error, -int_I int_{Gamma_D} eps (g_tau - u) d_n z
  /// ds dt (the term the error identity gains where u_h interpolates g instead of taking
  /// it: doc/method.md §8; g_tau interpolates g at the slab's temporal nodes, where u_h
  /// takes it, so g - g_tau stays with eta_tau), as functionals of the weight z on the
  /// slab, one per direction: a boundary face's share goes to its tangential direction,
  /// the one whose refinement resolves g along the face. False (data untouched) on cells
  /// without Dirichlet faces.
  bool dirichlet_data_functionals(double t0, double tau, const dealii::Vector<double> &Un,
                                  std::array<SlabFunctional, dim> &data) const;

  /// The primal's quadrature error in its data on the slab, as a functional of the weight
  /// w: the primal integrates f and u_0 by QGauss(p+2), this kernel by its finer rule,
  /// and the error identity's rho(u)(z_h) - S(u)(z_h) is their difference, not zero
  /// (doc/method.md §6). val[m]: wt_m (f(t_m), w + delta b.grad w) on the kernel's rule
  /// minus the same on the primal's; jump (first slab only): (u_0, w + delta b.grad w)
  /// likewise. Only with data_quadrature_error(); call after primal_functionals of the
  /// same slab (it reuses f's values).
  void load_quadrature_error(double t0, double tau, bool first_slab,
                             SlabFunctional &D) const;

  /// J'(v) on this cell: the part over I at the Gauss points, the end part at T.
  void goal_functional(double tau, const dealii::Vector<double> &jt,
                       SlabFunctional &J) const;

private:
  struct Piece
  {
    int kind;                          // 0 interior, 1 Neumann, 2 Dirichlet
    dealii::types::boundary_id id = 0; ///< the boundary id (kinds 1 and 2)
    std::vector<double> JxW;
    dealii::FullMatrix<double> w; ///< W's shape values at the points (Neumann data)
    /// Dirichlet pieces: W's normal derivatives and u's shape values at the points, and
    /// the face's tangential direction on the reference cell
    dealii::FullMatrix<double> dn_w, u_values;
    unsigned int tangential = 0;
    std::vector<dealii::Point<dim>> x;
    std::vector<dealii::Tensor<1, dim>> normal;
    std::vector<dealii::types::global_dof_index> nb_dofs;
    /// interior pieces: the neighbour's half of the flux jump, +eps/2 (d_n u_nb, w),
    /// as a matrix on the neighbour's coefficients
    dealii::FullMatrix<double> nb_flux;
  };

  std::vector<dealii::types::global_dof_index>
  dofs_of(const typename dealii::DoFHandler<dim>::cell_iterator &c);

  void add_piece(const dealii::FEFaceValuesBase<dim> &fp,
                 const dealii::FEFaceValuesBase<dim> &fw,
                 const dealii::FEFaceValuesBase<dim> *fn,
                 std::vector<dealii::types::global_dof_index> nb, int kind);

  /// c_l = scale * sum_k a_k U(dofs_l (r+1) + k)
  void combine(const dealii::Vector<double> &U,
               const std::vector<dealii::types::global_dof_index> &dofs,
               const std::vector<double> &a, double scale,
               dealii::Vector<double> &c) const;

  /// node_terms[k] for u = temporal node k of Un: [0] the face fluxes (the cell's own
  /// side through own_flux, the neighbours' through Piece::nb_flux), [1..5]
  /// (constant_coefficients) primal_matrices[0..4] applied to u's coefficients.
  void nodal_products(const dealii::Vector<double> &Un) const;
  mutable std::vector<std::array<dealii::Vector<double>, 6>> node_terms;

  /// rho += the face terms at Gauss point m (time t, weight wt) from node_terms: half
  /// the flux jump (interior), the Neumann mismatch, -eps d_n u (Dirichlet).
  void add_face_terms(unsigned int m, double t, double wt, SlabFunctional &rho) const;

  /// rho and S += the temporal jump terms of u^+ - u^- at t0.
  void add_temporal_jump(double t0, double delta, const dealii::Vector<double> &Un,
                         const dealii::Vector<double> *Uprev, SlabFunctional &rho,
                         SlabFunctional &supg) const;

  const Space<dim> &primal;
  const Scene<dim> &scene;
  const dealii::FiniteElement<dim> &fe_p;
  const dealii::FE_Q<dim> &fe_w;
  const TemporalBasis &basis;
  dealii::QGauss<dim> quad;
  dealii::QGauss<dim - 1> fquad;
  dealii::FEValues<dim> fv_p, fv_w;
  const bool data_error; // DataQuadrature::error_term
  /// W on the primal's own cell rule QGauss(p+2) (load_quadrature_error)
  dealii::QGauss<dim> quad_primal;
  dealii::FEValues<dim> fv_lo;
  /// W on the rule for the data f and u_0 where they are integrated once per cell (a
  /// separable load, u_0 with coefficients constant in time): QGauss(deg W + 2) iterated
  /// load_copies times per direction
  dealii::QIterated<dim> quad_load;
  dealii::FEValues<dim> fv_load;
  dealii::FEFaceValues<dim> ff_p, ff_w;
  dealii::FESubfaceValues<dim> fs_p, fs_w;
  dealii::FEFaceValues<dim> fn_p;
  dealii::FESubfaceValues<dim> fns_p;
  std::vector<double> g, omega;
  std::vector<std::vector<double>> ell, dell;
  cell_iterator K;
  double delta_h = 0; // delta_K before the bound by tau_n
  typename Space<dim>::CellDiffusion cw; // the stabilization terms' D_K (Space::cell_diffusion)
  std::vector<dealii::types::global_dof_index> idx;
  std::vector<Piece> pieces;
  mutable std::array<dealii::Vector<double>, 3> scratch; // cell-local coefficient buffers
  mutable std::vector<double> boundary_scratch; // g at the temporal nodes, per face point
  mutable std::array<std::vector<dealii::Vector<double>>, 2> nodal_scratch;

  /// For coefficients constant in time, A(.)(z) and S'(., z) are cell matrices applied
  /// to z (per unit temporal weight): [0] A's val part, [1] A's dt/jump part, [2] S'
  /// val part, [3] S' dt/jump part, [4] the stabilization terms' (D_K grad ., grad z) (rows:
  /// the first slot, columns: z).
  const bool constant_coefficients;
  std::array<dealii::FullMatrix<double>, 5> adj_matrices;
  /// rho(u) and S(u) as cell matrices on u's coefficients, per unit temporal weight (S
  /// per unit delta_K), for coefficients constant in time: [0] rho from u (-(L u, w)),
  /// [1] rho from d_t u and from the jump u^+ - u^- (-(u, w)), [2] S from u
  /// ((L u, b.grad w)), [3] S from d_t u and the jump ((u, b.grad w)), [4] S's
  /// stabilization terms' part ((D_K grad u, grad w)); with a separable load,
  /// (g_j, w) and (g_j, b.grad w) per term j.
  std::array<dealii::FullMatrix<double>, 5> primal_matrices;
  std::vector<dealii::Vector<double>> load_rho, load_supg;
  /// the same on the primal's rule (load_quadrature_error; data_error only)
  std::vector<dealii::Vector<double>> lo_rho, lo_supg;
  /// the faces' terms from the cell's own side: -eps (d_n u, w), halved on interior faces
  dealii::FullMatrix<double> own_flux;
  /// rho and S += the cell terms at Gauss point m through node_terms
  /// (constant_coefficients) and the loads
  void add_cell_terms_by_matrices(unsigned int m, double t, double wt, double delta,
                                  double tau, SlabFunctional &rho,
                                  SlabFunctional &supg) const;
  /// add_temporal_jump through primal_matrices (constant_coefficients)
  void add_temporal_jump_by_matrices(double delta, const dealii::Vector<double> &Un,
                                     const dealii::Vector<double> *Uprev,
                                     SlabFunctional &rho, SlabFunctional &supg) const;
  /// Coefficients that depend on time: W's shape values, gradients (by component) and
  /// Laplacians at the cell's quadrature points, point-major (index q nw + l), for the
  /// point-by-point adjoint functional
  std::vector<double> w_value, w_laplacian;
  std::array<std::vector<double>, dim> w_gradient;
  /// eps, b and alpha at the cell's quadrature points, evaluated once per cell where
  /// they do not depend on t (constant_coefficients)
  std::vector<weak_form::Coefficients<dim>> coefficients_at_q;
  /// eps, b and alpha at quadrature point q and time t
  weak_form::Coefficients<dim> coefficients(unsigned int q, double t) const
  {
    return constant_coefficients
               ? coefficients_at_q[q]
               : weak_form::coefficients(scene, fv_p.quadrature_point(q), t);
  }

  /// f = sum_j a_j(t) g_j(x) where the scene gives it (Scene::separable_rhs; then the
  /// coefficients are constant in t): the terms' vectors load_rho, load_supg are formed
  /// once per cell on the data rule
  bool separable_load = false;
  std::vector<LoadTerm<dim>> load_terms;
  /// f at [Gauss point m][quadrature point q] as primal_functionals evaluated it
  mutable std::vector<std::vector<double>> f_at;
  mutable std::vector<double> times_scratch, f_scratch; // rhs_at_times' times and values
  /// a_j(t) by t: the same few temporal Gauss points recur on every cell
  mutable std::unordered_map<double, std::vector<double>> load_factors;
  const std::vector<double> &load_factors_at(double t) const;
  /// out(m, q) = f(x_q, t0 + g[m] tau) on the points of fv (Scene::rhs_at_times)
  template <typename Out>
  void rhs_at_points(double t0, double tau, const dealii::FEValues<dim> &fv,
                     const Out &out) const;
  void build_cell_matrices();
  /// A separable load's vectors (g_j, w_l) and (g_j, b.grad w_l) per term j on the rule of
  /// fv (W's shapes, the weights and points).
  void load_vectors_on(const dealii::FEValues<dim> &fv,
                       std::vector<dealii::Vector<double>> &rho,
                       std::vector<dealii::Vector<double>> &supg) const;
};

/// W-local coefficients of temporal node k of an interleaved slab vector.
void gather(const dealii::Vector<double> &U,
            const std::vector<dealii::types::global_dof_index> &dofs, unsigned int m1,
            unsigned int k, const dealii::FullMatrix<double> &to_w,
            dealii::Vector<double> &out);

/// f = the slab function sum_k l_k(s) V_k from W-local nodal vectors V_k (f.minus is
/// left as it is; f's vectors are reused).
template <int dim>
void slab_function(const CellKernel<dim> &kernel, const TemporalBasis &basis, double tau,
                   const std::vector<dealii::Vector<double>> &V, SlabFunction &f);

/// d = a (d's vectors are reused).
void assign(const SlabFunction &a, SlabFunction &d);

/// d = a - b (d's vectors are reused).
void difference(const SlabFunction &a, const SlabFunction &b, SlabFunction &d);

/// The degree of the weight element W = FE_Q(max(q, 2p)).
template <int dim>
unsigned int weight_degree(const Space<dim> &primal, const Space<dim> &other)
{
  return std::max(other.degree(), 2 * primal.degree());
}
} // namespace anisodwr
