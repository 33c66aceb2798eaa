#include "slab/slab_operator.h"

#include "base/errors.h"
#include "base/mpi.h"
#include "solver/matrix_market.h"

#include <deal.II/base/timer.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <future>
#include <iostream>
#include <map>
#include <mutex>

namespace anisodwr
{
using namespace dealii;

SolverTotals &detail::mutable_solver_totals()
{
  static SolverTotals totals;
  return totals;
}

namespace
{
SolverTotals &totals = detail::mutable_solver_totals();

/// solver.type = modes on a scene whose coefficients depend on time: said once.
void warn_modes_time_dependent()
{
  static std::once_flag once;
  std::call_once(once,
                 []()
                 {
                   on_output_rank(
                       []()
                       {
                         std::cerr << "anisodwr: solver.type = modes needs coefficients "
                                      "constant in time; the slab systems of this scene "
                                      "are solved by the coupled direct solver\n";
                       });
                 });
}
} // namespace

const SolverTotals &solver_totals() { return totals; }

std::string solver_totals_json()
{
  return "\"solver_fallbacks\": " + std::to_string(totals.fallbacks) +
         ", \"krylov\": {\"solves\": " + std::to_string(totals.krylov_solves) +
         ", \"iterations\": " + std::to_string(totals.krylov_iterations) +
         ", \"max_iterations\": " + std::to_string(totals.max_krylov_iterations) +
         ", \"inner_iterations\": " + std::to_string(totals.inner_iterations) +
         ", \"frozen_factorizations\": " + std::to_string(totals.frozen_factorizations) + "}";
}

template <int dim>
SlabOperator<dim>::SlabOperator(const Space<dim> &space, const TemporalBasis &basis,
                                const SlabSolverOptions &options)
    : space(space), basis(basis), opt(options), reuse(options.reuse_factorization),
      lu(options.refinement_steps, options.direct_solver), modes_lu(options.refinement_steps)
{
}

template <int dim>
SlabOperator<dim>::~SlabOperator() = default;

template <int dim>
void SlabOperator<dim>::assemble_matrix()
{
  Timer timer;
  if (pattern.n_rows() == 0)
    make_kron_sparsity(space.sparsity(), basis.n_dofs(), pattern);
  assemble_kron(terms_cond, pattern, K);
  k_assembled = true;
  time.assemble_slab += timer.wall_time();
}

template <int dim>
void SlabOperator<dim>::factorize(bool release)
{
  if (!k_assembled)
    assemble_matrix();
  Timer timer;
  const auto n = K.m();
  if (release)
  {
    // the matrices K was built from, K itself once UMFPACK has its copy
    release_condensed();
    lu.analyze(K);
    K.clear();
    pattern.reinit(0, 0, 0);
    k_assembled = false;
    lu.factorize();
  }
  else
    lu.factorize(K);
  time.factorize += timer.wall_time();
  time.factor_mb = std::max(time.factor_mb, lu.info().factor_mb);
  // (MUMPS: its own figures; UMFPACK: the measured heap)
  const DirectSolverInfo &info = lu.info();
  record_lu(n, space.degree(), basis.n_dofs(),
            info.heap_peak_mb > 0 ? info.heap_peak_mb : info.peak_mb,
            info.heap_peak_mb > 0 ? info.heap_held_mb : info.factor_mb);
  ++time.n_factorizations;
  lu_valid = true;
}

template <int dim>
void SlabOperator<dim>::factorize_modes(bool release)
{
  Timer timer;
  modes_lu.factorize(kron);
  if (release)
  {
    // M_c stays for the Schur coupling; A_c is assembled again when tau changes
    mats[0].Ac.clear();
    terms_cond.clear();
    kron.S2 = nullptr;
  }
  time.factorize += timer.wall_time();
  time.factor_mb = std::max(time.factor_mb, modes_lu.factor_mb());
  record_modes(space.n_dofs(), space.degree(), modes_lu.mode_figures());
  time.n_factorizations += static_cast<unsigned int>(modes_lu.schur().blocks.size());
  lu_valid = true;
}

template <int dim>
void SlabOperator<dim>::choose_solver(bool constant)
{
  const unsigned int m = basis.n_dofs();
  const double n = double(space.n_dofs()) * m;
  const double budget = auto_memory_budget_mb(opt);
  const bool factorization_reused = constant && reuse;
  if (auto_picks_frozen_modes(opt, space.n_dofs(), m, space.degree(), constant))
  {
    use_modes = false;
    use_iterative = true;
    it_opt.preconditioner = Preconditioner::modes;
    // GMRES (deal.II's, without Trilinos): with a fixed preconditioner flexible GMRES
    // gains nothing, and BiCGStab has no restart to keep the vectors few
    it_opt.krylov = Krylov::gmres;
    // a near-exact preconditioner: 1e-13 costs about 1.5 iterations more per solve and
    // makes eta agree with the coupled direct solve to 8 digits (1e-10: 3e-6)
    it_opt.tolerance = std::min(it_opt.tolerance, 1e-13);
    choice = "iterative, preconditioned by the mode solver of the slab operator frozen at "
             "the slab's middle (coefficients depend on time; Krylov tolerance 1e-13; "
             "refactorized after a solve of more than " +
             std::to_string(it_opt.refactor_iterations) +
             " iterations; predicted peak " +
             std::to_string(long(std::ceil(
                 std::min(predicted_modes_mb(space.n_dofs(), space.degree(), m), 1e15)))) +
             " MB + 10%, budget " + std::to_string(long(budget)) + " MB)";
    return;
  }
  use_modes = auto_picks_modes(opt, space.n_dofs(), m, space.degree(), factorization_reused);
  if (use_modes)
  {
    use_iterative = false;
    choice = "modes (dG(" + std::to_string(m - 1) +
             "), coefficients constant in time: one UMFPACK LU per temporal mode, "
             "predicted peak " +
             std::to_string(long(std::ceil(
                 std::min(predicted_modes_mb(space.n_dofs(), space.degree(), m), 1e15)))) +
             " MB + 10%, budget " + std::to_string(long(budget)) + " MB)";
    return;
  }
  const double peak = predicted_lu_mb(n, space.degree(), m);
  use_iterative = !opt.no_trilinos &&
                  auto_picks_iterative(opt, n, m, space.degree(), factorization_reused);
  const std::string engine = opt.direct_solver == DirectEngine::mumps ? "MUMPS" : "UMFPACK";
  const std::string memory = "predicted " + engine + " peak " +
                             std::to_string(long(std::ceil(std::min(peak, 1e15)))) +
                             " MB + 10%, budget " + std::to_string(long(budget)) + " MB";
  if (!use_iterative)
    choice = engine + " (" + memory + ")";
  else if (auto_memory_margin * peak > budget)
    choice = "iterative (" + memory + ")";
  else
    choice = "iterative (a factorization per slab, N_space (r+1)^2 = " +
             std::to_string(long(n * m)) + " >= solver.auto_threshold = " +
             std::to_string(long(auto_size_threshold(opt, space.degree()))) + ")";
}

template <int dim>
void SlabOperator<dim>::assemble_terms(double t_start, double tau_n, bool constant,
                                       bool same_tau)
{
  terms_full.clear();
  terms_cond.clear();
  FullMatrix<double> tM(basis.mass());
  tM *= tau_n;
  if (constant)
  {
    // delta_K <= c tau_n: a new slab length needs new spatial matrices
    if (mats.empty() || mats[0].Mc.empty() || mats[0].Ac.empty() ||
        (space.delta_depends_on_tau() && !same_tau))
    {
      mats.resize(1);
      space.assemble_matrices(0., tau_n, mats[0]);
    }
    terms_full = {{basis.derivative_with_jump(), &mats[0].M}, {tM, &mats[0].A}};
    terms_cond = {{basis.derivative_with_jump(), &mats[0].Mc}, {tM, &mats[0].Ac}};
    jump_M = &mats[0].M;
    kron = {basis.derivative_with_jump(), tM, &mats[0].Mc, &mats[0].Ac};
    return;
  }
  // r+2 Gauss points integrate polynomial-in-t coefficients of degree <= 2 exactly.
  const unsigned int m = basis.n_dofs();
  TemporalFactors f;
  gauss_rule(m + 1, f.points, f.weights);
  for (unsigned int q = 0; q < f.points.size(); ++q)
  {
    std::vector<double> l = basis.values(f.points[q]), dl(m);
    for (unsigned int k = 0; k < m; ++k)
      dl[k] = basis.derivative(k, f.points[q]);
    f.Tm.push_back(outer(l, dl));
    f.Ta.push_back(outer(l, l));
    f.Tm[q] *= f.weights[q];
    f.Ta[q] *= f.weights[q] * tau_n;
  }
  f.Tj = outer(basis.left_trace(), basis.left_trace());
  mats.resize(f.points.size() + 1);
  const unsigned int mid = f.points.size() / 2;
  if (const auto *nodes = time_nodes(tau_n))
    add_node_terms(*nodes, f, t_start, tau_n);
  else
    add_quadrature_terms(f, t_start, tau_n);
  jump_M = &mats.back().M;
  // Kronecker preconditioner: D (x) M + tau Mhat (x) A frozen at the middle Gauss point.
  kron = KronSplit();
  if (!mats[mid].Mc.empty())
    kron = {basis.derivative_with_jump(), tM, &mats[mid].Mc, &mats[mid].Ac};
}

template <int dim>
void SlabOperator<dim>::add_node_terms(const TimeInterpolation &ti,
                                       const TemporalFactors &f, double t_start,
                                       double tau_n)
{
  // The matrices at the quadrature points are combinations of the node matrices: K's
  // terms are the node matrices, each with its share of the temporal factors, so that no
  // quadrature point's matrices are formed.
  const unsigned int m = basis.n_dofs(), nq = f.points.size();
  const std::vector<SpatialMatrices> &nodes = ti.at_nodes;
  std::vector<FullMatrix<double>> TM(nodes.size(), FullMatrix<double>(m, m)), TA = TM;
  for (unsigned int q = 0; q < nq; ++q)
  {
    const std::vector<double> l = lagrange_weights(ti.times, t_start + f.points[q] * tau_n);
    for (unsigned int c = 0; c < nodes.size(); ++c)
    {
      TM[c].add(l[c], f.Tm[q]);
      TA[c].add(l[c], f.Ta[q]);
    }
  }
  const std::vector<double> lj = lagrange_weights(ti.times, t_start);
  for (unsigned int c = 0; c < nodes.size(); ++c)
  {
    TM[c].add(lj[c], f.Tj);
    if (!opt.transposed_only)
    {
      terms_full.push_back({TM[c], &nodes[c].M});
      terms_full.push_back({TA[c], &nodes[c].A});
    }
    terms_cond.push_back({TM[c], &nodes[c].Mc});
    terms_cond.push_back({TA[c], &nodes[c].Ac});
  }
  matrices_at(t_start, tau_n, mats.back(), true);
  // the quadrature points' matrices are not needed; the middle point's only for a
  // Kronecker preconditioner's split
  for (unsigned int q = 0; q < nq; ++q)
    mats[q] = SpatialMatrices();
  if ((opt.type == SolverType::iterative || opt.type == SolverType::automatic) &&
      is_kronecker(opt.iterative.preconditioner))
    matrices_at(t_start + f.points[nq / 2] * tau_n, tau_n, mats[nq / 2]);
}

template <int dim>
void SlabOperator<dim>::add_quadrature_terms(const TemporalFactors &f, double t_start,
                                             double tau_n)
{
  for (unsigned int q = 0; q < f.points.size(); ++q)
  {
    matrices_at(t_start + f.points[q] * tau_n, tau_n, mats[q]);
    terms_full.push_back({f.Tm[q], &mats[q].M});
    terms_full.push_back({f.Ta[q], &mats[q].A});
    terms_cond.push_back({f.Tm[q], &mats[q].Mc});
    terms_cond.push_back({f.Ta[q], &mats[q].Ac});
  }
  auto &mj = mats.back();
  matrices_at(t_start, tau_n, mj);
  terms_full.push_back({f.Tj, &mj.M});
  terms_cond.push_back({f.Tj, &mj.Mc});
}

template <int dim>
void SlabOperator<dim>::prepare(double t_start, double tau_n)
{
  const bool constant = !space.scene.coefficients_depend_on_time();
  // Equal slab lengths computed as differences of t_n differ in the last bits.
  const bool same_tau = std::abs(tau_n - tau) <= 1e-12 * tau_n;
  if (constant && reuse && factorized && same_tau)
  {
    t0 = t_start;
    return;
  }
  Timer timer;
  assemble_terms(t_start, tau_n, constant, same_tau);
  time.assemble_spatial += timer.wall_time();
  krylov[0].reset();
  krylov[1].reset();
  lu_valid = false;
  factorized = false; // until the new K is factorized (or the Krylov path is set up)
  lu.clear();
  modes_lu.clear();
  // The kronecker preconditioners work matrix-free: K is assembled only if needed.
  K.clear();
  k_assembled = false;
  it_opt = opt.iterative;
  if (opt.type == SolverType::automatic)
    choose_solver(constant);
  else
  {
    use_iterative = opt.type == SolverType::iterative;
    use_modes = opt.type == SolverType::modes && constant;
    if (opt.type == SolverType::modes && !constant)
      warn_modes_time_dependent();
  }
  if (frozen_modes() &&
      (frozen.stale || !frozen.lu.factorized() ||
       std::abs(frozen.tau - tau_n) > 1e-12 * tau_n ||
       frozen.max_iterations > it_opt.refactor_iterations))
    freeze(t_start, tau_n);
  if ((!use_iterative && !use_modes) ||
      (use_iterative && IterativeSlabSolver::needs_assembled_matrix(it_opt)) ||
      !opt.dump_matrix.empty())
    assemble_matrix();
  if (!opt.dump_matrix.empty())
  {
    write_matrix_market(K, opt.dump_matrix);
    opt.dump_matrix.clear(); // the first slab only
  }
  if (use_modes)
  {
    K.clear(); // assembled only for output.dump_slab_loop
    pattern.reinit(0, 0, 0);
    k_assembled = false;
    factorize_modes(releases_assembly_matrices(opt, constant));
  }
  else if (!use_iterative)
    // UMFPACK without iterative refinement reads neither K nor its copy of K in the
    // solves, and a reused factorization needs no condensed matrices until the slab
    // length changes: the march keeps only M (the jump) and A (the Dirichlet lift).
    factorize(releases_assembly_matrices(opt, constant));
  factorized = true;
  t0 = t_start;
  tau = tau_n;
}

template <int dim>
void SlabOperator<dim>::freeze(double t_start, double tau_n)
{
  Timer timer;
  frozen.lu.clear();
  matrices_at(t_start + 0.5 * tau_n, tau_n, frozen.mats);
  FullMatrix<double> tM(basis.mass());
  tM *= tau_n;
  frozen.lu.factorize(
      KronSplit{basis.derivative_with_jump(), tM, &frozen.mats.Mc, &frozen.mats.Ac});
  // the mode solver keeps a pointer to Mc (the Schur form's coupling) only
  frozen.mats.M.clear();
  frozen.mats.A.clear();
  frozen.mats.Ac.clear();
  frozen.tau = tau_n;
  frozen.t_start = t_start;
  frozen.max_iterations = 0;
  frozen.stale = false;
  time.factorize += timer.wall_time();
  ++time.n_frozen_factorizations;
  ++totals.frozen_factorizations;
}

template <int dim>
void SlabOperator<dim>::release_condensed()
{
  mats[0].Mc.clear();
  mats[0].Ac.clear();
  terms_cond.clear();
  kron = KronSplit();
}

namespace
{
/// f(k, block) on each temporal block k of the interleaved vector v (m blocks of n), in
/// place.
template <typename F>
void on_blocks(Vector<double> &v, unsigned int m, types::global_dof_index n, const F &f)
{
  Vector<double> block(n);
  for (unsigned int k = 0; k < m; ++k)
  {
    extract_block(v, k, m, block);
    f(k, block);
    insert_block(block, k, m, v);
  }
}
} // namespace

template <int dim> void SlabOperator<dim>::condense_blocks(Vector<double> &v) const
{
  on_blocks(v, basis.n_dofs(), space.n_dofs(),
            [&](unsigned int, auto &b) { space.constraints().condense(b); });
}

template <int dim>
void SlabOperator<dim>::distribute_blocks(
    Vector<double> &U, const std::vector<std::map<types::global_dof_index, double>> *nodes) const
{
  on_blocks(U, basis.n_dofs(), space.n_dofs(),
            [&](unsigned int k, auto &b)
            {
              if (nodes)
                space.distribute_dirichlet((*nodes)[k], b);
              else
                space.constraints().distribute(b);
            });
}

template <int dim>
void SlabOperator<dim>::direct_transposed(const Vector<double> &load, Vector<double> &U) const
{
  U = load;
  condense_blocks(U);
  if (use_modes)
    modes_lu.solve(U, true);
  else
    lu.solve(U, true);
  distribute_blocks(U, nullptr);
}

template <int dim>
Vector<double>
SlabOperator<dim>::lifted_load(double t_start, const Vector<double> &load,
                               std::vector<std::map<types::global_dof_index, double>> &nodes) const
{
  const unsigned int m = basis.n_dofs();
  nodes.resize(m);
  // Dirichlet lift g (values at constrained DoFs only): rhs -= K_full g.
  Vector<double> g(space.n_dofs() * m), Kg, rhs(load);
  on_blocks(g, m, space.n_dofs(),
            [&](unsigned int k, auto &b)
            {
              nodes[k] = space.dirichlet_values(t_start + basis.nodes()[k] * tau);
              space.distribute_dirichlet(nodes[k], b);
            });
  vmult_kron(terms_full, g, Kg);
  rhs -= Kg;
  condense_blocks(rhs);
  return rhs;
}

template <int dim> bool SlabOperator<dim>::prepared_for(const TimeMesh &mesh) const
{
  if (!factorized || !reuse || use_iterative || opt.transposed_only ||
      opt.direct_solver == DirectEngine::mumps || space.scene.coefficients_depend_on_time())
    return false;
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
    if (std::abs(mesh.tau(n) - tau) > 1e-12 * mesh.tau(n)) // (prepare()'s same_tau)
      return false;
  return true;
}

template <int dim>
void SlabOperator<dim>::solve_prepared(double t_start, const Vector<double> &load,
                                       Vector<double> &U) const
{
  std::vector<std::map<types::global_dof_index, double>> nodes;
  U = lifted_load(t_start, load, nodes);
  if (use_modes)
    modes_lu.solve(U);
  else
    lu.solve(U);
  distribute_blocks(U, &nodes);
}

template <int dim>
void SlabOperator<dim>::solve_transposed(const std::vector<const Vector<double> *> &loads,
                                         const std::vector<Vector<double> *> &U)
{
  // The direct solves run side by side in threads, except with MUMPS: one MUMPS
  // instance takes one call at a time, and under mpirun its messages from two threads
  // would interleave (hemker.json's two goals crashed in DMUMPS_BUF_SEND on 2 ranks).
  if (use_iterative || loads.size() < 2 || opt.direct_solver == DirectEngine::mumps)
  {
    for (std::size_t i = 0; i < loads.size(); ++i)
      solve(*loads[i], *U[i], true);
    return;
  }
  Timer timer;
  std::vector<std::future<void>> others;
  for (std::size_t i = 1; i < loads.size(); ++i)
    others.push_back(std::async(std::launch::async,
                                [this, &loads, &U, i]() { direct_transposed(*loads[i], *U[i]); }));
  direct_transposed(*loads[0], *U[0]);
  for (auto &f : others)
    f.get();
  time.solve += timer.wall_time();
  time.n_solves += static_cast<unsigned int>(loads.size());
}

template <int dim>
void SlabOperator<dim>::solve(const Vector<double> &load, Vector<double> &U, bool transpose)
{
  if (!transpose && opt.transposed_only)
    throw std::logic_error("SlabOperator: a transposed_only operator solved untransposed");
  Timer timer;
  double setup_time = 0;
  if (!use_iterative || lu_valid) // by the factors (after a fallback: UMFPACK's)
  {
    if (transpose)
      direct_transposed(load, U);
    else
      solve_prepared(t0, load, U);
  }
  else
  {
    std::vector<std::map<types::global_dof_index, double>> nodes;
    if (transpose)
    {
      U = load;
      condense_blocks(U);
    }
    else
      U = lifted_load(t0, load, nodes);
    setup_time = solve_iterative(U, transpose);
    distribute_blocks(U, transpose ? nullptr : &nodes);
  }
  time.solve += timer.wall_time() - setup_time;
  ++time.n_solves;
}

template class SlabOperator<2>;
} // namespace anisodwr
