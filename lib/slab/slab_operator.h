#pragma once
// The slab operator K_n of doc/method.md §2 as a Kronecker sum, for one space and one
// dG(r) basis, with its condensed (constrained) form solved by UMFPACK or, per
// SlabSolverOptions, by a Belos Krylov method (lib/solver/iterative_solver.h).
//
//   K_n = sum_q w_q [ l(s_q) l'(s_q)^T (x) M(t_q) + tau l(s_q) l(s_q)^T (x) A(t_q) ]
//         + e e^T (x) M(t_{n-1})
// reduces to D (x) M + tau Mhat (x) A when b and alpha do not depend on t; the
// spatial matrices are then assembled once per mesh and the factorization is
// reused while tau does not change.
#include "slab/slab_solver_options.h"
#include "solver/direct_solver.h"
#include "solver/iterative_solver.h"
#include "solver/mode_solver.h"
#include "space/space.h"
#include "time/kronecker.h"
#include "time/temporal_basis.h"

#include <memory>

namespace anisodwr
{
struct SlabTimings
{
  double assemble_spatial = 0, assemble_slab = 0, factorize = 0, solve = 0;
  unsigned int n_factorizations = 0, n_solves = 0;
  /// Iterative path: preconditioner setups (incl. the Tpetra copy of K), their time,
  /// Krylov solves, their total and largest iteration counts, and the number of
  /// failed Krylov solves replaced by UMFPACK (solver.fallback = direct).
  double precondition = 0;
  /// UMFPACK: the largest factor size (MB, UMFPACK's figure)
  double factor_mb = 0;
  unsigned int n_preconditioners = 0, n_krylov_solves = 0, krylov_iterations = 0,
               max_krylov_iterations = 0, n_fallbacks = 0;
  /// GMRES iterations inside the kronecker* preconditioners (solver.inner_iterations)
  unsigned long inner_iterations = 0;
};

/// Process-wide totals over all SlabOperators (for summary.json).
struct SolverTotals
{
  unsigned long krylov_solves = 0, krylov_iterations = 0, max_krylov_iterations = 0,
                fallbacks = 0, inner_iterations = 0;
};
const SolverTotals &solver_totals();
/// `"solver_fallbacks": n, "krylov": {...}` (JSON members, no braces).
std::string solver_totals_json();

/// Writes A to `path` in Matrix Market coordinate format (1-based, all stored entries;
/// rank 0 writes, all ranks throw an InputError if it cannot). Collective.
void write_matrix_market(const dealii::SparseMatrix<double> &A, const std::string &path);

/// Physical memory of the machine, MB (8192 if the system does not say).
double physical_memory_mb();

/// UMFPACK factorization peak (MB) of an n x n slab matrix of FE_Q(degree) with m
/// temporal DoFs per node as fitted to measured peaks (doc/results.md, "Slab solvers").
double fitted_lu_mb(double n, unsigned int degree, unsigned int m);
/// Predicted UMFPACK factorization peak (MB): extrapolated from the last factorization
/// of the same degree and m in this process (record_lu), else fitted_lu_mb. UMFPACK's
/// own symbolic bound is far too loose for this (33x at 2.4e5 unknowns).
double predicted_lu_mb(double n, unsigned int degree, unsigned int m);
/// Records a measured factorization peak for predicted_lu_mb (SlabOperator does); the
/// records are per process (not thread-safe). reset_lu_records forgets them (tests).
void record_lu(double n, unsigned int degree, unsigned int m, double peak_mb);
void reset_lu_records();

/// The memory a UMFPACK factorization may take under solver.type = auto (MB):
/// solver.auto_memory_mb, or half the physical memory if that is 0.
double auto_memory_budget_mb(const SlabSolverOptions &opt);

/// The slab size N_space (r+1)^2 from which solver.type = auto solves iteratively when
/// each slab needs its own factorization: solver.auto_threshold if it is positive, else
/// by the spatial degree, where the best Krylov solver's factorization-plus-solve time
/// per slab overtakes UMFPACK's (doc/results.md, "Slab solvers: UMFPACK versus Krylov"):
/// 2e4 for Q1, 3e5 for Q2, 1e6 for Q3, 3e6 from Q4 on.
double auto_size_threshold(const SlabSolverOptions &opt, unsigned int degree);

/// Which solver solver.type = auto picks (true: iterative) for n slab unknowns with m
/// temporal DoFs per node, given whether one factorization serves all slabs: iterative
/// if predicted_lu_mb exceeds auto_memory_budget_mb, or if each slab needs its own
/// factorization (time-dependent coefficients, reuse_factorization = false) and
/// N_space m^2 >= auto_size_threshold; UMFPACK otherwise.
bool auto_picks_iterative(const SlabSolverOptions &opt, double n, unsigned int m,
                          unsigned int degree, bool factorization_reused);

/// Predicted peak (MB) of the mode solver for N_space = n_space and m temporal modes:
/// the factors of m - 1 real N_space LUs (a complex pair counts as two) held while the
/// last one factorizes, each as predicted_lu_mb(n_space, degree, 1).
double predicted_modes_mb(double n_space, unsigned int degree, unsigned int m);

/// Whether solver.type = auto picks the mode solver: m = r+1 >= 2, one factorization
/// serves all slabs (coefficients constant in time, reuse_factorization), the direct
/// solver is UMFPACK and predicted_modes_mb fits auto_memory_budget_mb.
bool auto_picks_modes(const SlabSolverOptions &opt, double n_space, unsigned int m,
                      unsigned int degree, bool factorization_reused);

/// True if `options` solve by temporal modes (type modes with coefficients constant in
/// time, or auto_picks_modes).
bool solves_by_modes(const SlabSolverOptions &options, double n_space, unsigned int m,
                     unsigned int degree, bool coefficients_constant,
                     bool factorization_reused);

/// True if the slab operator frees M_c, A_c and K before the numeric factorization: one
/// UMFPACK factorization serves every slab (coefficients constant in t,
/// reuse_factorization) and its solves read no matrix (refinement_steps = 0).
bool releases_assembly_matrices(const SlabSolverOptions &options,
                                bool coefficients_constant);

/// True if `options` solve the slab system of a space of FE_Q(degree) with n_space DoFs
/// and a dG basis of m functions iteratively (type iterative, or auto_picks_iterative
/// for n_space m unknowns, unless auto_picks_modes).
bool solves_iteratively(const SlabSolverOptions &options, double n_space, unsigned int m,
                        unsigned int degree, bool factorization_reused);

template <int dim>
class SlabOperator
{
public:
  SlabOperator(const Space<dim> &space, const TemporalBasis &basis,
               const SlabSolverOptions &options);
  ~SlabOperator();

