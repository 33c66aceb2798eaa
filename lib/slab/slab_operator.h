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
#include "slab/auto_solver.h"
#include "solver/direct_solver.h"
#include "solver/iterative_solver.h"
#include "solver/mode_solver.h"
#include "space/space.h"
#include "time/kronecker.h"
#include "time/temporal_basis.h"
#include "time/time_mesh.h"

#include <atomic>
#include <limits>
#include <map>
#include <memory>
#include <utility>

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
  /// preconditioner = modes: factorizations of the frozen operator
  unsigned int n_frozen_factorizations = 0;
  /// coefficients that depend on time: spatial assemblies, and the spatial matrix sets
  /// formed by interpolation in time instead (TimeInterpolation: the jump's
  /// mass per slab, a frozen operator's set; K itself takes the node matrices as terms)
  unsigned int n_spatial_assemblies = 0, n_interpolated = 0;
};

/// Process-wide totals over all SlabOperators (for summary.json); atomic: the DWR
/// loop's concurrent marches add to them from two threads.
struct SolverTotals
{
  std::atomic<unsigned long> krylov_solves{0}, krylov_iterations{0},
      max_krylov_iterations{0}, fallbacks{0}, inner_iterations{0}, frozen_factorizations{0};
  /// max_krylov_iterations = max(itself, n)
  void raise_max_iterations(unsigned long n)
  {
    unsigned long now = max_krylov_iterations.load();
    while (now < n && !max_krylov_iterations.compare_exchange_weak(now, n))
    {
    }
  }
};
const SolverTotals &solver_totals();
/// The Lagrange polynomials of the points `nodes` at t (the weights of the node
/// matrices of an interpolation in time).
std::vector<double> lagrange_weights(const std::vector<double> &nodes, double t);
namespace detail
{
/// The totals SlabOperator's solves add to (slab_operator.cc, slab_krylov.cc).
SolverTotals &mutable_solver_totals();
} // namespace detail
/// `"solver_fallbacks": n, "krylov": {...}` (JSON members, no braces).
std::string solver_totals_json();

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
  /// while K_n is unchanged; the previous solve's solution, continued in time, is the
  /// initial guess. A failed Krylov solve throws (KrylovFailure) or, with fallback =
  /// direct, is redone by UMFPACK (which then serves the remaining slabs with the same K_n).
  void solve(const dealii::Vector<double> &load, dealii::Vector<double> &U,
             bool transpose = false);
  /// K_n^T U[i] = loads[i] for every i, as solve(loads[i], U[i], true); with a direct
  /// solver (whose back-substitutions only read the factors) each in its own thread.
  void solve_transposed(const std::vector<const dealii::Vector<double> *> &loads,
                        const std::vector<dealii::Vector<double> *> &U);

  /// Whether prepare() keeps the present factorization on every slab of `mesh`:
  /// coefficients constant in time, solver.reuse_factorization, the last prepare()'s slab
  /// length on every slab, a direct solve (UMFPACK or the modes; not MUMPS) and not
  /// transposed_only. Then solve_prepared() may run in another thread beside this
  /// operator's solve(), solve_transposed() and prepare() calls on that mesh.
  bool prepared_for(const TimeMesh &mesh) const;
  /// K_n U = load on the slab (t_start, t_start + tau] as solve() does, by the present
  /// factors and without changing the operator (its timings neither: the caller times
  /// it). Requires prepared_for(the slab's mesh).
  void solve_prepared(double t_start, const dealii::Vector<double> &load,
                      dealii::Vector<double> &U) const;

  const SlabTimings &timings() const { return time; }
  dealii::types::global_dof_index n_slab_dofs() const
  {
    return space.n_dofs() * basis.n_dofs();
  }
  /// True if the last prepare() chose the iterative path.
  bool iterative() const { return use_iterative; }
  /// True if the last prepare() chose the Krylov solve preconditioned by the frozen
  /// operator's mode solver (solver.preconditioner = modes, or auto).
  bool frozen_modes() const
  {
    return use_iterative && it_opt.preconditioner == Preconditioner::modes;
  }
  /// True if the last prepare() chose the mode solver.
  bool modes() const { return use_modes; }
  /// The mode solver (its Schur form and factor sizes; empty unless modes()).
  const ModeDirectSolver &mode_solver() const { return modes_lu; }
  /// solver.type = auto: the last prepare()'s choice and its reason, e.g. "UMFPACK
  /// (predicted UMFPACK peak 812 MB + 10%, budget 12052 MB)"; empty for direct and iterative.
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
  /// the slab (t0, tau) each guess was solved on
  std::pair<double, double> guess_slab[2] = {{0., -1.}, {0., -1.}};
  /// The Krylov solve's initial guess from the previous solve in direction d: on the
  /// same slab that solution, else the previous slab's polynomial in time continued to
  /// this slab's temporal nodes (an O(tau^(r+1)) guess for a smooth solution).
  void initial_guess(int d, dealii::Vector<double> &x) const;
  bool lu_valid = false, k_assembled = false;
  /// The Krylov options in force (solver.iterative, or auto's choice).
  IterativeOptions it_opt;
  /// preconditioner = modes: the operator frozen at a slab's middle and its mode
  /// factors, kept over the following slabs (see IterativeOptions::refactor_iterations).
  struct Frozen
  {
    SpatialMatrices mats;
    ModeDirectSolver lu;
    double tau = -1;
    /// the start of the slab whose middle it is frozen at
    double t_start = std::numeric_limits<double>::quiet_NaN();
    unsigned int max_iterations = 0;
    bool stale = true;
  } frozen;
  /// Coefficients that depend on time: the spatial matrices at a few times of [0, T]
  /// (one set per slab length where delta_K depends on it, for at most two slab lengths:
  /// the slabs of any other length assemble their own). Where their polynomial
  /// interpolant of the lowest degree d <= 3 that reproduces the assembled matrices at
  /// two further times to 1e-12 relative exists (coefficients polynomial in t, as in the
  /// manufactured rotating field: d = 2 with SUPG), each temporal quadrature point's
  /// matrices are the interpolant's linear combination of its d + 1 node matrices
  /// instead of an assembly.
  struct TimeInterpolation
  {
    std::vector<double> times;
    /// empty where no interpolant is exact
    std::vector<SpatialMatrices> at_nodes;
  };
  std::map<double, TimeInterpolation> interpolation;
  /// The interpolation in time for slabs of length tau_n (built and checked on first
  /// use), or null where it is off, not exact or not kept.
  const TimeInterpolation *time_nodes(double tau_n);
  /// The spatial matrices at time t for slabs of length tau_n: interpolated where the
  /// check passed, else assembled. With `mass_only`, an interpolation forms M only.
  void matrices_at(double t, double tau_n, SpatialMatrices &m, bool mass_only = false);
  /// Assembles the spatial matrices at t_start + tau_n/2 and factorizes the frozen
  /// operator D (x) Mc + tau Mhat (x) Ac by its temporal modes.
  void freeze(double t_start, double tau_n);
  /// The Krylov solver of direction d (1: transposed) and its preconditioner, built if
  /// missing; returns the set-up time.
  double solve_iterative_setup(int d, bool transpose);
  /// The direct transposed solve of solve() (reads the factors and the constraints only).
  void direct_transposed(const dealii::Vector<double> &load, dealii::Vector<double> &U) const;
  /// C^T v on each temporal block (the homogeneous constraints), in place.
  void condense_blocks(dealii::Vector<double> &v) const;
  /// U's constrained entries on each temporal block: with `nodes` the Dirichlet values
  /// at each temporal node and the hanging nodes' (lifted_load's), else the homogeneous
  /// constraints' (the transposed solve).
  void distribute_blocks(
      dealii::Vector<double> &U,
      const std::vector<std::map<dealii::types::global_dof_index, double>> *nodes) const;
  /// C^T (load - K_full g) block by block: g the Dirichlet values u_D(t_start + s_k tau)
  /// at the temporal nodes and the hanging nodes' that follow (the lift); `nodes` gets
  /// those Dirichlet values (Space::dirichlet_values, one per temporal node, for
  /// distributing the solution).
  dealii::Vector<double>
  lifted_load(double t_start, const dealii::Vector<double> &load,
              std::vector<std::map<dealii::types::global_dof_index, double>> &nodes) const;
  void assemble_matrix();
  /// The Kronecker terms of K_n (full and condensed), the jump mass and the split for
  /// the Kronecker preconditioners; assembles the spatial matrices they need.
  void assemble_terms(double t_start, double tau_n, bool constant, bool same_tau);
  /// The temporal factors of K's terms on a slab of length tau_n, for coefficients that
  /// depend on time: per Gauss point q of the slab (points in [0, 1], weights) Tm_q =
  /// w_q l(s_q) l'(s_q)^T and Ta_q = w_q tau_n l(s_q) l(s_q)^T, and the jump's Tj.
  struct TemporalFactors
  {
    std::vector<double> points, weights;
    std::vector<dealii::FullMatrix<double>> Tm, Ta;
    dealii::FullMatrix<double> Tj;
  };
  /// assemble_terms' terms from the node matrices of the interpolation in time.
  void add_node_terms(const TimeInterpolation &ti, const TemporalFactors &f,
                      double t_start, double tau_n);
  /// assemble_terms' terms from the spatial matrices at each Gauss point.
  void add_quadrature_terms(const TemporalFactors &f, double t_start, double tau_n);
  /// Frees the condensed spatial matrices (constant coefficients: mats[0]); the next
  /// assemble_terms assembles them again.
  void release_condensed();
  /// Assembles K first if the iterative path skipped it. With `release` (a reused
  /// factorization without iterative refinement), frees Mc and Ac once K is built and K
  /// and its pattern once UMFPACK has copied it, before the numeric factorization: the
  /// factorization's peak then holds only M, A, UMFPACK's copy and its work space.
  void factorize(bool release = false);
  /// solver.type = auto: sets use_iterative (auto_picks_frozen_modes, which also sets
  /// it_opt's preconditioner to modes, or auto_picks_iterative), use_modes
  /// (auto_picks_modes) and `choice`.
  void choose_solver(bool constant);
  /// One LU per temporal mode of `kron`; with `release` frees A_c afterwards (M_c stays:
  /// the Schur form's coupling multiplies by it).
  void factorize_modes(bool release);
  /// Krylov solve in place (rhs -> solution); returns the time spent on setup.
  double solve_iterative(dealii::Vector<double> &rhs, bool transpose);
  double t0 = 0, tau = -1;
  SlabTimings time;
};
} // namespace anisodwr
