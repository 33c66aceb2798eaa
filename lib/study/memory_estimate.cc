#include "study/memory_estimate.h"
#include "study/options.h"

#include "base/errors.h"
#include "base/mpi.h"
#include "io/table.h"

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace anisodwr
{
namespace
{
constexpr double MB = 1024. * 1024.;
/// Calibrated (doc/results.md, "Memory estimate"): bytes per spatial DoF of a space
/// besides its sparsity pattern (triangulation share, DoF handler, constraints,
/// estimator and march scratch).
constexpr double bytes_per_dof = 200.;
/// Resident memory the process gains on its first solves beyond what it had before
/// (library code paged in, solver and quadrature initialization), MB: calibrated on
/// moving_hump.json, moving_hump_p1.json and hemker.json (doc/results.md, "Memory
/// estimate of the shipped DWR configs").
constexpr double startup_mb = 30.;
/// Iterative path: ILU factors and the Tpetra copy of the slab matrix, per nonzero.
constexpr double precondition_bytes_per_nnz = 36.;

struct Phase
{
  double solutions = 0, matrices = 0, solver = 0;
  double total() const { return solutions + matrices + solver; }
};

/// One slab operator (bytes): its spatial and slab matrices, and its solver at the
/// factorization's peak and while it solves.
struct Operator
{
  double matrices = 0, factorizing = 0, solving = 0;
  /// assembly matrices beside `matrices` before the factorization
  double assembly = 0;
};

/// The operator of system s with t temporal DoFs per node.
Operator slab_operator(const SlabSystemSize &s, const MemoryModel &m, unsigned int t)
{
  Operator op;
  if (s.n_space <= 0)
    return op;
  const double nnz_k = double(t) * t * s.nnz_space, n_k = t * s.n_space;
  const double sets = m.time_dependent ? t + 2 : 1;
  if (s.modes)
  {
    // K is not assembled. Kept: M (jump), A (Dirichlet lift), M_c (the Schur form's
    // coupling), and A_c while the modes factorize unless released; the solver: the
    // modes' factorization peak (with UMFPACK's copy of the mode matrix), the factors
    // of all modes and the 2t + 2 spatial vectors of a solve afterwards.
    const ModesMemory lu = predicted_modes_memory(s.n_space, s.degree, t);
    op.matrices = (m.lean_direct ? 3 : 4) * 8 * s.nnz_space;
    op.assembly = m.lean_direct ? 8 * s.nnz_space : 0.;
    op.factorizing = op.assembly + lu.peak_mb * MB;
    op.solving = 8 * (2 * t + 2) * s.n_space + lu.factors_mb * MB;
    return op;
  }
  // The assembly's matrices: the spatial sets (M, A, M_c, A_c), K and its pattern.
  const double assembly = sets * 4 * 8 * s.nnz_space + 12 * nnz_k + 8 * n_k;
  if (s.iterative && s.frozen_modes)
  {
    // matrix-free K: the spatial sets and the frozen operator's M_c; the frozen
    // operator's mode factors (with their factorization peak) and the Krylov vectors
    const ModesMemory lu = predicted_modes_memory(s.n_space, s.degree, t);
    op.matrices = (sets + 1) * 4 * 8 * s.nnz_space;
    op.factorizing = lu.peak_mb * MB + 8. * m.krylov_vectors * n_k;
    op.solving = lu.factors_mb * MB + 8. * m.krylov_vectors * n_k;
    return op;
  }
  if (s.iterative)
  {
    op.matrices = assembly;
    op.factorizing = op.solving =
        8. * m.krylov_vectors * n_k + precondition_bytes_per_nnz * nnz_k;
    return op;
  }
  // UMFPACK's heap peak (the copy it factorizes, factors and work space) as
  // solver.type = auto predicts it: from the run's last factorization of this degree and
  // r, else from the fit to measured peaks; afterwards the factors and the vectors of a
  // solve
  const double peak = predicted_lu_mb(n_k, s.degree, t) * MB;
  op.solving = 16 * n_k + predicted_lu_held_mb(n_k, s.degree, t) * MB;
  if (m.lean_direct)
  {
    // M_c, A_c and K go before the numeric factorization, M and A stay: the larger of
    // the assembly and the factorization beside M and A
    op.matrices = 2 * 8 * s.nnz_space;
    op.assembly = assembly - op.matrices;
    op.factorizing = std::max(op.assembly, peak);
  }
  else
  {
    op.matrices = assembly;
    op.factorizing = peak;
  }
  return op;
}

/// The larger of two phases.
Phase larger(const Phase &a, const Phase &b) { return b.total() > a.total() ? b : a; }

/// `base` with operator `op` added at its factorization (solutions unchanged) or at the
/// end of its march (`marched`: solutions added).
Phase with(Phase base, const Operator &op, bool factorizing, double marched = 0)
{
  base.matrices += op.matrices;
  base.solver += factorizing ? op.factorizing : op.solving;
  base.solutions += factorizing ? 0. : marched;
  return base;
}
} // namespace

MemoryEstimate estimate_memory(const MemoryModel &m)
{
  const unsigned int t = m.r + 1;
  auto space = [](const SlabSystemSize &s)
  { return bytes_per_dof * s.n_space + 4 * s.nnz_space; };
  auto solutions = [&](const SlabSystemSize &s, double slabs)
  { return 8. * t * s.n_space * slabs; };

  const Operator op_p = slab_operator(m.primal, m, t), op_a = slab_operator(m.adjoint, m, t);
  const Operator op_hi = m.higher_order ? slab_operator(m.primal, m, t + 1) : Operator();
  const double U = solutions(m.primal, m.n_slabs + m.extra_primal_slabs),
               U_hi = solutions(m.primal, m.higher_order_slabs),
               Z = m.adjoints_stored * solutions(m.adjoint, m.n_slabs),
               U_q = m.enriched || m.consistent ? solutions(m.adjoint, m.n_slabs) : 0.,
               // what the adjoint's operator holds at the end of its marches
               Z_end = Z + (m.consistent ? U_q : 0.);
  Phase start;
  start.matrices = space(m.primal) + space(m.adjoint);
  Phase peak;
  if (m.concurrent && m.adjoint.n_space > 0)
  {
    Phase primal_done = start;
    primal_done.solutions = U;
    // The adjoint (of a higher degree) assembles while the primal factorizes; its
    // factorization's peak comes while the primal marches
    Phase assembling = with(start, op_p, true);
    assembling.matrices += op_a.matrices + op_a.assembly;
    peak = larger(assembling, with(with(primal_done, op_p, false), op_a, true));
    if (m.higher_order)
      peak = larger(peak, with(with(primal_done, op_hi, true), op_a, true));
    peak = larger(peak, with(with(primal_done, m.higher_order ? op_hi : op_p, false, U_hi),
                             op_a, false, Z_end));
    if (m.enriched)
    {
      // the primal thread's degree-q march beside the adjoints' (their factorizations
      // may overlap)
      Phase hi_done = primal_done;
      hi_done.solutions += U_hi;
      peak = larger(peak, with(with(hi_done, op_a, true), op_a, true));
      peak = larger(peak, with(with(hi_done, op_a, false, U_q), op_a, false, Z));
    }
  }
  else
  {
    peak = larger(with(start, op_p, true), with(start, op_p, false, U));
    Phase done = start;
    done.solutions = U;
    if (m.higher_order)
    {
      peak = larger(peak, larger(with(done, op_hi, true), with(done, op_hi, false, U_hi)));
      done.solutions += U_hi;
    }
    if (m.adjoint.n_space > 0)
      peak = larger(peak, larger(with(done, op_a, true), with(done, op_a, false, Z_end)));
    if (m.enriched && m.adjoint.n_space > 0)
    {
      // after the adjoints' factors are freed, beside their solutions
      done.solutions += Z;
      peak = larger(peak, larger(with(done, op_a, true), with(done, op_a, false, U_q)));
    }
  }
  MemoryEstimate e;
  e.solutions_mb = peak.solutions / MB;
  e.stored_solutions_mb = (U + U_hi + (m.adjoint.n_space > 0 ? Z : 0.)) / MB;
  e.matrices_mb = peak.matrices / MB;
  e.solver_mb = peak.solver / MB;
  e.total_mb = m.base_mb + startup_mb + peak.total() / MB;
  return e;
}

void release_free_memory()
{
  malloc_trim(0);
}

double resident_memory_mb()
{
  std::FILE *f = std::fopen("/proc/self/status", "r");
  if (!f)
    return peak_memory_mb();
  char line[256];
  double kb = -1;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmRSS:", 6) == 0)
    {
      kb = std::atof(line + 6);
      break;
    }
  std::fclose(f);
  return kb >= 0 ? kb / 1024. : peak_memory_mb();
}

MemoryLimit memory_limit(const Parameters &prm)
{
  if (prm.adaptivity.max_memory_mb > 0)
    return {prm.adaptivity.max_memory_mb,
            "adaptivity.max_memory_mb = " + json_number(prm.adaptivity.max_memory_mb, 6) +
                " MB"};
  const double phys = physical_memory_mb();
  return {phys, "the physical memory of " + json_number(std::round(phys), 8) +
                    " MB (adaptivity.max_memory_mb = 0)"};
}

SlabSystemSize slab_system(const Space<2> &space, const SlabSolverOptions &options,
                           unsigned int r)
{
  SlabSystemSize s;
  s.n_space = space.n_dofs();
  s.nnz_space = space.sparsity().n_nonzero_elements();
  s.degree = space.degree();
  const bool constant = !space.scene.coefficients_depend_on_time();
  s.iterative = solves_iteratively(options, s.n_space, r + 1, space.degree(), constant);
  s.frozen_modes = solves_by_frozen_modes(options, s.n_space, r + 1, space.degree(), constant);
  s.modes = solves_by_modes(options, s.n_space, r + 1, space.degree(), constant,
                            options.reuse_factorization && constant);
  return s;
}

void count_uq_marches(MemoryModel &m, const Parameters &prm, bool switched)
{
  const bool own_consistent =
      marches_consistent_uq(prm) && consistent_uq_needs_own_operator(prm, switched);
  m.enriched = marches_enriched_uq(prm) || own_consistent;
  m.consistent = marches_consistent_uq(prm) && !own_consistent;
}

namespace
{
/// The model for given slab systems (adjoint.n_space = 0: primal only).
MemoryModel memory_model(const Parameters &prm, const SlabSystemSize &primal,
                         const SlabSystemSize &adjoint, bool time_dependent,
                         unsigned int n_slabs, double base_mb, unsigned int n_goals)
{
  const SlabSolverOptions options = slab_solver_options(prm);
  const unsigned int r = prm.discretization.r;
  const bool has_adjoint = adjoint.n_space > 0;
  MemoryModel m;
  m.primal = primal;
  m.adjoint = adjoint;
  m.r = r;
  m.n_slabs = n_slabs;
  m.time_dependent = time_dependent;
  m.lean_direct = releases_assembly_matrices(options, !m.time_dependent);
  m.krylov_vectors = prm.solver.iterative.restart + 2;
  if (has_adjoint)
  {
    // one adjoint per goal (goal.weights = estimate, per_goal_estimates): every goal's
    // adjoint is marched before the estimates
    m.adjoints_stored =
        prm.goal.weights == "estimate" || prm.adaptivity.per_goal_estimates
            ? std::max(1u, n_goals)
            : 1;
    m.extra_primal_slabs = prm.adaptivity.measure_time_error ? 4 * n_slabs : 0;
    // time_indicator = higher_order keeps the dG(r+1) primal: (r+2)/(r+1) primal slabs each
    m.higher_order = prm.adaptivity.time_indicator == TimeIndicator::higher_order;
    if (m.higher_order)
      m.higher_order_slabs = (n_slabs * (r + 2) + r) / (r + 1);
    count_uq_marches(m, prm, true);
  }
  m.base_mb = base_mb;
  return m;
}


/// The slab system of FE_Q(degree) on `cells` cells of a structured mesh, predicted:
/// (n p + 1)^2 ~ cells p^2 DoFs, each coupled with (p + 2)^2 DoFs on average (exact for
/// the interior of a uniform mesh: vertex, edge and cell DoFs together).
SlabSystemSize predicted_system(double cells, unsigned int degree,
                                const SlabSolverOptions &options, unsigned int r,
                                bool constant)
{
  SlabSystemSize s;
  s.n_space = cells * degree * degree;
  s.nnz_space = s.n_space * (degree + 2.) * (degree + 2.);
  s.degree = degree;
  const bool reused = options.reuse_factorization && constant;
  s.iterative = solves_iteratively(options, s.n_space, r + 1, degree, constant);
  s.frozen_modes = solves_by_frozen_modes(options, s.n_space, r + 1, degree, constant);
  s.modes = solves_by_modes(options, s.n_space, r + 1, degree, constant, reused);
  return s;
}
} // namespace

MemoryModel memory_model(const Parameters &prm, const Space<2> &primal,
                         const Space<2> *adjoint, unsigned int n_slabs, double base_mb,
                         unsigned int n_goals)
{
  const SlabSolverOptions options = slab_solver_options(prm);
  const unsigned int r = prm.discretization.r;
  return memory_model(prm, slab_system(primal, options, r),
                      adjoint ? slab_system(*adjoint, options, r) : SlabSystemSize(),
                      primal.scene.coefficients_depend_on_time(), n_slabs, base_mb,
                      n_goals);
}

void check_initial_mesh_memory(const Parameters &prm, const Scene<2> &scene,
                               double coarse_cells, unsigned int adjoint_degree,
                               unsigned int n_goals, const MemoryLimit &limit)
{
  const unsigned int k = prm.discretization.initial_refinements, r = prm.discretization.r;
  const double cells = coarse_cells * std::pow(4., double(k));
  const SlabSolverOptions options = slab_solver_options(prm);
  const bool constant = !scene.coefficients_depend_on_time();
  const SlabSystemSize primal =
      predicted_system(cells, prm.discretization.p, options, r, constant);
  const SlabSystemSize adjoint =
      adjoint_degree > 0 ? predicted_system(cells, adjoint_degree, options, r, constant)
                         : SlabSystemSize();
  MemoryModel model = memory_model(prm, primal, adjoint, !constant, prm.discretization.n_slabs,
                                   mpi_max(resident_memory_mb()), n_goals);
  // loop 1's u_q: without a crosswind factor unless crosswind_first_solve gives one
  count_uq_marches(model, prm, first_loop_crosswind_switched(prm));
  // (the mesh is part of the calibrated bytes per DoF, at least one DoF per cell)
  const double estimate = estimate_memory(model).total_mb;
  std::ostringstream note;
  note << " (predicted before the mesh is built: " << json_number(coarse_cells, 10)
       << " coarse cells x 4^" << k << " = " << json_number(cells, 15) << " cells)";
  check_memory(adjoint_degree > 0 ? "loop 1" : "the run", estimate, limit, model,
               note.str());
}

void check_memory(const std::string &what, double estimate_mb, const MemoryLimit &limit,
                  const MemoryModel &model, const std::string &note)
{
  if (!(estimate_mb > limit.mb))
    return;
  auto solver = [](const SlabSystemSize &s)
  { return std::string(s.iterative ? "Krylov" : s.modes ? "UMFPACK per temporal mode" : "UMFPACK"); };
  std::string sizes = "N_space " + std::to_string(std::size_t(model.primal.n_space));
  if (model.adjoint.n_space > 0)
    sizes += ", adjoint " + std::to_string(std::size_t(model.adjoint.n_space)) + " DoFs";
  sizes += ", " + std::to_string(model.n_slabs) + " slabs of dG(" +
           std::to_string(model.r) + "), " + solver(model.primal) +
           (model.adjoint.n_space > 0 && (model.adjoint.iterative != model.primal.iterative ||
                 model.adjoint.modes != model.primal.modes)
                ? "/" + solver(model.adjoint)
                : "");
  throw ResourceLimitError(what + ": memory estimate " +
                           json_number(std::round(estimate_mb), 10) + " MB" + note +
                           " exceeds " + limit.name + "; " + sizes +
                           "; not started");
}
} // namespace anisodwr