  /// Prepares K_n for the slab (t0, t0 + tau]: assembles spatial matrices if needed,
  /// builds the condensed slab matrix and factorizes, unless the previous
  /// factorization can be reused.
  void prepare(double t0, double tau);

  /// Unconstrained Kronecker terms of K_n (for tests and for the Dirichlet lift).
  const std::vector<KronTerm> &full_terms() const { return terms_full; }
  /// M(t_{n-1}) (unconstrained): the mass matrix of the jump term.
  const dealii::SparseMatrix<double> &jump_mass() const { return *jump_M; }

  /// Solves K_n U = load with the Dirichlet values u_D(t0 + s_k tau) at the temporal
  /// nodes and the hanging-node constraints. `load` and U are interleaved full vectors.
  /// If `transpose`, solves K_n^T U = load with homogeneous constraints (adjoint).
  /// Iterative path: the preconditioner is built on first use per direction and reused
  /// while K_n is unchanged; the previous solve's solution is the initial guess. A failed
  /// Krylov solve throws (KrylovFailure) or, with fallback = direct, is redone by UMFPACK
  /// (which then serves the remaining slabs with the same K_n).
  void solve(const dealii::Vector<double> &load, dealii::Vector<double> &U,
             bool transpose = false);

  const SlabTimings &timings() const { return time; }
  dealii::types::global_dof_index n_slab_dofs() const
  {
    return space.n_dofs() * basis.n_dofs();
  }
  /// True if the last prepare() chose the iterative path.
  bool iterative() const { return use_iterative; }
  /// True if the last prepare() chose the mode solver.
  bool modes() const { return use_modes; }
  /// The mode solver (its Schur form and factor sizes; empty unless modes()).
  const ModeDirectSolver &mode_solver() const { return modes_lu; }
  /// solver.type = auto: the last prepare()'s choice and its reason, e.g. "UMFPACK
  /// (predicted UMFPACK peak 812 MB, budget 12052 MB)"; empty for direct and iterative.
  const std::string &auto_choice() const { return choice; }
  /// UMFPACK's figures of the last analysis and factorization.
  const DirectSolverInfo &direct_info() const { return lu.info(); }

private:
  const Space<dim> &space;
  const TemporalBasis &basis;
  SlabSolverOptions opt;
  bool reuse;
  bool use_iterative = false;
  bool use_modes = false;

  std::vector<SpatialMatrices> mats; // one per temporal quadrature point (+ jump), or one
  std::vector<KronTerm> terms_full, terms_cond;
  const dealii::SparseMatrix<double> *jump_M = nullptr;
  dealii::SparsityPattern pattern;
  dealii::SparseMatrix<double> K;
  DirectSolver lu;
  ModeDirectSolver modes_lu;
  std::string choice;
  bool factorized = false;
  KronSplit kron;
  std::unique_ptr<IterativeSlabSolver> krylov[2]; // [transpose]
  dealii::Vector<double> guess[2];
  bool lu_valid = false, k_assembled = false;
  void assemble_matrix();
  /// The Kronecker terms of K_n (full and condensed), the jump mass and the split for
  /// the Kronecker preconditioners; assembles the spatial matrices they need.
  void assemble_terms(double t_start, double tau_n, bool constant, bool same_tau);
  /// Frees the condensed spatial matrices (constant coefficients: mats[0]); the next
  /// assemble_terms assembles them again.
  void release_condensed();
  /// Assembles K first if the iterative path skipped it. With `release` (a reused
  /// factorization without iterative refinement), frees Mc and Ac once K is built and K
  /// and its pattern once UMFPACK has copied it, before the numeric factorization: the
  /// factorization's peak then holds only M, A, UMFPACK's copy and its work space.
  void factorize(bool release = false);
  /// solver.type = auto: sets use_iterative (auto_picks_iterative), use_modes
  /// (auto_picks_modes) and `choice`.
  void choose_solver(bool factorization_reused);
  /// One LU per temporal mode of `kron`; with `release` frees A_c afterwards (M_c stays:
  /// the Schur form's coupling multiplies by it).
  void factorize_modes(bool release);
  /// Krylov solve in place (rhs -> solution); returns the time spent on setup.
  double solve_iterative(dealii::Vector<double> &rhs, bool transpose);
  double t0 = 0, tau = -1;
  SlabTimings time;
};
} // namespace anisodwr
