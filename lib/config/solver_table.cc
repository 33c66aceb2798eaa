// The parameter table: the keys of section solver (see parameter_table.cc for the entry format).
#include "config/table_binding.h"

namespace anisodwr::config::table
{
std::vector<Entry> solver_entries()
{
  using S = SolverSection;
  const auto m = [](auto member) { return at(&Parameters::solver, member); };
  // the Krylov options: members of SlabSolverOptions::iterative
  using I = IterativeOptions;
  const auto k = [](auto member)
  { return at(&Parameters::solver, &SlabSolverOptions::iterative, member); };
  return {
      {"solver", "type", "auto", m(&S::type), by_name,
       "Slab solver: direct (UMFPACK, or solver.direct, on the coupled slab matrix), "
       "modes (exact solves by the temporal modes of K = D (x) M + tau Mhat (x) A: the "
       "real Schur form of the dG(r) matrices, one UMFPACK LU of an N_space matrix per "
       "real mode and one complex LU per complex pair, reused while tau is unchanged; "
       "same answers as direct up to round-off, factors about (r+1) instead of "
       "(r+1)^2 times those of one N_space LU; UMFPACK on every MPI rank; coefficients "
       "that depend on time are solved by direct instead, with a warning), iterative "
       "(Belos Krylov method solver.krylov with solver.preconditioner, Trilinos), or "
       "auto: with coefficients that depend on time iterative with preconditioner = modes "
       "(gmres, tolerance min(solver.tolerance, 1e-13)) while the modes' predicted peak "
       "fits solver.auto_memory_mb, else as follows; modes for r >= 1 with coefficients constant in time, "
       "solver.reuse_factorization and solver.direct = umfpack while their predicted "
       "peak fits solver.auto_memory_mb; otherwise UMFPACK on the coupled matrix while "
       "its predicted factorization peak fits solver.auto_memory_mb, iterative "
       "otherwise; with a factorization per slab (coefficients that depend on time, or "
       "no reuse) also iterative from N_space (r+1)^2 >= solver.auto_threshold. The "
       "choice and its reason are printed when they change."},
      {"solver", "dof_numbering", "auto", m(&S::dof_numbering), by_name,
       "Spatial DoF order: native (deal.II's cell-wise order), downstream (sorted "
       "along the convection b at the domain's centre; ILU and Gauss-Seidel then sweep "
       "with the flow, which keeps them effective on convection-dominated, anisotropic "
       "meshes), or auto: native where the slab systems go to UMFPACK (solver.type = "
       "direct, or modes, also as auto picks it for the space's DoF count), else "
       "downstream. Direct solves are unaffected up to round-off; native is a few "
       "percent faster there."},
      {"solver", "time_interpolation", "true", m(&S::time_interpolation), boolean,
       "Coefficients that depend on time: assemble the spatial matrices once per loop at "
       "a few times of [0, T] (per slab length where delta_K depends on it, for the "
       "first two slab lengths met) and, where their interpolant of the lowest degree "
       "d <= 3 reproduces the matrices assembled at two further times to 1e-12 relative "
       "(d + 3 assemblies; the matrices, SUPG terms included, polynomial in t of degree "
       "<= 3), build each slab operator from them (the d + 1 node matrices as its "
       "Kronecker terms) instead of assembling the temporal quadrature points' matrices; "
       "otherwise, and with false, every slab assembles its own."},
      {"solver", "reuse_factorization", "true", m(&S::reuse_factorization), boolean,
       "Reuse the LU factorization (or the preconditioner) while the slab matrix is "
       "unchanged (same tau, coefficients constant in time)."},
      {"solver", "direct", "umfpack", m(&S::direct_solver), by_name,
       "Sparse direct solver of the slab systems (solver.type = direct or auto, and "
       "the fallback): umfpack (SuiteSparse, one process) or mumps (MUMPS, on all MPI "
       "ranks of the run; the factors are distributed over the ranks). Both factorize "
       "once per slab matrix and reuse the factors; results agree to round-off."},
      {"solver", "refinement_steps", "0", m(&S::refinement_steps), integer(0, 10),
       "Direct solves: iterative refinement steps per solve (UMFPACK's own "
       "default is 2). Each step costs a residual and a further solve; on the slab "
       "systems the solution changes only in the last digits (doc/results.md)."},
      {"solver", "auto_threshold", "0", m(&S::auto_threshold), real(0.),
       "solver.type = auto with a factorization per slab (coefficients that depend on "
       "time, or no reuse): iterative if also N_space (r+1)^2 (slab unknowns times the "
       "temporal block size, which UMFPACK's cost follows) reaches this; 0 = by the "
       "spatial degree of the system: 2e4 (Q1), 3e5 (Q2), 1e6 (Q3), 3e6 (Q4 and up), "
       "where the Krylov solver's factorization-plus-solve time per slab overtakes "
       "UMFPACK's (doc/results.md)."},
      {"solver", "auto_memory_mb", "0", m(&S::auto_memory_mb), real(0.),
       "solver.type = auto: the largest predicted UMFPACK factorization peak (MB) solved "
       "directly (extrapolated from the last measured factorization of the same degree "
       "and r in the run, else from a fit: about 1 kB per unknown for dG(0), 2 kB for "
       "dG(2)); 0 = half the physical memory. The budget covers UMFPACK's own peak only, "
       "not the slab matrix or the stored solutions."},
      {"solver", "krylov", "gmres", k(&I::krylov), by_name,
       "Iterative solver: gmres (restarted, right preconditioned), fgmres (flexible) or "
       "bicgstab (Belos). gmres with preconditioner = modes runs on deal.II's GMRES "
       "(no Trilinos: the DWR loop's primal and adjoint then march concurrently, "
       "adaptivity.concurrent_marches)."},
      {"solver", "preconditioner", "kronecker_presb", k(&I::preconditioner), by_name,
       "Preconditioner (Ifpack2 unless noted): ilut / riluk = ILUT / ILU(k) of the whole "
       "slab matrix; block_jacobi / block_gauss_seidel = one sweep of block relaxation "
       "with the (r+1)x(r+1) temporal blocks; block_ilu = block ILU(k) (RBILUK) with "
       "those blocks; kronecker = real Schur decomposition of (tau Mhat)^{-1} D "
       "decoupling "
       "the temporal modes, ILU(k) of each shifted spatial matrix, PRESB for complex "
       "pairs (coefficients frozen at the slab midpoint if they depend on t); modes = "
       "the exact temporal-mode solve (solver.type = modes: one UMFPACK LU per mode) of "
       "the slab operator with its coefficients frozen at the slab's middle, reused over "
       "the following slabs until a solve needs more than solver.refactor_iterations "
       "iterations (for coefficients constant in time it is exact: one iteration); none."},
      {"solver", "refactor_iterations", "10", k(&I::refactor_iterations),
       integer(0, 1000000),
       "preconditioner = modes: refactorize the frozen operator (at the next slab's "
       "middle) once a Krylov solve has needed more than this many iterations; 0 "
       "refactorizes on every slab."},
      {"solver", "tolerance", "1e-10", k(&I::tolerance), real(0.),
       "Krylov stopping rule: ||b - K x|| <= tolerance ||b|| (true residual checked)."},
      {"solver", "restart", "30", k(&I::restart), integer(1, 10000),
       "GMRES restart length (Krylov vectors kept)."},
      {"solver", "max_iterations", "500", k(&I::max_iterations), integer(1, 1000000),
       "Krylov iterations per slab solve before it counts as failed."},
      {"solver", "ilu_fill", "2", k(&I::ilu_fill), real(0., 10.),
       "ILU(k) level k (riluk, block_ilu, kronecker; rounded) or ILUT fill ratio "
       "(ilut, >= 1); at most 10 (for ILU(k) Ifpack2 reserves 2^k times the entries of "
       "each matrix row in advance).",
       "a number with 0 <= v <= 10"},
      {"solver", "spatial_preconditioner", "ilu", k(&I::spatial_preconditioner), by_name,
       "Inner solver of the kronecker and kronecker_presb preconditioners for each "
       "temporal mode's spatial matrix (lambda M + A; the 2n x 2n real form or the PRESB "
       "matrices of complex pairs): ilu = Ifpack2 ILU(k), k = solver.ilu_fill; amg = "
       "one V-cycle of ML smoothed aggregation for nonsymmetric matrices (NSSA, through "
       "deal.II's TrilinosWrappers::PreconditionAMG), smoother solver.amg_smoother."},
      {"solver", "amg_smoother", "ilu", k(&I::amg_smoother), by_name,
       "Smoother of solver.spatial_preconditioner = amg (one sweep per level): ilu "
       "(ILU(0)), gauss_seidel or chebyshev."},
      {"solver", "inner_iterations", "0", k(&I::inner_iterations), integer(0, 1000),
       "kronecker and kronecker_presb: 0 = each temporal mode block is approximated by "
       "one application of its spatial preconditioner; k > 0 = solved by at most k "
       "GMRES iterations right-preconditioned by it (complex pairs: on the 2n x 2n "
       "block, with PRESB as the preconditioner for kronecker_presb) to the relative "
       "residual solver.inner_tolerance. The outer solve then runs as flexible GMRES "
       "(solver.krylov gmres or fgmres; bicgstab is rejected). Makes the outer "
       "iteration count nearly independent of epsilon, r and the aspect ratio "
       "(doc/results.md)."},
      {"solver", "inner_tolerance", "1e-2", k(&I::inner_tolerance), real(0.),
       "Relative residual at which an inner GMRES (solver.inner_iterations > 0) stops."},
      {"solver", "stagnation_window", "50", k(&I::stagnation_window), integer(0, 1000000),
       "Stagnation detection: a Krylov solve whose residual has not fallen by "
       "solver.stagnation_factor over the last stagnation_window iterations stops and "
       "counts as failed (then solver.fallback applies); 0 = off. gmres/fgmres watch "
       "the implicit residual every iteration, bicgstab runs in chunks of this many "
       "iterations."},
      {"solver", "stagnation_factor", "10", k(&I::stagnation_factor), real(0.),
       "Stagnation detection: required residual reduction over "
       "solver.stagnation_window iterations; <= 1 = off."},
      {"solver", "fallback", "direct", m(&S::fallback), by_name,
       "On a failed Krylov solve: none = numerical error (exit code 3) naming loop, "
       "slab, "
       "solver and residual; direct = redo it with UMFPACK (kept for the remaining slabs "
       "with the same matrix) and count it in summary.json (solver_fallbacks)."},
  };
}
} // namespace anisodwr::config::table
