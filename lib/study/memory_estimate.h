#pragma once
// Memory estimate of a single run, a convergence level or a DWR loop, made before it
// starts from the sizes of its systems (no allocation). The byte counts per stored
// value are exact (8-byte values, 4-byte column indices, deal.II's copy of the slab
// matrix for UMFPACK); the UMFPACK fill and the per-DoF overhead (mesh, DoF handler,
// constraints, estimator scratch) are calibrated against measured peaks
// (doc/results.md, "Memory estimate").
#include "config/parameters.h"
#include "slab/slab_operator.h"
#include "space/space.h"

#include <string>

namespace anisodwr
{
/// The slab system of one spatial space.
struct SlabSystemSize
{
  double n_space = 0;     ///< spatial DoFs (0: no such system)
  double nnz_space = 0;   ///< nonzeros of the spatial sparsity pattern
  bool iterative = false; ///< Krylov solver (else UMFPACK)
  bool modes = false;     ///< UMFPACK per temporal mode (solver.type = modes or auto)
  /// Krylov preconditioned by the frozen operator's modes (preconditioner = modes)
  bool frozen_modes = false;
  unsigned int degree = 1; ///< FE_Q degree (UMFPACK's predicted peak depends on it)
};

struct MemoryModel
{
  SlabSystemSize primal;
  SlabSystemSize adjoint;   ///< n_space = 0 for a primal-only run
  unsigned int r = 0;       ///< dG(r): r+1 temporal DoFs per slab
  unsigned int n_slabs = 1; ///< N: slab solutions stored for all of them
  /// Coefficients depend on t: r+3 sets of spatial matrices per operator, else one.
  bool time_dependent = false;
  /// UMFPACK with a reused factorization and no iterative refinement: the condensed
  /// spatial matrices and K are freed before the numeric factorization (SlabOperator),
  /// so the operator holds only M, A, UMFPACK's copy of K and the factors.
  bool lean_direct = false;
  unsigned int krylov_vectors = 32; ///< iterative: restart + 2 vectors of the slab size
  /// adjoint solutions held at once: 2 with adaptivity.per_goal_estimates, the number
  /// of goals with goal.weights = estimate
  unsigned int adjoints_stored = 1;
  /// adaptivity.measure_time_error: the primal on 4 N slabs beside the N-slab solution.
  unsigned int extra_primal_slabs = 0;
  /// time_indicator = higher_order: the dG(r+1) primal, its own slab operator (marched
  /// after the primal's) and its solutions, counted in dG(r) slab solutions
  bool higher_order = false;
  unsigned int higher_order_slabs = 0;
  double base_mb = 0; ///< resident memory of the process before the run's data
  /// The primal and the adjoint marched at the same time (adaptivity.concurrent_marches):
  /// the primal thread's operators (dG(r), then dG(r+1)) beside the adjoint's.
  bool concurrent = false;
  /// adaptivity.goal_estimate = enriched or both: the primal marched once more in the adjoint's
  /// degree (an operator of the adjoint's size and its slab solutions), after the
  /// adjoints, or in the primal thread while they march when `concurrent`.
  bool enriched = false;
  /// adaptivity.goal_estimate = consistent or both: u_q's slab solutions, marched after the
  /// adjoints with their operator (no operator of its own)
  bool consistent = false;
};

struct MemoryEstimate
{
  /// base_mb + startup growth + the larger of the primal and the adjoint phase
  double total_mb = 0;
  double solutions_mb = 0; ///< stored slab solutions in the peak phase
  /// every slab solution stored at the end of the marches (primal, dG(r+1) primal,
  /// adjoints), whichever phase is the peak
  double stored_solutions_mb = 0;
  double matrices_mb = 0;  ///< spatial and slab matrices, spaces, in the peak phase
  double solver_mb = 0;    ///< UMFPACK factors or Krylov vectors and preconditioner
};

/// Peak memory of the run, base_mb plus the largest of its phases. Each slab operator
/// holds its matrices and either its factorization's peak (at the start of its march)
/// or its factors and the solutions marched so far (at the end). One after the other:
/// the primal, the dG(r+1) primal and the adjoint march, each beside the solutions
/// before it. Concurrent marches: both factorizations at the start; the dG(r+1)
/// factorization beside the adjoint's and the primal solutions (measured to overlap);
/// both operators with all solutions at the end.
MemoryEstimate estimate_memory(const MemoryModel &m);

/// Resident memory of this process now (VmRSS), MB.
double resident_memory_mb();
/// Returns the heap's free pages to the system (glibc's malloc_trim): called between the
/// phases of a loop, so that the next phase's factorizations (fresh mappings) do not
/// sit beside freed but resident memory of the last one.
void release_free_memory();
/// (physical_memory_mb: slab/slab_operator.h)

/// The memory limit of a run: adaptivity.max_memory_mb, or the physical memory when
/// that key is 0. `name` describes it for messages.
struct MemoryLimit
{
  double mb = 0;
  std::string name;
};
MemoryLimit memory_limit(const Parameters &prm);

/// The slab system of `space` (set up) with dG(r) and the solver choice of `options`.
SlabSystemSize slab_system(const Space<2> &space, const SlabSolverOptions &options,
                           unsigned int r);

/// The model of one run (study levels: primal only; DWR loops: with the adjoint space
/// and n_goals goals) for the parameters `prm`.
MemoryModel memory_model(const Parameters &prm, const Space<2> &primal,
                         const Space<2> *adjoint, unsigned int n_slabs, double base_mb,
                         unsigned int n_goals = 1);

/// The goal estimates' degree-q marches of a DWR loop whose crosswind term is
/// `switched` by a solution (or off), into m: `enriched` for each u_q with an operator
/// of its own (enriched's; consistent's where consistent_uq_needs_own_operator),
/// `consistent` for consistent's u_q by the adjoint's factors. memory_model sets them for
/// a switched loop; the first loop and each loop of the DWR run set them for their own.
void count_uq_marches(MemoryModel &m, const Parameters &prm, bool switched);

/// Before the mesh is refined: the memory estimate of the first DWR loop (adjoint of
/// degree adjoint_degree) or, with adjoint_degree = 0, of a primal-only run, predicted
/// from the coarse mesh's cells times 4^discretization.initial_refinements (FE_Q(p) on
/// a structured mesh); ResourceLimitError (as check_memory) if it
/// exceeds the limit. A setting too large for the memory stops here, before a mesh or
/// DoFs are built.
void check_initial_mesh_memory(const Parameters &prm, const Scene<2> &scene,
                               double coarse_cells, unsigned int adjoint_degree,
                               unsigned int n_goals, const MemoryLimit &limit);

/// Throws ResourceLimitError with a one-line message naming `what` (e.g. "loop 3"),
/// the estimate, the limit and the sizes if estimate_mb > limit.mb.
void check_memory(const std::string &what, double estimate_mb, const MemoryLimit &limit,
                  const MemoryModel &model, const std::string &note = "");
} // namespace anisodwr
