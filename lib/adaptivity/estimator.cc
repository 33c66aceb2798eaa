#include "adaptivity/estimator.h"

#include "adaptivity/indicator_assembly.h"
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
            &s.eta_h_rhostar, &s.eta_h_supg, &s.eta_h_split_rest, &s.eta_h_data,
            &s.eta_h_quad})
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
/// returns the per-chunk sums in chunk order, one per adjoint (the cell's own
/// indicators go to ind[a]).
template <int dim, class MakeAssembly>
std::vector<std::vector<Indicators<dim>>>
add_cells_in_chunks(const DoFHandler<dim> &dofs, unsigned int n_slabs,
                    const MakeAssembly &make_assembly, std::vector<Indicators<dim>> &ind)
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
  std::vector<std::vector<Indicators<dim>>> sums(n_chunks,
                                                 std::vector<Indicators<dim>>(ind.size()));
  for (auto &chunk_sums : sums)
    for (auto &s : chunk_sums)
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
    for (std::size_t a = 0; a < ind.size(); ++a)
    {
      std::vector<Indicators<dim>> of_a;
      for (auto &chunk_sums : sums)
        of_a.push_back(std::move(chunk_sums[a]));
      allreduce_chunks(of_a, ind[a]);
      for (std::size_t k = 0; k < sums.size(); ++k)
        sums[k][a] = std::move(of_a[k]);
    }
  return sums;
}
} // namespace

template <int dim>
std::vector<Indicators<dim>>
estimate_each(const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
              const TemporalBasis &basis, const std::vector<Vector<double>> &U,
              const std::vector<AdjointOf> &adjoints, const TimeIndicator time_indicator,
              const HigherOrderPrimal *hi, const SpaceIndicator space_indicator,
              const DataQuadrature &data, const bool conforming_weights)
{
  if ((time_indicator == TimeIndicator::higher_order) != (hi != nullptr))
    throw std::invalid_argument("estimate: the higher_order time indicator needs the "
                                "dG(r+1) primal (and only it)");
  if (hi && (hi->basis.n_dofs() != basis.n_dofs() + 1 || hi->U.size() != mesh.n_slabs()))
    throw std::invalid_argument(
        "estimate: the higher-order primal must be dG(r+1) on the "
        "same slabs");
  // per adjoint: z(T^+) (end-time goals) and the hanging-node defects
  std::vector<Vector<double>> zT(adjoints.size());
  std::vector<HangingDefect<dim>> hanging;
  hanging.reserve(adjoints.size());
  for (std::size_t a = 0; a < adjoints.size(); ++a)
  {
    const auto &goals = adjoints[a].goals;
    if (std::any_of(goals.begin(), goals.end(),
                    [](const GoalSpec &g) { return !g.over_time; }))
      zT[a] = end_time_representer(adjoint, goals);
    if (conforming_weights)
      hanging.emplace_back(primal, adjoint, *adjoints[a].Z, basis.n_dofs());
    else
      hanging.emplace_back(basis.n_dofs());
  }
  Vector<double> u0(primal.n_dofs());
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
  std::vector<Indicators<dim>> ind(adjoints.size());
  std::vector<AssemblyAdjoint<dim>> in;
  for (std::size_t a = 0; a < adjoints.size(); ++a)
  {
    ind[a].eta_h_cell.assign(tria.n_active_cells(), std::array<double, dim>{});
    ind[a].eta_tau_cell.assign(tria.n_active_cells(), 0.);
    ind[a].eta_tau_slab.assign(mesh.n_slabs(), 0.);
    in.push_back({*adjoints[a].Z, adjoints[a].goals, zT[a], hanging[a]});
  }

  const auto sums = add_cells_in_chunks(
      primal.dof_handler(), mesh.n_slabs(),
      [&]()
      {
        return IndicatorAssembly<dim>(primal, adjoint, mesh, basis, U, in, time_indicator,
                                      hi, space_indicator, u0, data);
      },
      ind);
  for (std::size_t a = 0; a < adjoints.size(); ++a)
    for (const auto &chunk_sums : sums)
    {
      const Indicators<dim> &s = chunk_sums[a];
      for (unsigned int i = 0; i < dim; ++i)
        ind[a].eta_h[i] += s.eta_h[i];
      for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
        ind[a].eta_tau_slab[n] += s.eta_tau_slab[n];
      ind[a].eta_tau += s.eta_tau;
      ind[a].eta_tau_rho += s.eta_tau_rho;
      ind[a].eta_tau_rhostar += s.eta_tau_rhostar;
      ind[a].eta_h_rho += s.eta_h_rho;
      ind[a].eta_h_rhostar += s.eta_h_rhostar;
      ind[a].eta_h_supg += s.eta_h_supg;
      ind[a].eta_h_split_rest += s.eta_h_split_rest;
      ind[a].eta_h_data += s.eta_h_data;
      ind[a].eta_h_quad += s.eta_h_quad;
      ind[a].no_lift += s.no_lift;
    }
  return ind;
}

template <int dim>
Indicators<dim>
estimate(const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
         const TemporalBasis &basis, const std::vector<Vector<double>> &U,
         const std::vector<Vector<double>> &Z, const std::vector<GoalSpec> &goals,
         const TimeIndicator time_indicator, const HigherOrderPrimal *hi,
         const SpaceIndicator space_indicator, const DataQuadrature &data,
         const bool conforming_weights)
{
  return std::move(estimate_each(primal, adjoint, mesh, basis, U, {{&Z, goals}},
                                 time_indicator, hi, space_indicator, data,
                                 conforming_weights)
                       .front());
}

template std::vector<Indicators<2>>
estimate_each<2>(const Space<2> &, const Space<2> &, const TimeMesh &, const TemporalBasis &,
                 const std::vector<Vector<double>> &, const std::vector<AdjointOf> &,
                 TimeIndicator, const HigherOrderPrimal *, SpaceIndicator,
                 const DataQuadrature &, bool);
template Indicators<2> estimate<2>(const Space<2> &, const Space<2> &, const TimeMesh &,
                                   const TemporalBasis &,
                                   const std::vector<Vector<double>> &,
                                   const std::vector<Vector<double>> &,
                                   const std::vector<GoalSpec> &, TimeIndicator,
                                   const HigherOrderPrimal *, SpaceIndicator,
                                   const DataQuadrature &, bool);
} // namespace anisodwr
