// The Krylov path of a slab operator (solver.type = iterative, or auto's choice where
// the coefficients depend on time): the solver and its preconditioner, the solve with
// its retries (the operator frozen at this slab, then the coupled direct solve), and the
// initial guess continued from the previous slab.
#include "slab/slab_operator.h"

#include "base/mpi.h"

#include <deal.II/base/timer.h>
#include <deal.II/lac/full_matrix.h>

#include <algorithm>
#include <iostream>

namespace anisodwr
{
using namespace dealii;

namespace
{
SolverTotals &totals = detail::mutable_solver_totals();
}

template <int dim>
double SlabOperator<dim>::solve_iterative_setup(int d, bool transpose)
{
  if (krylov[d])
    return 0.;
  Timer timer;
  auto solver = std::make_unique<IterativeSlabSolver>(it_opt);
  SlabMatrix matrix;
  matrix.assembled = k_assembled ? &K : nullptr;
  matrix.terms = &terms_cond;
  matrix.m = basis.n_dofs();
  matrix.split = kron.S1 ? &kron : nullptr;
  matrix.modes = frozen_modes() ? &frozen.lu : nullptr;
  solver->setup(matrix, transpose);
  krylov[d] = std::move(solver);
  const double setup_time = timer.wall_time();
  time.precondition += setup_time;
  ++time.n_preconditioners;
  return setup_time;
}

template <int dim>
double SlabOperator<dim>::solve_iterative(Vector<double> &rhs, bool transpose)
{
  const int d = transpose ? 1 : 0;
  double setup_time = solve_iterative_setup(d, transpose);
  Vector<double> x(rhs.size());
  if (guess[d].size() == rhs.size())
    initial_guess(d, x);
  bool refrozen = false;
  try
  {
    KrylovStats stats;
    try
    {
      stats = krylov[d]->solve(rhs, x);
    }
    catch (const KrylovFailure &)
    {
      // A preconditioner frozen at an earlier slab: once more with the operator frozen
      // at this slab's middle (one mode factorization) before the coupled direct solve
      // (a coupled LU of the slab takes several times the mode factors' memory).
      if (!frozen_modes() || frozen.t_start == t0)
        throw;
      Timer timer;
      freeze(t0, tau);
      refrozen = true;
      krylov[0].reset();
      krylov[1].reset();
      const double refreeze = timer.wall_time();
      setup_time += refreeze + solve_iterative_setup(d, transpose);
      x = 0.;
      if (guess[d].size() == rhs.size())
        initial_guess(d, x);
      stats = krylov[d]->solve(rhs, x);
    }
    ++time.n_krylov_solves;
    time.krylov_iterations += stats.iterations;
    time.max_krylov_iterations = std::max(time.max_krylov_iterations, stats.iterations);
    time.inner_iterations += stats.inner_iterations;
    totals.inner_iterations += stats.inner_iterations;
    ++totals.krylov_solves;
    totals.krylov_iterations += stats.iterations;
    totals.raise_max_iterations(stats.iterations);
    if (frozen_modes())
      frozen.max_iterations = std::max(frozen.max_iterations, stats.iterations);
  }
  catch (const KrylovFailure &e)
  {
    if (frozen_modes())
      frozen.stale = true; // the next slab refactorizes
    if (opt.fallback != Fallback::direct)
      throw;
    if (frozen_modes())
      on_output_rank(
          [&]()
          {
            std::cerr << "anisodwr: Krylov solve on slab (" << t0 << ", " << t0 + tau
                      << "] failed (" << e.what()
                      << (refrozen ? "; also with the operator frozen at this slab" : "")
                      << "); solved by the coupled direct solver\n";
          });
    ++time.n_fallbacks;
    ++totals.fallbacks;
    Timer timer;
    factorize();
    setup_time += timer.wall_time();
    lu.solve(rhs, transpose);
    guess[d] = rhs;
    guess_slab[d] = {t0, tau};
    return setup_time;
  }
  guess[d] = x;
  guess_slab[d] = {t0, tau};
  rhs = x;
  return setup_time;
}

template <int dim>
void SlabOperator<dim>::initial_guess(int d, Vector<double> &x) const
{
  const auto [g0, gtau] = guess_slab[d];
  if (g0 == t0 && gtau == tau)
  {
    x = guess[d]; // the same slab (another load of solve_transposed)
    return;
  }
  // the previous slab's polynomial in time, continued to this slab's temporal nodes
  const unsigned int m = basis.n_dofs();
  FullMatrix<double> W(m, m); // W(j, k) = l_k at this slab's node j
  for (unsigned int j = 0; j < m; ++j)
  {
    const std::vector<double> l = basis.values((t0 + basis.nodes()[j] * tau - g0) / gtau);
    for (unsigned int k = 0; k < m; ++k)
      W(j, k) = l[k];
  }
  const std::size_t n = x.size() / m;
  for (std::size_t i = 0; i < n; ++i)
    for (unsigned int j = 0; j < m; ++j)
    {
      double v = 0;
      for (unsigned int k = 0; k < m; ++k)
        v += W(j, k) * guess[d][i * m + k];
      x[i * m + j] = v;
    }
}

template double SlabOperator<2>::solve_iterative_setup(int, bool);
template double SlabOperator<2>::solve_iterative(Vector<double> &, bool);
template void SlabOperator<2>::initial_guess(int, Vector<double> &) const;
} // namespace anisodwr
