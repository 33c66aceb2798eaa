#pragma once
// The cell-by-cell assembly of the DWR indicators that estimate() (adaptivity/estimator.h)
// runs over chunks of cells on several threads. Private to lib/adaptivity.
#include "adaptivity/cell_kernel.h"
#include "adaptivity/estimator.h"
#include "adaptivity/hanging_defect.h"
#include "adaptivity/spatial_operators.h"
#include "adaptivity/temporal_reconstruction.h"

#include <array>
#include <vector>

namespace anisodwr
{
/// The indicators of estimate(), assembled cell by cell: the operators, the temporal
/// reconstruction and the goal parts, set up once, and the buffers reused over cells
/// and slabs (the per-slab work allocates nothing once sized).
template <int dim> class IndicatorAssembly
{
public:
  using cell_iterator = typename dealii::DoFHandler<dim>::active_cell_iterator;

  IndicatorAssembly(const Space<dim> &primal, const Space<dim> &adjoint,
                    const TimeMesh &mesh, const TemporalBasis &basis,
                    const std::vector<dealii::Vector<double>> &U,
                    const std::vector<dealii::Vector<double>> &Z,
                    const std::vector<GoalSpec> &goals, TimeIndicator time_indicator,
                    const HigherOrderPrimal *hi, SpaceIndicator space_indicator,
                    const dealii::Vector<double> &zT, const dealii::Vector<double> &u0,
                    const DataQuadrature &data_rule,
                    const HangingDefect<dim> &hanging);

  /// Adds the cell's eta_h,i and eta_tau (all slabs) to cells.eta_h_cell and
  /// cells.eta_tau_cell, and its contributions to the sums (per slab, per direction,
  /// the parts) to `sums`.
  void add_cell(const cell_iterator &cell, Indicators<dim> &cells, Indicators<dim> &sums);

private:
  /// The slab's terms for the cell; supg_part, quad_part and lift_size accumulate over
  /// the slabs.
  void add_slab(unsigned int n, unsigned int c, Indicators<dim> &cells,
                Indicators<dim> &ind, double &supg_part, double &quad_part,
                std::array<double, dim> &lift_size);
  /// W-local z and u at the temporal nodes of slab n, z(t_n^+) and u(t_{n-1}^-).
  void gather_slab(unsigned int n);
  /// eta_h,i on slab n; adds ||I_2h,i u - u||^2 over the slab to lift_size and the
  /// primal and adjoint halves to ind.eta_h_rho, ind.eta_h_rhostar; sets half_rho to
  /// the primal half 1/2 rho(u)(z - R_i z).
  double directional_indicator(unsigned int i, unsigned int n, double tau, bool last,
                               double &lift_size, double &half_rho, Indicators<dim> &ind);
  /// recon_error_z = E z - z (outside value z(t_n^+)), recon_error_u = E u - u (outside
  /// value u(t_{n-1}^-)).
  void reconstruction_errors(double tau);
  /// recon_error_u = u_r+1 - u (values and derivatives at the Gauss points, the jump at
  /// t_{n-1}); returns J_T(u_r+1(T) - u(T)) on the last slab, else 0.
  double higher_order_errors(unsigned int n, double tau, bool last);

  const Space<dim> &primal, &adjoint;
  const TimeMesh &mesh;
  const TemporalBasis &basis;
  const std::vector<dealii::Vector<double>> &U, &Z;
  const TimeIndicator time_indicator;
  const HigherOrderPrimal *const hi;
  const SpaceIndicator space_indicator;
  const dealii::Triangulation<dim> &tria;
  const SpatialOperators<dim> ops;
  const dealii::FE_Q<dim> &fe_w;
  /// interpolation of the primal's and the adjoint's cell vectors into the weight
  /// space W (cell matrices)
  const dealii::FullMatrix<double> from_primal, from_adjoint;
  CellKernel<dim> kernel;
  const TemporalReconstruction recon;
  const LocalGoal<dim> goal_t, goal_T;
  /// slabs, temporal nodes of dG(r) per slab, W's DoFs per cell
  const unsigned int N, n_nodes, n_w;
  /// z(T^+) = M^{-1} j_T (empty without an end-time goal) and the interpolant of u_0
  /// (E_tau u at t_0), shared by the assemblies of all threads
  const dealii::Vector<double> &zT, &u0;
  /// E_tau at the temporal Gauss points (values [0] and derivatives [1]): the same
  /// combinations for every cell and slab
  std::vector<std::array<TimeCombination, 2>> recon_z, recon_u;
  /// the dG(r+1) basis at the temporal Gauss points (values, derivatives per unit s)
  const unsigned int n_nodes_hi;
  std::vector<std::vector<double>> hi_val, hi_der;

  /// Rz_nodes = R_h z at the temporal nodes of slab n, the conforming I_h z on cells
  /// with hanging nodes (the groups' defects subtracted)
  void restrict_weights(unsigned int n);
  /// the W-local defects of the cell's groups on slab n (n_groups > 0)
  void gather_defects(unsigned int n);
  /// adds rho(u)(defect) of each group to the cell's eta_h in the group's direction
  /// (half of it in the average form) and to the sums; returns the sum of rho(u)(defect)
  double add_defect_indicators(double tau, unsigned int c, Indicators<dim> &cells,
                               Indicators<dim> &ind);

  const HangingDefect<dim> &hanging;
  /// the cell's constrained DoFs (local index, slot), grouped by the direction they
  /// are charged to; per group the W-local defect at each temporal node (I_h z = R_h z
  /// minus the groups' defects)
  struct DefectGroup
  {
    unsigned int direction = 0;
    std::vector<std::pair<unsigned int, unsigned int>> slots;
    std::vector<dealii::Vector<double>> w;
  };
  std::vector<std::pair<unsigned int, unsigned int>> cell_slots;
  std::vector<DefectGroup> groups; // the first n_groups are the cell's
  unsigned int n_groups = 0;
  dealii::Vector<double> defect_p;
  SlabFunction defect;
  /// the dG(r+1) primal's W-local vectors at its temporal nodes (higher_order)
  std::vector<dealii::Vector<double>> u_hi_nodes;
  dealii::Vector<double> e_prev;
  std::vector<dealii::types::global_dof_index> idx_q;
  /// the slab's functionals on the cell: rho(u)(.) and S(u)(.) of u_h; A'(.)(R_h z) and
  /// S'(.)(R_h z), A'(.)(z) (the adjoint residual's forms); J'(.) over I
  SlabFunctional rho_u, supg_u, load_error, adjoint_form_Rhz, supg_derivative_Rhz,
      adjoint_form_z, goal_derivative;
  std::array<SlabFunctional, dim> data; // the Dirichlet data's share, per direction
  /// W-local z, u and I_2h,i u - u at the temporal nodes of the slab
  std::vector<dealii::Vector<double>> z_nodes, u_nodes, lift_nodes;
  /// z's nodal vectors of slab n+1 (gathered for z(t_n^+), reused by slab n+1) and
  /// each direction's I_2h,i u - u at the last node of slab n (lift_error(t_n^-) of slab
  /// n+1)
  std::vector<dealii::Vector<double>> z_nodes_next, lift_error_last;
  std::vector<dealii::Vector<double>> Rz_nodes; // R_h or R_i applied to z_nodes
  /// z(t_n^+), u(t_{n-1}^-); scratch vectors (work_T: a value at the slab's end)
  dealii::Vector<double> z_next, u_prev, tmp, work_T, work_z, work_u;
  /// z and u on the slab; R_h z, R_i z and z - R z (R_h or R_i); I_2h,i u - u (the
  /// lift's error); E z - z and E u - u (the temporal reconstruction's errors)
  SlabFunction z, u, Rh_z, Ri_z, z_minus_Rz, lift_error, recon_error_z, recon_error_u;
  std::vector<LocalMap> lift;
  /// the cell's goal vectors: the part over I and the part at T
  dealii::Vector<double> goal_vector_I, goal_vector_T;
};
} // namespace anisodwr
