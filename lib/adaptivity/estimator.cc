#include "adaptivity/estimator.h"

#include "adaptivity/cell_kernel.h"
#include "adaptivity/short_vectors.h"
#include "adaptivity/spatial_operators.h"
#include "adaptivity/temporal_reconstruction.h"
#include "base/mpi.h"
#include "slab/adjoint_march.h"

#include <deal.II/base/function.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

namespace anisodwr
{
using namespace dealii;
namespace sv = short_vectors;

namespace
{
/// The indicators of estimate(), assembled cell by cell: the operators, the temporal
/// reconstruction and the goal parts, set up once, and the buffers reused over cells
/// and slabs (the per-slab work allocates nothing once sized).
template <int dim> class IndicatorAssembly
{
public:
  using cell_iterator = typename DoFHandler<dim>::active_cell_iterator;

  IndicatorAssembly(const Space<dim> &primal, const Space<dim> &adjoint,
                    const TimeMesh &mesh, const TemporalBasis &basis,
                    const std::vector<Vector<double>> &U,
                    const std::vector<Vector<double>> &Z,
                    const std::vector<GoalSpec> &goals, TimeIndicator time_indicator,
                    const HigherOrderPrimal *hi, SpaceIndicator space_indicator,
                    const Vector<double> &zT, const Vector<double> &u0);

  /// Adds the cell's eta_h,i and eta_tau (all slabs) to cells.eta_h_cell and
  /// cells.eta_tau_cell, and its contributions to the sums (per slab, per direction,
  /// the parts) to `sums`.
  void add_cell(const cell_iterator &cell, Indicators<dim> &cells, Indicators<dim> &sums);

private:
  /// The slab's terms for the cell; supg_part and lift_size accumulate over the slabs.
  void add_slab(unsigned int n, unsigned int c, Indicators<dim> &cells,
                Indicators<dim> &ind, double &supg_part,
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
  const std::vector<Vector<double>> &U, &Z;
  const TimeIndicator time_indicator;
  const HigherOrderPrimal *const hi;
  const SpaceIndicator space_indicator;
  const Triangulation<dim> &tria;
  const SpatialOperators<dim> ops;
  const FE_Q<dim> &fe_w;
  /// interpolation of the primal's and the adjoint's cell vectors into the weight
  /// space W (cell matrices)
  const FullMatrix<double> from_primal, from_adjoint;
  CellKernel<dim> kernel;
  const TemporalReconstruction recon;
  const LocalGoal<dim> goal_t, goal_T;
  /// slabs, temporal nodes of dG(r) per slab, W's DoFs per cell
  const unsigned int N, n_nodes, n_w;
  /// z(T^+) = M^{-1} j_T (empty without an end-time goal) and the interpolant of u_0
  /// (E_tau u at t_0), shared by the assemblies of all threads
  const Vector<double> &zT, &u0;
  /// E_tau at the temporal Gauss points (values [0] and derivatives [1]): the same
  /// combinations for every cell and slab
  std::vector<std::array<TimeCombination, 2>> recon_z, recon_u;
  /// the dG(r+1) basis at the temporal Gauss points (values, derivatives per unit s)
  const unsigned int n_nodes_hi;
  std::vector<std::vector<double>> hi_val, hi_der;

  /// the dG(r+1) primal's W-local vectors at its temporal nodes (higher_order)
  std::vector<Vector<double>> u_hi_nodes;
  Vector<double> e_prev;
  std::vector<types::global_dof_index> idx_q;
  /// the slab's functionals on the cell: rho(u)(.) and S(u)(.) of u_h; A'(.)(R_h z) and
  /// S'(.)(R_h z), A'(.)(z) (the adjoint residual's forms); J'(.) over I
  SlabFunctional rho_u, supg_u, adjoint_form_Rhz, supg_derivative_Rhz, adjoint_form_z,
      goal_derivative;
  std::array<SlabFunctional, dim> data; // the Dirichlet data's share, per direction
  /// W-local z, u and I_2h,i u - u at the temporal nodes of the slab
  std::vector<Vector<double>> z_nodes, u_nodes, lift_nodes;
  /// z's nodal vectors of slab n+1 (gathered for z(t_n^+), reused by slab n+1) and
  /// each direction's I_2h,i u - u at the last node of slab n (lift_error(t_n^-) of slab
  /// n+1)
  std::vector<Vector<double>> z_nodes_next, lift_error_last;
  std::vector<Vector<double>> Rz_nodes; // R_h or R_i applied to z_nodes
  /// z(t_n^+), u(t_{n-1}^-); scratch vectors (work_T: a value at the slab's end)
  Vector<double> z_next, u_prev, tmp, work_T, work_z, work_u;
  /// z and u on the slab; R_h z, R_i z and z - R z (R_h or R_i); I_2h,i u - u (the
  /// lift's error); E z - z and E u - u (the temporal reconstruction's errors)
  SlabFunction z, u, Rh_z, Ri_z, z_minus_Rz, lift_error, recon_error_z, recon_error_u;
  std::vector<LocalMap> lift;
  /// the cell's goal vectors: the part over I and the part at T
  Vector<double> goal_vector_I, goal_vector_T;
};

template <int dim>
IndicatorAssembly<dim>::IndicatorAssembly(
    const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
    const TemporalBasis &basis, const std::vector<Vector<double>> &U,
    const std::vector<Vector<double>> &Z, const std::vector<GoalSpec> &goals,
    TimeIndicator time_indicator, const HigherOrderPrimal *hi,
    SpaceIndicator space_indicator, const Vector<double> &zT, const Vector<double> &u0)
    : primal(primal), adjoint(adjoint), mesh(mesh), basis(basis), U(U), Z(Z),
      time_indicator(time_indicator), hi(hi), space_indicator(space_indicator),
      tria(primal.dof_handler().get_triangulation()),
      ops(primal.dof_handler(), weight_degree(primal, adjoint)),
      fe_w(ops.weight_element()),
      from_primal(ops.interpolation_from(primal.finite_element())),
      from_adjoint(ops.interpolation_from(adjoint.finite_element())),
      kernel(primal, fe_w, basis), recon(basis),
      goal_t(primal.scene, primal.mapping(), fe_w, tria, goals, true),
      goal_T(primal.scene, primal.mapping(), fe_w, tria, goals, false), N(mesh.n_slabs()),
      n_nodes(basis.n_dofs()), n_w(fe_w.n_dofs_per_cell()), zT(zT), u0(u0),
      recon_z(kernel.n_points()), recon_u(kernel.n_points()),
      n_nodes_hi(hi ? hi->basis.n_dofs() : 0), u_hi_nodes(n_nodes_hi), e_prev(n_w),
      idx_q(adjoint.finite_element().n_dofs_per_cell()), z_nodes(n_nodes),
      u_nodes(n_nodes), lift_nodes(n_nodes), z_nodes_next(n_nodes), lift_error_last(dim),
      Rz_nodes(n_nodes), z_next(n_w), u_prev(n_w), tmp(n_w), work_T(n_w), work_z(n_w),
      work_u(n_w), lift(dim)
{
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
    for (unsigned int d = 0; d < 2; ++d)
    {
      recon_z[m][d] = recon.adjoint(kernel.point(m), d == 1);
      recon_u[m][d] = recon.primal(kernel.point(m), d == 1);
    }
  if (hi)
    for (unsigned int m = 0; m < kernel.n_points(); ++m)
    {
      hi_val.push_back(hi->basis.values(kernel.point(m)));
      std::vector<double> d(n_nodes_hi);
      for (unsigned int k = 0; k < n_nodes_hi; ++k)
        d[k] = hi->basis.derivative(k, kernel.point(m));
      hi_der.push_back(d);
    }
}

template <int dim>
void IndicatorAssembly<dim>::add_cell(const cell_iterator &cell, Indicators<dim> &cells,
                                      Indicators<dim> &ind)
{
  kernel.reinit(cell);
  typename DoFHandler<dim>::active_cell_iterator cq(&tria, cell->level(), cell->index(),
                                                    &adjoint.dof_handler());
  cq->get_dof_indices(idx_q);
  for (unsigned int i = 0; i < dim; ++i)
    lift[i] = ops.directional_lift(cell, i);
  if (!goal_t.empty())
    goal_t.cell_vector(cell, goal_vector_I);
  if (!goal_T.empty())
    goal_T.cell_vector(cell, goal_vector_T);
  const auto c = cell->active_cell_index();
  double supg_part = 0;                // S(u)(R_h z) on this cell
  std::array<double, dim> lift_size{}; // ||I_2h,i u - u||^2 over the slabs

  for (unsigned int n = 0; n < N; ++n)
    add_slab(n, c, cells, ind, supg_part, lift_size);
  // The SUPG consistency term is not directional (the seed formula's 1/2 S(u)(R_i z)
  // is nearly the same for every i: R_i z does not measure direction i). Its cell
  // total S(u)(R_h z) is split over the directions in proportion to the size of the
  // directional primal error ||I_2h,i u - u||^2 (summed over the slabs).
  ind.eta_h_supg += supg_part;
  for (unsigned int i = 0; i < dim; ++i)
    ind.no_lift += lift[i].exists ? 0 : 1;
  double total = 0;
  for (double l : lift_size)
    total += l;
  for (unsigned int i = 0; i < dim; ++i)
  {
    const double share = (total > 0 ? lift_size[i] / total : 1. / dim) * supg_part;
    cells.eta_h_cell[c][i] += share;
    ind.eta_h[i] += share;
  }
}

template <int dim>
void IndicatorAssembly<dim>::add_slab(unsigned int n, unsigned int c,
                                      Indicators<dim> &cells, Indicators<dim> &ind,
                                      double &supg_part,
                                      std::array<double, dim> &lift_size)
{
  const double t0 = mesh.start(n), tau = mesh.tau(n);
  kernel.primal_functionals(t0, tau, U[n], n ? &U[n - 1] : nullptr, rho_u, supg_u);
  gather_slab(n);

  slab_function(kernel, basis, tau, z_nodes, z);
  // R_h z, from R_h applied to z's nodal vectors (R_h acts in space only)
  for (unsigned int k = 0; k < n_nodes; ++k)
    sv::vmult(Rz_nodes[k], ops.restriction(dim), z_nodes[k]);
  slab_function(kernel, basis, tau, Rz_nodes, Rh_z);
  kernel.adjoint_functional(t0, tau, Rz_nodes, Rh_z, false, adjoint_form_Rhz);
  kernel.adjoint_functional(t0, tau, Rz_nodes, Rh_z, true, supg_derivative_Rhz);
  kernel.adjoint_functional(t0, tau, z_nodes, z, false, adjoint_form_z);
  kernel.goal_functional(tau, goal_vector_I, goal_derivative);
  const bool last = n + 1 == N;
  slab_function(kernel, basis, tau, u_nodes, u);
  // S(u)(R_h z): with z_h = R_h z in the primal space, J(e) = rho(u)(z - z_h) +
  // S(u)(z_h) and J(e) = rho*(z_h)(u - u_h) + S(u)(z_h) hold exactly, so the
  // average of the two carries the full SUPG consistency term.
  supg_part += apply(supg_u, Rh_z, false);

  double split = 0; // sum_i rho(u)(z - R_i z)
  for (unsigned int i = 0; i < dim; ++i)
  {
    double half_rho;
    const double eta =
        directional_indicator(i, n, tau, last, lift_size[i], half_rho, ind);
    cells.eta_h_cell[c][i] += eta;
    ind.eta_h[i] += eta;
    split += 2 * half_rho;
  }
  difference(z, Rh_z, z_minus_Rz);
  ind.eta_h_split_rest += split - apply(rho_u, z_minus_Rz, false);
  // the Dirichlet data's share, weighted by z itself (u_h interpolates g on Gamma_D)
  if (kernel.dirichlet_data_functionals(t0, tau, U[n], data))
    for (unsigned int i = 0; i < dim; ++i)
    {
      const double eta = apply(data[i], z, false);
      cells.eta_h_cell[c][i] += eta;
      ind.eta_h[i] += eta;
      ind.eta_h_data += eta;
    }

  reconstruction_errors(tau);
  // J_T(E u - u) at T: 0 for the Radau reconstruction (E u - u vanishes at t_n)
  const double end_part = hi ? higher_order_errors(n, tau, last) : 0.;
  const double jv = apply(goal_derivative, recon_error_u, false) +
                    end_part; // J'(E u - u) over I and at T
  const double half_rho = 0.5 * apply(rho_u, recon_error_z, false),
               half_rhostar = 0.5 * (jv - apply(adjoint_form_z, recon_error_u, true));
  const double eta_tau = time_indicator == TimeIndicator::average
                             ? half_rho + half_rhostar
                             : 2 * half_rhostar;
  ind.eta_tau_rho += half_rho;
  ind.eta_tau_rhostar += half_rhostar;
  cells.eta_tau_cell[c] += eta_tau;
  ind.eta_tau_slab[n] += eta_tau;
  ind.eta_tau += eta_tau;
}

template <int dim> void IndicatorAssembly<dim>::gather_slab(unsigned int n)
{
  // The slabs run in order on a cell: slab n-1 gathered Z[n] (for z(t_{n-1}^+)) and
  // U[n-1]'s last node (its own u), so each slab vector is gathered once per cell.
  const auto &idx = kernel.dof_indices();
  if (n > 0)
  {
    sv::copy(u_prev, u_nodes[n_nodes - 1]);
    z_nodes.swap(z_nodes_next);
  }
  else
  {
    gather(u0, idx, 1, 0, from_primal, u_prev);
    for (unsigned int k = 0; k < n_nodes; ++k)
      gather(Z[n], idx_q, n_nodes, k, from_adjoint, z_nodes[k]);
  }
  for (unsigned int k = 0; k < n_nodes; ++k)
    gather(U[n], idx, n_nodes, k, from_primal, u_nodes[k]);
  sv::zero(z_next);
  if (n + 1 < N)
    for (unsigned int k = 0; k < n_nodes; ++k)
    {
      gather(Z[n + 1], idx_q, n_nodes, k, from_adjoint, z_nodes_next[k]);
      sv::add(z_next, basis.left_trace()[k], z_nodes_next[k]);
    }
  else if (zT.size())
    gather(zT, idx_q, 1, 0, from_adjoint, z_next);
}

template <int dim>
double IndicatorAssembly<dim>::directional_indicator(unsigned int i, unsigned int n,
                                                     double tau, bool last,
                                                     double &lift_size, double &half_rho,
                                                     Indicators<dim> &ind)
{
  for (unsigned int k = 0; k < n_nodes; ++k)
    sv::vmult(Rz_nodes[k], ops.restriction(i), z_nodes[k]);
  slab_function(kernel, basis, tau, Rz_nodes, Ri_z);
  difference(z, Ri_z, z_minus_Rz);
  half_rho = 0.5 * apply(rho_u, z_minus_Rz, false);
  ind.eta_h_rho += half_rho;
  if (space_indicator == SpaceIndicator::primal_residual)
    return 2 * half_rho;
  if (!lift[i].exists)
    return half_rho;
  for (unsigned int k = 0; k < n_nodes; ++k)
  {
    lift[i].apply(U[n], lift_nodes[k], n_nodes, k);
    sv::subtract(lift_nodes[k], u_nodes[k]);
  }
  slab_function(kernel, basis, tau, lift_nodes, lift_error);
  for (const auto &vv : lift_error.val)
    lift_size += tau * sv::norm_sqr(vv);
  if (n > 0)
    sv::copy(lift_error.minus, lift_error_last[i]); // I_2h,i u - u at U[n-1]'s last node
  else
    lift_error.minus.reinit(0);
  sv::copy(lift_error_last[i], lift_nodes[n_nodes - 1]);
  double jv = apply(goal_derivative, lift_error, false); // J' over I
  if (last && goal_vector_T.size())
  {
    sv::zero(work_T);
    for (unsigned int k = 0; k < n_nodes; ++k)
      sv::add(work_T, basis.right_trace()[k], lift_nodes[k]);
    jv += sv::dot(goal_vector_T, work_T);
  }
  const double half_rhostar = 0.5 * (jv - apply(adjoint_form_Rhz, lift_error, true)) +
                              0.5 * apply(supg_derivative_Rhz, lift_error, true);
  ind.eta_h_rhostar += half_rhostar;
  return half_rho + half_rhostar;
}

template <int dim> void IndicatorAssembly<dim>::reconstruction_errors(double tau)
{
  recon_error_z.val.resize(kernel.n_points());
  recon_error_z.dt.resize(kernel.n_points());
  recon_error_u.val.resize(kernel.n_points());
  recon_error_u.dt.resize(kernel.n_points());
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
  {
    for (bool deriv : {false, true})
    {
      const TimeCombination &a = recon_z[m][deriv], &b = recon_u[m][deriv];
      sv::zero(work_z);
      sv::zero(work_u);
      sv::add(work_z, a.outside, z_next);
      sv::add(work_u, b.outside, u_prev);
      for (unsigned int k = 0; k < n_nodes; ++k)
      {
        sv::add(work_z, a.slab[k], z_nodes[k]);
        sv::add(work_u, b.slab[k], u_nodes[k]);
      }
      if (deriv)
      {
        // (deal.II's operator/= multiplies by the reciprocal)
        sv::scale(work_z, 1. / tau);
        sv::scale(work_u, 1. / tau);
        sv::subtract(work_z, z.dt[m]);
        sv::subtract(work_u, u.dt[m]);
        sv::copy(recon_error_z.dt[m], work_z);
        sv::copy(recon_error_u.dt[m], work_u);
      }
      else
      {
        sv::subtract(work_z, z.val[m]);
        sv::subtract(work_u, u.val[m]);
        sv::copy(recon_error_z.val[m], work_z);
        sv::copy(recon_error_u.val[m], work_u);
      }
    }
  }
  sv::zero(recon_error_z.plus, n_w);    // E z(t_{n-1}) = z(t_{n-1}^+)
  sv::copy(recon_error_u.plus, u_prev); // E u(t_{n-1}) - u(t_{n-1}^+)
  sv::subtract(recon_error_u.plus, u.plus);
}

template <int dim>
double IndicatorAssembly<dim>::higher_order_errors(unsigned int n, double tau, bool last)
{
  // E u := u_r+1: values and derivatives at the Gauss points, the jump of
  // e = u_r+1 - u at t_{n-1} (e(t_0^-) = 0: both start from u_0), and J_T(e(T))
  const auto &idx = kernel.dof_indices();
  if (n > 0) // u_r+1(t_{n-1}^-) from slab n-1's nodal vectors, still in u_hi_nodes
  {
    e_prev = 0.;
    for (unsigned int k = 0; k < n_nodes_hi; ++k)
      e_prev.add(hi->basis.right_trace()[k], u_hi_nodes[k]);
  }
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    gather(hi->U[n], idx, n_nodes_hi, k, from_primal, u_hi_nodes[k]);
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
  {
    sv::zero(work_u);
    sv::zero(tmp);
    for (unsigned int k = 0; k < n_nodes_hi; ++k)
    {
      sv::add(work_u, hi_val[m][k], u_hi_nodes[k]);
      sv::add(tmp, hi_der[m][k] / tau, u_hi_nodes[k]);
    }
    sv::subtract(work_u, u.val[m]);
    sv::subtract(tmp, u.dt[m]);
    sv::copy(recon_error_u.val[m], work_u);
    sv::copy(recon_error_u.dt[m], tmp);
  }
  recon_error_u.plus = 0.;
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    recon_error_u.plus.add(hi->basis.left_trace()[k], u_hi_nodes[k]);
  recon_error_u.plus -= u.plus;
  if (n > 0)
  {
    e_prev -= u_prev; // u(t_{n-1}^-)
    recon_error_u.plus -= e_prev;
  }
  if (!(last && goal_vector_T.size()))
    return 0.;
  work_T = 0.;
  for (unsigned int k = 0; k < n_nodes_hi; ++k)
    work_T.add(hi->basis.right_trace()[k], u_hi_nodes[k]);
  for (unsigned int k = 0; k < n_nodes; ++k)
    work_T.add(-basis.right_trace()[k], u_nodes[k]);
  return goal_vector_T * work_T;
}
} // namespace

namespace
{
/// The sums over the MPI ranks of the per-chunk sums and of the cells' own indicators
/// (each computed on one rank, zero on the others: the sums are exact).
template <int dim>
void allreduce_chunks(std::vector<Indicators<dim>> &sums, Indicators<dim> &ind)
{
  std::vector<double> buffer;
  const auto pack = [&](auto &&visit)
  {
    for (auto &c : ind.eta_h_cell)
      for (auto &e : c)
        visit(e);
    for (auto &e : ind.eta_tau_cell)
      visit(e);
    for (auto &s : sums)
    {
      for (auto &e : s.eta_tau_slab)
        visit(e);
      for (auto &e : s.eta_h)
        visit(e);
      for (double *e :
           {&s.eta_tau, &s.eta_tau_rho, &s.eta_tau_rhostar, &s.eta_h_rho,
            &s.eta_h_rhostar, &s.eta_h_supg, &s.eta_h_split_rest, &s.eta_h_data})
        visit(*e);
      double no_lift = s.no_lift;
      visit(no_lift);
      s.no_lift = static_cast<unsigned int>(no_lift + 0.5);
    }
  };
  pack([&](double &e) { buffer.push_back(e); });
  allreduce_sum(buffer);
  std::size_t i = 0;
  pack([&](double &e) { e = buffer[i++]; });
}

/// Runs assembly.add_cell over all cells on MultithreadInfo::n_threads() threads and
/// returns the per-chunk sums in chunk order (the cell's own indicators go to `ind`).
template <int dim, class MakeAssembly>
std::vector<Indicators<dim>>
add_cells_in_chunks(const DoFHandler<dim> &dofs, unsigned int n_slabs,
                    const MakeAssembly &make_assembly, Indicators<dim> &ind)
{
  // The cells are cut into chunks that depend only on their number; each chunk sums
  // its own contributions and the chunks are added in order, so the totals depend on
  // the number of threads only through round-off in the cell terms (deal.II's FEValues
  // reuses data between similar consecutive cells). Each thread has its own assembly
  // (buffers, FEValues); a cell's own indicators are written by the one thread that
  // owns it. Threads: MultithreadInfo::n_threads() (all cores; DEAL_II_NUM_THREADS).
  std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
  for (const auto &cell : dofs.active_cell_iterators())
    cells.push_back(cell);
  const std::size_t chunk = std::max<std::size_t>(64, (cells.size() + 255) / 256),
                    n_chunks = (cells.size() + chunk - 1) / chunk;
  std::vector<Indicators<dim>> sums(n_chunks);
  for (auto &s : sums)
    s.eta_tau_slab.assign(n_slabs, 0.);
  // Under MPI each rank takes every ranks-th chunk; the others stay zero, and the sum
  // over the ranks (allreduce_chunks) restores every chunk and cell exactly.
  const std::size_t ranks = mpi_ranks(), rank = mpi_rank(),
                    n_mine = n_chunks > rank ? (n_chunks - rank + ranks - 1) / ranks : 0;
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&]()
  {
    try
    {
      auto assembly = make_assembly();
      for (std::size_t j = next++; j < n_mine; j = next++)
      {
        const std::size_t k = rank + j * ranks;
        for (std::size_t c = k * chunk; c < std::min(cells.size(), (k + 1) * chunk); ++c)
          assembly.add_cell(cells[c], ind, sums[k]);
      }
    }
    catch (...)
    {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      failure = std::current_exception();
      next = n_mine; // the other threads stop after their chunk
    }
  };
  const unsigned int n_threads = std::max<std::size_t>(
      1, std::min<std::size_t>(MultithreadInfo::n_threads(), n_mine));
  std::vector<std::thread> threads;
  for (unsigned int t = 1; t < n_threads; ++t)
    threads.emplace_back(work);
  work();
  for (auto &t : threads)
    t.join();
  if (failure)
    std::rethrow_exception(failure);
  if (ranks > 1)
    allreduce_chunks(sums, ind);
  return sums;
}
} // namespace

template <int dim>
Indicators<dim>
estimate(const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
         const TemporalBasis &basis, const std::vector<Vector<double>> &U,
         const std::vector<Vector<double>> &Z, const std::vector<GoalSpec> &goals,
         const TimeIndicator time_indicator, const HigherOrderPrimal *hi,
         const SpaceIndicator space_indicator)
{
  if ((time_indicator == TimeIndicator::higher_order) != (hi != nullptr))
    throw std::invalid_argument("estimate: the higher_order time indicator needs the "
                                "dG(r+1) primal (and only it)");
  if (hi && (hi->basis.n_dofs() != basis.n_dofs() + 1 || hi->U.size() != mesh.n_slabs()))
    throw std::invalid_argument(
        "estimate: the higher-order primal must be dG(r+1) on the "
        "same slabs");
  Vector<double> zT, u0(primal.n_dofs());
  if (std::any_of(goals.begin(), goals.end(),
                  [](const GoalSpec &g) { return !g.over_time; }))
    zT = end_time_representer(adjoint, goals);
  {
    const ScalarFunctionFromFunctionObject<dim> f0(
        [&](const Point<dim> &x) { return primal.scene.initial_value(x); });
    VectorTools::interpolate(primal.mapping(), primal.dof_handler(), f0, u0);
    // E_tau u on the first slab starts from u_0. Where u_0 misses the Dirichlet data
    // (hemker: u_0 = 0, u_D = 1 on the circle), E_tau u - u would not vanish on Gamma_D,
    // and rho*(u,z)(E_tau u - u) would weigh that incompatibility of the data, which is
    // no temporal error of u_tau h (measured: eta_tau of x_e1's goal -0.03 against a
    // temporal error of 1e-6). u_0 takes the Dirichlet values of t_0 at the DoFs on
    // Gamma_D; all others keep their interpolated values.
    std::map<types::global_dof_index, double> boundary;
    for (const auto id : primal.scene.dirichlet_ids)
    {
      const ScalarFunctionFromFunctionObject<dim> g(
          [&](const Point<dim> &x)
          { return primal.scene.boundary_value(x, mesh.start(0), id); });
      VectorTools::interpolate_boundary_values(primal.mapping(), primal.dof_handler(), id,
                                               g, boundary);
    }
    for (const auto &[i, value] : boundary)
      u0[i] = value;
  }
  const auto &tria = primal.dof_handler().get_triangulation();
  Indicators<dim> ind;
  ind.eta_h_cell.assign(tria.n_active_cells(), std::array<double, dim>{});
  ind.eta_tau_cell.assign(tria.n_active_cells(), 0.);
  ind.eta_tau_slab.assign(mesh.n_slabs(), 0.);

  const auto sums = add_cells_in_chunks(
      primal.dof_handler(), mesh.n_slabs(),
      [&]()
      {
        return IndicatorAssembly<dim>(primal, adjoint, mesh, basis, U, Z, goals,
                                      time_indicator, hi, space_indicator, zT, u0);
      },
      ind);
  for (const auto &s : sums)
  {
    for (unsigned int i = 0; i < dim; ++i)
      ind.eta_h[i] += s.eta_h[i];
    for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
      ind.eta_tau_slab[n] += s.eta_tau_slab[n];
    ind.eta_tau += s.eta_tau;
    ind.eta_tau_rho += s.eta_tau_rho;
    ind.eta_tau_rhostar += s.eta_tau_rhostar;
    ind.eta_h_rho += s.eta_h_rho;
    ind.eta_h_rhostar += s.eta_h_rhostar;
    ind.eta_h_supg += s.eta_h_supg;
    ind.eta_h_split_rest += s.eta_h_split_rest;
    ind.eta_h_data += s.eta_h_data;
    ind.no_lift += s.no_lift;
  }
  return ind;
}

template Indicators<2> estimate<2>(const Space<2> &, const Space<2> &, const TimeMesh &,
                                   const TemporalBasis &,
                                   const std::vector<Vector<double>> &,
                                   const std::vector<Vector<double>> &,
                                   const std::vector<GoalSpec> &, TimeIndicator,
                                   const HigherOrderPrimal *, SpaceIndicator);
} // namespace anisodwr
