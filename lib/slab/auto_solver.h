#pragma once
// What solver.type = auto picks for a slab system, and the memory models it uses: the
// physical memory, UMFPACK's factorization peak (fitted and extrapolated from measured
// factorizations) and the mode solver's peak (doc/results.md, "Slab solvers").
#include "slab/slab_solver_options.h"
#include "solver/mode_figures.h"

#include <vector>

namespace anisodwr
{
/// Physical memory of the machine, MB (8192 if the system does not say).
double physical_memory_mb();

/// UMFPACK factorization peak (MB) of an n x n slab matrix of FE_Q(degree) with m
/// temporal DoFs per node as fitted to measured peaks (doc/results.md, "Slab solvers").
double fitted_lu_mb(double n, unsigned int degree, unsigned int m);
/// Predicted UMFPACK factorization peak (MB): extrapolated from the measured heap peak
/// (with the solver's copy of the matrix) of the last factorization of the same degree
/// and m in this process (record_lu), else fitted_lu_mb. UMFPACK's own symbolic bound
/// is far too loose for this (33x at 2.4e5 unknowns).
double predicted_lu_mb(double n, unsigned int degree, unsigned int m);
/// The heap the factorization holds afterwards (factors, analysis), predicted the same
/// way (MB).
double predicted_lu_held_mb(double n, unsigned int degree, unsigned int m);
/// Records a measured factorization peak for predicted_lu_mb (SlabOperator does); the
/// records are per process (not thread-safe). reset_lu_records forgets them and the
/// mode solver's (record_modes) (tests).
void record_lu(double n, unsigned int degree, unsigned int m, double peak_mb,
               double held_mb);
void reset_lu_records();

/// solver.type = auto compares the predicted factorization peaks, times this margin, with
/// its memory budget.
constexpr double auto_memory_margin = 1.1;

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
/// if predicted_lu_mb times auto_memory_margin exceeds auto_memory_budget_mb, or if each
/// slab needs its own factorization (time-dependent coefficients, reuse_factorization =
/// false) and N_space m^2 >= auto_size_threshold; UMFPACK otherwise.
bool auto_picks_iterative(const SlabSolverOptions &opt, double n, unsigned int m,
                          unsigned int degree, bool factorization_reused);

/// The blocks of the real Schur form of dG(m-1)'s T2^{-1} T1 in the mode solver's order
/// (1: a real mode, 2: a complex pair; m / 2 pairs and, for odd m, one real mode),
/// computed once per m.
std::vector<unsigned int> mode_blocks(unsigned int m);

/// Predicted memory of the mode solver for N_space = n_space and m temporal modes (MB):
/// the factors of all modes (held while the slabs are solved) and the peak of the
/// factorization: each mode's peak beside the factors of those before it, in the order
/// of the Schur form's blocks (mode_blocks). The peaks are the measured heap of UMFPACK
/// with the solver's copy of the mode matrix (solver/umfpack_memory.h), the factors what
/// UMFPACK holds afterwards. Per kind of mode (real, complex) extrapolated from the last
/// factorization of that kind and degree in this process (record_modes: the size per
/// unknown allowed to grow like log n), else from fitted_lu_mb (a complex factor 1.8 real
/// ones, measured).
struct ModesMemory
{
  double factors_mb = 0, peak_mb = 0;
};
ModesMemory predicted_modes_memory(double n_space, unsigned int degree, unsigned int m);
/// predicted_modes_memory(...).peak_mb
double predicted_modes_mb(double n_space, unsigned int degree, unsigned int m);
/// Records the figures of a mode factorization of N_space = n_space (SlabOperator does).
void record_modes(double n_space, unsigned int degree, const ModeLuFigures &f);

/// Whether solver.type = auto picks the mode solver: m = r+1 >= 2, one factorization
/// serves all slabs (coefficients constant in time, reuse_factorization), the direct
/// solver is UMFPACK and predicted_modes_mb times auto_memory_margin fits
/// auto_memory_budget_mb.
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

/// Whether solver.type = auto picks the Krylov solve preconditioned by the mode solver
/// of the frozen operator (preconditioner = modes): coefficients that depend on time,
/// reuse_factorization, UMFPACK, and predicted_modes_mb times auto_memory_margin fits
/// auto_memory_budget_mb. (It runs on deal.II's GMRES, so no_trilinos allows it.)
bool auto_picks_frozen_modes(const SlabSolverOptions &opt, double n_space, unsigned int m,
                             unsigned int degree, bool coefficients_constant);

/// True if `options` solve by Krylov preconditioned by the frozen operator's modes
/// (type iterative with preconditioner modes, or auto_picks_frozen_modes).
bool solves_by_frozen_modes(const SlabSolverOptions &options, double n_space,
                            unsigned int m, unsigned int degree, bool coefficients_constant);

/// True if `options` solve the slab system of a space of FE_Q(degree) with n_space DoFs
/// and a dG basis of m functions iteratively (type iterative, or auto_picks_frozen_modes,
/// or auto_picks_iterative for n_space m unknowns, unless auto_picks_modes).
bool solves_iteratively(const SlabSolverOptions &options, double n_space, unsigned int m,
                        unsigned int degree, bool coefficients_constant);

/// True if `options` solve that slab system without Trilinos: directly, or by GMRES
/// preconditioned by the frozen operator's modes (IterativeSlabSolver::
/// runs_without_trilinos; auto's frozen-modes path always is). Such solves may run in
/// two threads (the DWR loop's concurrent marches).
bool solves_without_trilinos(const SlabSolverOptions &options, double n_space,
                             unsigned int m, unsigned int degree, bool coefficients_constant);
} // namespace anisodwr
