#pragma once
// The space-time DWR indicators of doc/method.md §6 and §8, localized cell by cell
// and slab by slab:
//
//   eta_tau   = 1/2 rho(u)(E z - z) + 1/2 rho*(u,z)(E u - u)
//   eta_h,i   = 1/2 rho(u)(z - R_i z) + 1/2 rho*(u, R_h z)(I_2h,i u - u)
//             + omega_i^K (S(u)(R_h z) + D(R_h z)) + 1/2 S'(u)(I_2h,i u - u, R_h z)
//
// D: the primal's quadrature error in its data f and u_0 (DataQuadrature below).
//
// The SUPG consistency term departs from the seed paper's 1/2 S(u)(R_i z): with
// z_h = R_h z in the primal space both J(e) = rho(u)(z - z_h) + S(u)(z_h) and
// J(e) = rho*(z_h)(u - u_h) + S(u)(z_h) are exact, so their average carries the whole
// S(u)(R_h z); and S(u)(R_i z) is nearly the same for every i (R_i z does not measure
// direction i), so the cell total is split over the directions by
// omega_i^K = ||I_2h,i u - u||_K^2 / sum_j ||I_2h,j u - u||_K^2 (1/d if all vanish).
// Measured (boundary_layer, eps = 1e-3, cG(1)-dG(1)): I_eff 1.25-1.42 with the seed
// term, 1.0-1.15 with this one; anisotropic refinement needs the directional split.
//
// rho(u)(w): the unstabilized primal residual, localized by integration by parts on
//   each cell (strong cell residual, half of the flux jump eps [d_n u] on interior
//   faces, the Neumann mismatch and -eps d_n u on Dirichlet faces, the temporal jump
//   -([u]_{n-1}, w^+)).
// rho*(u,z)(v) = J'(v) - A(v)(z): the adjoint residual, localized cell by cell in its
//   weak form (cell integrals; exact, no face terms needed).
// S, S': the SUPG form (with the time derivative and the jump, as in the discrete
//   scheme) and its derivative, cell by cell.
// Temporal integrals use r+2 Gauss points per slab (as the slab load does).
//
// This module reads solutions and meshes and solves no system itself: the end-time
// value of the adjoint, z(T^+) = M^{-1} j_T, comes from end_time_representer
// (slab/adjoint_march.h). The cell integrals are in cell_kernel.h; the localized forms
// for the tests in localized_forms.cc.
#include "adaptivity/adaptivity_keys.h"
#include "goal/goal.h"
#include "space/space.h"
#include "time/temporal_basis.h"
#include "time/time_mesh.h"

#include <array>
#include <vector>

