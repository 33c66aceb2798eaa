#pragma once
// What solver.type = auto picks for a slab system, and the memory models it uses: the
// physical memory, UMFPACK's factorization peak (fitted and extrapolated from measured
// factorizations) and the mode solver's peak (doc/results.md, "Slab solvers").
#include "slab/slab_solver_options.h"

namespace anisodwr
{
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
} // namespace anisodwr
