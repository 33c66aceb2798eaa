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
/// One adjoint of the assembly: its slab vectors Z (interleaved), the goals it answers,
/// z(T^+) = M^{-1} j_T (empty without an end-time goal) and its hanging-node defects.
template <int dim> struct AssemblyAdjoint
{
  const std::vector<dealii::Vector<double>> &Z;
  const std::vector<GoalSpec> &goals;
  const dealii::Vector<double> &zT;
  const HangingDefect<dim> &hanging;
};

/// The indicators of estimate(), assembled cell by cell: the operators, the temporal
/// reconstruction and the goal parts, set up once, and the buffers reused over cells
/// and slabs (the per-slab work allocates nothing once sized). With several adjoints
/// (one estimate per goal) the work on u_h alone -- the cell's FEValues and matrices,
/// rho(u) and S(u), the lifts I_2h,i u - u, E u - u -- is done once for all of them;
/// each adjoint's terms are formed as if it were alone, so its indicators are the ones
/// a separate assembly gives, bit for bit.
template <int dim> class IndicatorAssembly
{
public:
  using cell_iterator = typename dealii::DoFHandler<dim>::active_cell_iterator;

  IndicatorAssembly(const Space<dim> &primal, const Space<dim> &adjoint,
                    const TimeMesh &mesh, const TemporalBasis &basis,
                    const std::vector<dealii::Vector<double>> &U,
                    const std::vector<AssemblyAdjoint<dim>> &adjoints,
                    TimeIndicator time_indicator, const HigherOrderPrimal *hi,
                    SpaceIndicator space_indicator, const dealii::Vector<double> &u0,
                    const DataQuadrature &data_rule);

  /// Adds the cell's eta_h,i and eta_tau (all slabs) to cells[a].eta_h_cell and
  /// cells[a].eta_tau_cell, and its contributions to the sums (per slab, per direction,
  /// the parts) to sums[a], for each adjoint a.
  void add_cell(const cell_iterator &cell, std::vector<Indicators<dim>> &cells,
                std::vector<Indicators<dim>> &sums);

private:
  /// the cell's constrained DoFs (local index, slot), grouped by the direction they
  /// are charged to (the mesh's: the same for every adjoint's HangingDefect)
  struct DefectGroup
  {
    unsigned int direction = 0;
    std::vector<std::pair<unsigned int, unsigned int>> slots;
  };
  /// An adjoint's part of the assembly: its data, its weights on the cell and slab and
  /// the functionals formed from them.
  struct Weights
  {
    Weights(const AssemblyAdjoint<dim> &in, const Space<dim> &primal,
            const dealii::FE_Q<dim> &fe_w, unsigned int n_nodes, unsigned int n_w);
    const std::vector<dealii::Vector<double>> &Z;
    const dealii::Vector<double> &zT;
    const HangingDefect<dim> &hanging;
    const LocalGoal<dim> goal_t, goal_T;
    /// per group of the cell the W-local defect at each temporal node (I_h z = R_h z
    /// minus the groups' defects)
    std::vector<std::vector<dealii::Vector<double>>> defects;
    /// W-local z at the temporal nodes of the slab; those of slab n+1 (gathered for
    /// z(t_n^+), reused by slab n+1); R_h or R_i applied to z_nodes; z(t_n^+)
    std::vector<dealii::Vector<double>> z_nodes, z_nodes_next, Rz_nodes;
    dealii::Vector<double> z_next;
    /// z and R_h z on the slab
    SlabFunction z, Rh_z;
    /// A'(.)(R_h z) and S'(.)(R_h z), A'(.)(z) (the adjoint residual's forms); J'(.)
    /// over I
    SlabFunctional adjoint_form_Rhz, supg_derivative_Rhz, adjoint_form_z, goal_derivative;
    /// the cell's goal vectors: the part over I and the part at T
    dealii::Vector<double> goal_vector_I, goal_vector_T;
    /// S(u)(R_h z) and D(R_h z) on the cell, summed over the slabs
    double supg_part = 0, quad_part = 0;
  };

  /// The slab's terms on u_h alone (shared by the adjoints); lift_size accumulates over
  /// the slabs.
  void add_primal_slab(unsigned int n, std::array<double, dim> &lift_size);
  /// The adjoint's terms of slab n for the cell (after add_primal_slab).
  void add_slab(Weights &a, unsigned int n, unsigned int c, Indicators<dim> &cells,
                Indicators<dim> &ind);
  /// W-local u at the temporal nodes of slab n and u(t_{n-1}^-).
  void gather_primal(unsigned int n);
  /// W-local z at the temporal nodes of slab n and z(t_n^+).
  void gather_adjoint(Weights &a, unsigned int n);
  /// I_2h,i u - u on slab n for each direction with a lift; adds its square norm over
  /// the slab to lift_size.
  void lift_errors(unsigned int n, double tau, std::array<double, dim> &lift_size);
  /// eta_h,i on slab n; adds the primal and adjoint halves to ind.eta_h_rho,
  /// ind.eta_h_rhostar; sets half_rho to the primal half 1/2 rho(u)(z - R_i z).
  double directional_indicator(Weights &a, unsigned int i, double tau, bool last,
                               double &half_rho, Indicators<dim> &ind);
  /// error = E f - f at the temporal Gauss points (values and derivatives) for f on
  /// the slab given by its nodal vectors, E by `combination` with the value outside the
  /// slab (z(t_n^+) for z, u(t_{n-1}^-) for u); `work` is scratch.
  void reconstruction_error(const std::vector<std::array<TimeCombination, 2>> &combination,
                            const dealii::Vector<double> &outside,
                            const std::vector<dealii::Vector<double>> &nodes,
                            const SlabFunction &f, double tau, dealii::Vector<double> &work,
                            SlabFunction &error) const;
  /// recon_error_u = u_r+1 - u (values and derivatives at the Gauss points, the jump at
  /// t_{n-1}); on the last slab hi_end = u_r+1(T) - u(T).
  void higher_order_errors(unsigned int n, double tau, bool last);

  const Space<dim> &primal, &adjoint;
  const TimeMesh &mesh;
  const TemporalBasis &basis;
  const std::vector<dealii::Vector<double>> &U;
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
  /// slabs, temporal nodes of dG(r) per slab, W's DoFs per cell
  const unsigned int N, n_nodes, n_w;
  /// the interpolant of u_0 (E_tau u at t_0), shared by the assemblies of all threads
  const dealii::Vector<double> &u0;
  /// E_tau at the temporal Gauss points (values [0] and derivatives [1]): the same
  /// combinations for every cell and slab
  std::vector<std::array<TimeCombination, 2>> recon_z, recon_u;
  /// the dG(r+1) basis at the temporal Gauss points (values, derivatives per unit s)
  const unsigned int n_nodes_hi;
  std::vector<std::vector<double>> hi_val, hi_der;
  std::vector<Weights> weights;

  /// out[k] = R z_nodes[k] for the cell restriction R (R_h or R_i), with z's values on
  /// the cell's Dirichlet faces taken as 0 where the adjoint does not vanish there
  /// (Space::has_natural_outflow): R_h z then lies in the primal's test space.
  void restrict_nodes(const Weights &a, const dealii::FullMatrix<double> &R,
                      std::vector<dealii::Vector<double>> &out);
  /// the cell's W DoFs on Dirichlet faces (only with a natural-outflow adjoint)
  std::vector<unsigned int> wall_w;
  dealii::Vector<double> z_wall;
  /// Rz_nodes = R_h z at the temporal nodes of slab n, the conforming I_h z on cells
  /// with hanging nodes (the groups' defects subtracted)
  void restrict_weights(Weights &a, unsigned int n);
  /// the W-local defects of the cell's groups on slab n (n_groups > 0)
  void gather_defects(Weights &a, unsigned int n);
  /// adds rho(u)(defect) of each group to the cell's eta_h in the group's direction
  /// (half of it in the average form) and to the sums; returns the sum of rho(u)(defect)
  double add_defect_indicators(Weights &a, double tau, unsigned int c,
                               Indicators<dim> &cells, Indicators<dim> &ind);

  std::vector<std::pair<unsigned int, unsigned int>> cell_slots;
  std::vector<DefectGroup> groups; // the first n_groups are the cell's
  unsigned int n_groups = 0;
  dealii::Vector<double> defect_p;
  SlabFunction defect;
  /// the dG(r+1) primal's W-local vectors at its temporal nodes (higher_order)
  std::vector<dealii::Vector<double>> u_hi_nodes;
  dealii::Vector<double> e_prev;
  std::vector<dealii::types::global_dof_index> idx_q;
  /// the slab's functionals of u_h on the cell: rho(u)(.), S(u)(.), the data's
  /// quadrature error D(.) and the Dirichlet data's share (per direction)
  SlabFunctional rho_u, supg_u, load_error;
  std::array<SlabFunctional, dim> data;
  bool has_data = false;
  /// W-local u at the temporal nodes of the slab; per direction I_2h,i u - u there
  std::vector<dealii::Vector<double>> u_nodes;
  std::array<std::vector<dealii::Vector<double>>, dim> lift_nodes;
  /// each direction's I_2h,i u - u at the last node of slab n (lift_error(t_n^-) of slab
  /// n+1)
  std::vector<dealii::Vector<double>> lift_error_last;
  /// u(t_{n-1}^-); u_r+1(T) - u(T) (higher_order, last slab); scratch vectors (work_T:
  /// a value at the slab's end)
  dealii::Vector<double> u_prev, hi_end, tmp, work_T, work_z, work_u;
  /// u on the slab; R_i z and z - R z (R_h or R_i); per direction I_2h,i u - u (the
  /// lift's error); E z - z and E u - u (the temporal reconstruction's errors)
  SlabFunction u, Ri_z, z_minus_Rz, recon_error_z, recon_error_u;
  std::array<SlabFunction, dim> lift_error;
  std::vector<LocalMap> lift;
};
} // namespace anisodwr