namespace anisodwr
{
template <int dim> struct Indicators
{
  /// per active cell (active_cell_index), summed over slabs
  std::vector<std::array<double, dim>> eta_h_cell;
  std::vector<double> eta_tau_cell;
  /// per slab, summed over cells
  std::vector<double> eta_tau_slab;
  std::array<double, dim> eta_h{};
  double eta_tau = 0;
  /// the two halves of eta_tau: 1/2 rho(u)(E z - z) and 1/2 rho*(u,z)(E u - u) (each
  /// alone is a first-order approximation of the temporal error; they differ where
  /// the adjoint or the primal is poorly resolved in time)
  double eta_tau_rho = 0, eta_tau_rhostar = 0;
  /// the parts of eta_h (summed over directions): 1/2 rho(u)(z - R_i z), the adjoint
  /// half 1/2 rho*(u, R_h z)(I_2h,i u - u) + 1/2 S'(..) (cells with a lift only) and the
  /// SUPG consistency term S(u)(R_h z)
  double eta_h_rho = 0, eta_h_rhostar = 0, eta_h_supg = 0;
  /// what the directional split adds to the primal residual's weight:
  /// sum_i rho(u)(z - R_i z) - rho(u)(z - R_h z) (= rho(u)((I - R_1)(I - R_2) z) in 2D),
  /// the mixed-direction remainder that doc/method.md §6 does not keep
  double eta_h_split_rest = 0;
  /// the Dirichlet data's share of eta_h, -int_I int_{Gamma_D} eps (g_tau - u) d_n z
  /// (included in eta_h; zero where u_h takes g_tau, g at the temporal nodes, exactly)
  double eta_h_data = 0;
  /// the primal's quadrature error in f and u_0: (f, R_h z + delta b.grad R_h z) and
  /// (u_0, ...) on the estimator's data rule minus the same on the primal's
  /// QGauss(p+2), the term rho(u)(R_h z) - S(u)(R_h z) of the error identity that the
  /// primal's own rule sets to zero (included in eta_h; 0 with
  /// DataQuadrature::error_term false)
  double eta_h_quad = 0;
  /// (cell, direction) pairs without a directional lift (no adjoint half there)
  unsigned int no_lift = 0;
  double eta_h_total() const
  {
    double s = 0;
    for (double e : eta_h)
      s += e;
    return s;
  }
};

/// sum += w x, field by field; an empty sum takes x's sizes. The indicators are linear
/// in the adjoint and the goals, so the estimate of sum_i w_i J_i is sum_i w_i times the
/// estimate of J_i alone (with its own adjoint). no_lift (a mesh property) is x's.
template <int dim>
void add_scaled(Indicators<dim> &sum, double w, const Indicators<dim> &x)
{
  if (sum.eta_h_cell.empty())
  {
    sum.eta_h_cell.assign(x.eta_h_cell.size(), std::array<double, dim>{});
    sum.eta_tau_cell.assign(x.eta_tau_cell.size(), 0.);
    sum.eta_tau_slab.assign(x.eta_tau_slab.size(), 0.);
  }
  for (std::size_t c = 0; c < x.eta_h_cell.size(); ++c)
  {
    for (int d = 0; d < dim; ++d)
      sum.eta_h_cell[c][d] += w * x.eta_h_cell[c][d];
    sum.eta_tau_cell[c] += w * x.eta_tau_cell[c];
  }
  for (std::size_t n = 0; n < x.eta_tau_slab.size(); ++n)
    sum.eta_tau_slab[n] += w * x.eta_tau_slab[n];
  for (int d = 0; d < dim; ++d)
    sum.eta_h[d] += w * x.eta_h[d];
  sum.eta_tau += w * x.eta_tau;
  sum.eta_tau_rho += w * x.eta_tau_rho;
  sum.eta_tau_rhostar += w * x.eta_tau_rhostar;
  sum.eta_h_rho += w * x.eta_h_rho;
  sum.eta_h_rhostar += w * x.eta_h_rhostar;
  sum.eta_h_supg += w * x.eta_h_supg;
  sum.eta_h_split_rest += w * x.eta_h_split_rest;
  sum.eta_h_data += w * x.eta_h_data;
  sum.eta_h_quad += w * x.eta_h_quad;
  sum.no_lift = x.no_lift;
}

/// How the estimator integrates the data f and u_0 (adaptivity.data_rule_copies and
/// adaptivity.data_quadrature_error, doc/method.md §6).
struct DataQuadrature
{
  /// f (where it is separable in x and t) and u_0 (coefficients constant in time) on
  /// QGauss(deg W + 2) iterated this many times per direction, once per cell
  unsigned int copies = 2;
  /// add the primal's quadrature error in f and u_0, weighted by R_h z, to eta_h
  bool error_term = true;
};

/// The primal solved once more in dG(r+1) (basis.degree() = r+1) on the same slabs and
/// spatial space (TimeIndicator::higher_order).
struct HigherOrderPrimal
{
  const TemporalBasis &basis;
  const std::vector<dealii::Vector<double>> &U;
};

/// Primal u (FE_Q(p), `primal`) and adjoint z (FE_Q(q), `adjoint`) on the same mesh;
/// U, Z interleaved per slab. Weight element W = FE_Q(max(q, 2p)). conforming_weights:
/// at hanging nodes the weights use the conforming interpolant I_h z (doc/method.md §7,
/// adaptivity/hanging_defect.h); false: the cell-wise R_h z.
template <int dim>
Indicators<dim>
estimate(const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
         const TemporalBasis &basis, const std::vector<dealii::Vector<double>> &U,
         const std::vector<dealii::Vector<double>> &Z, const std::vector<GoalSpec> &goals,
         TimeIndicator time_indicator = TimeIndicator::average,
         const HigherOrderPrimal *higher_order = nullptr,
         SpaceIndicator space_indicator = SpaceIndicator::average,
         const DataQuadrature &data = {}, bool conforming_weights = true);

/// One adjoint of estimate_each(): its slab vectors (interleaved) and the goal(s) it
/// answers.
struct AdjointOf
{
  const std::vector<dealii::Vector<double>> *Z;
  std::vector<GoalSpec> goals;
};

/// estimate() for several adjoints on one primal at once (one estimate per goal): the
/// work on u_h alone is shared, each adjoint's indicators are estimate()'s for it alone,
/// bit for bit.
template <int dim>
std::vector<Indicators<dim>>
estimate_each(const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
              const TemporalBasis &basis, const std::vector<dealii::Vector<double>> &U,
              const std::vector<AdjointOf> &adjoints,
              TimeIndicator time_indicator = TimeIndicator::average,
              const HigherOrderPrimal *higher_order = nullptr,
              SpaceIndicator space_indicator = SpaceIndicator::average,
              const DataQuadrature &data = {}, bool conforming_weights = true);

/// The localized forms summed over all cells, one value per slab, for given global
/// functions (for the localization tests). u in `primal`'s space; the weights w, y, v
/// and the adjoint-slot function zt in `other`'s space (same mesh, degree <= W's).
template <int dim> struct LocalizedForms
{
  static std::vector<double>
  primal_residual(const Space<dim> &primal, const Space<dim> &other, const TimeMesh &mesh,
                  const TemporalBasis &basis,
                  const std::vector<dealii::Vector<double>> &U,
                  const std::vector<dealii::Vector<double>> &W);
  static std::vector<double> supg(const Space<dim> &primal, const Space<dim> &other,
                                  const TimeMesh &mesh, const TemporalBasis &basis,
                                  const std::vector<dealii::Vector<double>> &U,
                                  const std::vector<dealii::Vector<double>> &Y);
  /// A(v)(zt) (without J') and S'(v, zt) for v in `other`'s space, zt in `other`'s space.
  static std::vector<double>
  adjoint_form(const Space<dim> &primal, const Space<dim> &other, const TimeMesh &mesh,
               const TemporalBasis &basis, const std::vector<dealii::Vector<double>> &V,
               const std::vector<dealii::Vector<double>> &Zt, bool supg_derivative);
};
} // namespace anisodwr
