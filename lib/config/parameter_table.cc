#include "config/parameter_table.h"

namespace anisodwr::config
{
namespace
{
namespace P = dealii::Patterns;

std::vector<Entry> make_entries()
{
  auto integer = [](int lo, int hi) { return std::make_shared<P::Integer>(lo, hi); };
  auto real = [](double lo) { return std::make_shared<P::Double>(lo); };
  auto choice = [](const std::string &s) { return std::make_shared<P::Selection>(s); };
  auto boolean = std::make_shared<P::Bool>();
  auto text = std::make_shared<P::Anything>();
  return {
      {"scene", "name", "moving_hump", Kind::text,
       choice("moving_hump|manufactured|heat|boundary_layer|hemker"),
       "Benchmark scene (see SCENES.md): moving_hump, manufactured, heat, "
       "boundary_layer or hemker."},
      {"scene", "variant", "", Kind::text, text,
       "Scene variant. manufactured: constant (default), rotating (time-dependent b and "
       "alpha), poly_space (rotating coefficients, spatial part in Q2). heat: poly "
       "(default) or trig. moving_hump: none."},
      {"scene", "epsilon", "1e-6", Kind::real, real(0.),
       "Diffusion coefficient, 0 < eps <= 1e6 (the scenes are scaled to unit size and "
       "unit speed; larger values are rejected as meaningless).",
       "a number with 0 < v <= 1e6"},
      {"scene", "end_time", "0.5", Kind::real, real(0.),
       "Final time, 0 < T <= 1e6 (larger values are rejected as meaningless).",
       "a number with 0 < v <= 1e6"},
      {"discretization", "p", "1", Kind::integer, integer(1, 4),
       "Polynomial degree of FE_Q in space (1..4)."},
      {"discretization", "r", "0", Kind::integer, integer(0, 10),
       "Polynomial degree dG(r) in time (>= 0)."},
      {"discretization", "delta0", "1.0", Kind::real, real(0.),
       "SUPG parameter: delta_K = delta0 * |K|^(1/d); 0 turns SUPG off."},
      {"discretization", "supg_length", "volume", Kind::text, choice("volume|streamline"),
       "Cell length h_K in delta_K = delta0 h_K: volume = |K|^(1/d) (SPEC); streamline = "
       "the "
       "length of K along b at its centre (t = 0), for anisotropic cells across layers."},
      {"discretization", "supg_tau_factor", "1", Kind::real, real(0.),
       "Bound delta_K <= supg_tau_factor * tau_n on each slab (tau_n its length), the "
       "stability condition of SUPG whose test function also multiplies du/dt; 0 drops "
       "the bound (small slabs on strongly anisotropic meshes then blow up)."},
      {"discretization", "initial_refinements", "2", Kind::integer, integer(0, 14),
       "Global refinements of the scene's coarse mesh (unit square: 2 gives 4x4 cells)."},
      {"discretization", "n_slabs", "5", Kind::integer, integer(1, 1000000),
       "Number of equal time slabs."},
      {"solver", "type", "auto", Kind::text, choice("direct|iterative|auto"),
       "Slab solver: direct (UMFPACK), iterative (Belos Krylov method solver.krylov "
       "with solver.preconditioner, Trilinos), or auto: UMFPACK whenever UMFPACK's "
       "symbolic analysis of the slab matrix predicts a factorization peak within "
       "solver.auto_memory_mb, iterative otherwise; if the coefficients depend on time "
       "(a factorization per slab), iterative from N_space (r+1)^2 >= "
       "solver.auto_threshold. The choice and its reason are printed per loop."},
      {"solver", "dof_numbering", "native", Kind::text, choice("native|downstream"),
       "Spatial DoF order: native (deal.II's cell-wise order) or downstream (sorted along "
       "the convection b at the domain's centre; ILU and Gauss-Seidel then sweep with the "
       "flow, which keeps them effective on convection-dominated, anisotropic meshes). "
       "Direct solves are unaffected up to round-off."},
      {"solver", "reuse_factorization", "true", Kind::boolean, boolean,
       "Reuse the LU factorization (or the preconditioner) while the slab matrix is "
       "unchanged (same tau, coefficients constant in time)."},
      {"solver", "auto_threshold", "1e6", Kind::real, real(0.),
       "solver.type = auto with coefficients that depend on time (the factorization "
       "cannot be reused): iterative iff N_space (r+1)^2 (slab unknowns times the temporal "
       "block size, which UMFPACK's cost follows) reaches this."},
      {"solver", "auto_memory_mb", "0", Kind::real, real(0.),
       "solver.type = auto: the largest factorization peak (MB, as predicted by UMFPACK's "
       "symbolic analysis) for which UMFPACK is used; 0 = half the physical memory."},
      {"solver", "krylov", "gmres", Kind::text, choice("gmres|fgmres|bicgstab"),
       "Iterative solver: gmres (restarted, right preconditioned), fgmres (flexible) or "
       "bicgstab (Belos)."},
      {"solver", "preconditioner", "kronecker_presb", Kind::text,
       choice("none|ilut|riluk|block_jacobi|block_gauss_seidel|block_ilu|kronecker|"
              "kronecker_presb"),
       "Preconditioner (Ifpack2 unless noted): ilut / riluk = ILUT / ILU(k) of the whole "
       "slab matrix; block_jacobi / block_gauss_seidel = one sweep of block relaxation "
       "with the (r+1)x(r+1) temporal blocks; block_ilu = block ILU(k) (RBILUK) with "
       "those blocks; kronecker = real Schur decomposition of (tau Mhat)^{-1} D "
       "decoupling "
       "the temporal modes, ILU(k) of each shifted spatial matrix, PRESB for complex "
       "pairs (coefficients frozen at the slab midpoint if they depend on t); none."},
      {"solver", "tolerance", "1e-10", Kind::real, real(0.),
       "Krylov stopping rule: ||b - K x|| <= tolerance ||b|| (true residual checked)."},
      {"solver", "restart", "30", Kind::integer, integer(1, 10000),
       "GMRES restart length (Krylov vectors kept)."},
      {"solver", "max_iterations", "500", Kind::integer, integer(1, 1000000),
       "Krylov iterations per slab solve before it counts as failed."},
      {"solver", "ilu_fill", "1", Kind::real, real(0.),
       "ILU(k) level k (riluk, block_ilu, kronecker; rounded) or ILUT fill ratio "
       "(ilut, >= 1)."},
      {"solver", "spatial_preconditioner", "ilu", Kind::text, choice("ilu|amg"),
       "Inner solver of the kronecker and kronecker_presb preconditioners for each "
       "temporal mode's spatial matrix (lambda M + A; the 2n x 2n real form or the PRESB "
       "matrices of complex pairs): ilu = Ifpack2 ILU(k), k = solver.ilu_fill; amg = "
       "one V-cycle of ML smoothed aggregation for nonsymmetric matrices (NSSA, through "
       "deal.II's TrilinosWrappers::PreconditionAMG), smoother solver.amg_smoother."},
      {"solver", "amg_smoother", "ilu", Kind::text, choice("ilu|gauss_seidel|chebyshev"),
       "Smoother of solver.spatial_preconditioner = amg (one sweep per level): ilu "
       "(ILU(0)), gauss_seidel or chebyshev."},
      {"solver", "stagnation_window", "50", Kind::integer, integer(0, 1000000),
       "Stagnation detection: a Krylov solve whose residual has not fallen by "
       "solver.stagnation_factor over the last stagnation_window iterations stops and "
       "counts as failed (then solver.fallback applies); 0 = off. gmres/fgmres watch "
       "the implicit residual every iteration, bicgstab runs in chunks of this many "
       "iterations."},
      {"solver", "stagnation_factor", "10", Kind::real, real(0.),
       "Stagnation detection: required residual reduction over "
       "solver.stagnation_window iterations; <= 1 = off."},
      {"solver", "fallback", "direct", Kind::text, choice("none|direct"),
       "On a failed Krylov solve: none = numerical error (exit code 3) naming loop, "
       "slab, "
       "solver and residual; direct = redo it with UMFPACK (kept for the remaining slabs "
       "with the same matrix) and count it in summary.json (solver_fallbacks)."},
      {"study", "mode", "single", Kind::text, choice("single|convergence|dwr"),
       "single: one primal run; convergence: uniform refinement over study.levels "
       "levels; "
       "dwr: the adaptive DWR loop (section adaptivity, goals from section goal)."},
      {"study", "refine", "both", Kind::text, choice("space|time|both"),
       "Convergence study: refine h (space), tau (time) or both per level."},
      {"study", "levels", "4", Kind::integer, integer(1, 20),
       "Number of levels of a convergence study."},
      {"goal", "kind", "scene", Kind::text, choice("scene|point|mean"),
       "scene: the scene's goals (moving_hump: mollified u(x_e1,T), u(x_e2,T); "
       "boundary_layer: mean of u(T) over (0.5,1)x(0,1); others: u(0.5,0.5,T)); "
       "point: mollified point values at goal.locations; mean: means over the rectangles "
       "in goal.locations."},
      {"goal", "locations", "", Kind::text, text,
       "point: 'x,y; x,y; ...'; mean: 'x0,y0,x1,y1; ...' (lower-left, upper-right)."},
      {"goal", "over_time", "false", Kind::boolean, boolean,
       "Custom goals: integrate over I (true) or evaluate at T (false)."},
      {"goal", "radius", "0.01", Kind::real, real(0.),
       "Mollifier radius s of point goals; 0 = exact point evaluation (Dirac).",
       "a number >= 0 (and at most the diameter of the scene's domain)"},
      {"goal", "weights", "1", Kind::text, text,
       "Weights w_i of J_w = sum w_i J_i: one number for all goals, a comma list (one "
       "per "
       "goal), or auto (w_i = sign(J_i(I_2h u) - J_i(u_h)) / max(|J_i(u_h)|, 1e-12))."},
      {"adaptivity", "mode", "anisotropic", Kind::text,
       choice("anisotropic|isotropic|uniform"),
       "anisotropic: mark per direction by |eta_h,i|; isotropic: mark by |eta_h|, refine "
       "isotropically; uniform: refine every cell."},
      {"adaptivity", "marking", "cell", Kind::text, choice("joint|per_direction|cell"),
       "Anisotropic marking. joint: rank all (cell, direction) pairs by |eta_h,i^K| and "
       "mark the theta_h fraction of the pairs; per_direction: mark the theta_h fraction "
       "of cells in each direction separately (refines layer cells in every direction); "
       "cell: mark the theta_h fraction of cells by sum_i |eta_h,i^K| and cut each "
       "marked "
       "cell in direction i only where |eta_h,i^K| >= adaptivity.kappa * max_j "
       "|eta_h,j^K|."},
      {"adaptivity", "kappa", "0.75", Kind::real, real(0.),
       "marking = cell: a marked cell is cut in direction i iff |eta_h,i^K| >= kappa * "
       "its largest directional indicator, in [0,1] (1: the dominant direction only; 0: "
       "isotropic)."},
      {"adaptivity", "loops", "6", Kind::integer, integer(1, 1000),
       "Maximum number of DWR loops."},
      {"adaptivity", "theta_h", "0.25", Kind::real, real(0.),
       "Fraction of cells marked per direction (by count, largest indicators), in "
       "[0,1].",
       "a fraction in [0, 1]"},
      {"adaptivity", "theta_tau", "0.2", Kind::real, real(0.),
       "Fraction of slabs bisected (largest |eta_tau^n|), in [0,1]; 0 keeps the time "
       "mesh.",
       "a fraction in [0, 1]"},
      {"adaptivity", "theta_coarsen", "0", Kind::real, real(0.),
       "Fraction of cells (smallest |eta_h|) flagged for coarsening, in [0,1].",
       "a fraction in [0, 1]"},
      {"adaptivity", "tolerance", "0", Kind::real, real(0.),
       "Stop when |eta_tau_h| < tolerance (0: no tolerance)."},
      {"adaptivity", "max_dofs", "0", Kind::real, real(0.),
       "Stop before a loop whose N_tot would exceed this (0: no budget)."},
      {"adaptivity", "max_memory_mb", "0", Kind::real, real(0.),
       "Memory budget in MB (0: the physical memory). Before each DWR loop (and "
       "before a single run or convergence level) the peak memory is estimated from "
       "the DoFs of the primal and adjoint spaces, r, the number of slabs and the "
       "solver (DWR: scaled by the last loop's measured/estimated peak when that is "
       "above 1); a loop whose estimate exceeds the budget is not started: exit code "
       "2, summary.json status 'stopped'."},
      {"adaptivity", "max_wall_time", "0", Kind::real, real(0.),
       "Wall-time budget in seconds (0: none): no new loop starts when the time so far "
       "plus twice the last loop's time would exceed it."},
      {"adaptivity", "time_indicator", "average", Kind::text,
       choice("average|adjoint_residual|higher_order"),
       "Form of eta_tau. average: 1/2 rho(u)(E z - z) + 1/2 rho*(u,z)(E u - u); "
       "adjoint_residual: rho*(u,z)(E u - u), exact up to the reconstruction of the "
       "primal alone; use it when the adjoint is not resolved in time (point goals at T "
       "with |b| tau >> goal.radius, see doc/results.md); higher_order: rho*(u,z)(u' - "
       "u) "
       "with u' the primal solved once more in dG(r+1) (one more primal solve per loop), "
       "which does not rely on dG(r)'s nodal superconvergence and sees the temporal "
       "error "
       "at T."},
      {"adaptivity", "per_goal_estimates", "false", Kind::boolean, boolean,
       "Also solve one adjoint per goal and report each goal's own eta_tau h and I_eff "
       "(loops.csv: eta_<goal>, I_eff_<goal>), so that cancellation between goals in the "
       "combined estimate is visible; costs one adjoint solve and estimate per goal."},
      {"adaptivity", "measure_time_error", "false", Kind::boolean, boolean,
       "Diagnostic: on every loop solve the primal again with the slabs bisected once "
       "and twice and report the extrapolated temporal goal error on the loop's spatial "
       "mesh (loops.csv: err_tau, err_tau_order) next to eta_tau; costs ~6 primal "
       "solves."},
      {"adaptivity", "adjoint_degree", "0", Kind::integer, integer(0, 8),
       "Polynomial degree q of the adjoint; 0 means q = 2p."},
      {"adaptivity", "space_indicator", "average", Kind::text,
       choice("average|primal_residual"),
       "Form of eta_h,i. average: 1/2 rho(u)(z - R_i z) + 1/2 rho*(u, R_h z)(I_2h,i u - "
       "u) + SUPG terms (SPEC; where a cell has no directional lift only the primal "
       "half); primal_residual: rho(u)(z - R_i z) + S(u)(R_h z), the primal residual "
       "alone, which needs no lift of u."},
      {"adaptivity", "adjoint_stabilization", "transposed", Kind::text,
       choice("transposed|none"),
       "transposed: the adjoint is the transpose of the SUPG-stabilized primal operator "
       "in degree q (SPEC); none: the adjoint is the Galerkin (delta = 0) discretization "
       "of the continuous adjoint, consistent with it; the estimator's S terms still use "
       "the primal's delta_K."},
      {"output", "directory", "results/moving_hump", Kind::text, text,
       "Output directory (created if missing); --output overrides it."},
      {"output", "vtu_every", "1", Kind::integer, integer(0, 1000000),
       "Write VTU of u(t_n^-) every k-th slab (and at T); 0 writes none."},
      {"output", "progress", "true", Kind::boolean, boolean,
       "Print one progress line per slab to stdout."},
      {"output", "vtu_loops", "1", Kind::integer, integer(0, 1000000),
       "DWR: write VTU (mesh, u(T), indicators, aspect ratio) every k-th loop and at the "
       "last loop; 0 writes none."},
  };
}
} // namespace

const std::vector<Entry> &entries()
{
  static const std::vector<Entry> table = make_entries();
  return table;
}
} // namespace anisodwr::config
