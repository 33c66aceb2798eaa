// The parameter table: the keys of section adaptivity (see parameter_table.cc for the entry format).
#include "config/table_binding.h"

namespace anisodwr::config::table
{
std::vector<Entry> adaptivity_entries()
{
  using S = AdaptivitySection;
  const auto m = [](auto member) { return at(&Parameters::adaptivity, member); };
  return {
      {"adaptivity", "mode", "anisotropic", m(&S::mode), by_name,
       "anisotropic: mark per direction by |eta_h,i|; isotropic: mark by |eta_h|, refine "
       "isotropically; uniform: refine every cell."},
      {"adaptivity", "marking", "joint", m(&S::marking), by_name,
       "Anisotropic marking. joint: rank all (cell, direction) pairs by |eta_h,i^K| and "
       "mark the theta_h fraction of the pairs; per_direction: mark the theta_h fraction "
       "of cells in each direction separately (refines layer cells in every direction); "
       "cell: mark the theta_h fraction of cells by sum_i |eta_h,i^K| and cut each "
       "marked "
       "cell in direction i only where |eta_h,i^K| >= adaptivity.kappa * max_j "
       "|eta_h,j^K|."},
      {"adaptivity", "marking_criterion", "count", m(&S::marking_criterion), by_name,
       "How many cells (joint: pairs) theta_h selects. count: the theta_h fraction of "
       "them, largest indicators first; bulk: the fewest largest ones whose indicators "
       "sum to theta_h of the total (Doerfler; few cells where the error is "
       "concentrated). Cells, pairs or directions as adaptivity.marking ranks them; "
       "the coarsening and theta_tau stay by count."},
      {"adaptivity", "kappa", "0.75", m(&S::kappa), real(0., 1.),
       "marking = cell: a marked cell is cut in direction i iff |eta_h,i^K| >= kappa * "
       "its largest directional indicator, in [0,1] (1: the dominant direction only; 0: "
       "isotropic).",
       "a fraction in [0, 1]", Check::fraction},
      {"adaptivity", "loops", "6", m(&S::loops), integer(1, 1000),
       "Maximum number of DWR loops."},
      {"adaptivity", "theta_h", "0.25", m(&S::theta_h), real(0.),
       "Fraction of cells marked (adaptivity.marking says of which ranking; "
       "adaptivity.marking_criterion whether of their count or of the indicators' "
       "sum), in [0,1].",
       "a fraction in [0, 1]", Check::fraction},
      {"adaptivity", "theta_tau", "1", m(&S::theta_tau), real(0.),
       "Fraction of slabs bisected (largest |eta_tau^n|) in a loop that refines time "
       "(adaptivity.time_balance), in [0,1]; 0 keeps the time mesh. Default 1: a moving "
       "feature needs every slab refined, and time_balance already keeps time "
       "refinement to the loops where eta_tau is not small.",
       "a fraction in [0, 1]", Check::fraction},
      {"adaptivity", "time_balance", "0.5", m(&S::time_balance), real(0.),
       "Balance of time and space refinement, b: a loop bisects slabs (theta_tau) if "
       "|eta_tau| >= b (|eta_h,x| + |eta_h,y|) and refines cells if |eta_h,x| + "
       "|eta_h,y| >= b |eta_tau| (or if it bisects no slab), with the shares of eta_abs "
       "(per goal, weighted by |w_i|, where each goal has its own estimate). So time is "
       "refined where eta_tau dominates, space where eta_h does, both where they are "
       "within a factor 1/b; 0: both in every loop."},
      {"adaptivity", "theta_coarsen", "0", m(&S::theta_coarsen), real(0.),
       "Fraction of cells (smallest |eta_h|) flagged for coarsening, in [0,1].",
       "a fraction in [0, 1]", Check::fraction},
      {"adaptivity", "tolerance", "0", m(&S::tolerance), real(0.),
       "Stop when the estimate named by adaptivity.tolerance_measure is below tolerance "
       "and the corrected goal values have settled (adaptivity.tolerance_drift; 0: no "
       "tolerance). It bounds the error of the combined goal J_w = sum_i w_i J_i "
       "within the effectivity band (doc/results.md, 'Error control without tuning'): "
       "absolute in J_w's units for numeric goal.weights, relative for goal.weights = "
       "estimate (the default) or auto (w_i = +-1/|J_i(u_h)|: the sum over the goals of "
       "their relative errors; with estimate each goal's error relative to the larger of "
       "|J_i(u_h)| and 1% of |J_i(1)| max|u_h|)."},
      {"adaptivity", "tolerance_measure", "parts", m(&S::tolerance_measure), by_name,
       "What adaptivity.tolerance bounds. eta: |eta_tau_h|, the signed sum of all "
       "indicators; parts: |eta_h,x| + |eta_h,y| + |eta_tau| without signs, and with one "
       "estimate per goal (per_goal_estimates, goal.weights = estimate) the sum over the "
       "goals of |w_i| times each goal's parts (loops.csv eta_abs). The signed parts "
       "cancel on coarse meshes (doc/results.md), so eta can stop a run whose error is "
       "many times the tolerance; parts is never below eta. goals: max_i |w_i eta_i|, the "
       "largest of the goals' own signed estimates (one adjoint per goal, as with "
       "per_goal_estimates), with goal.weights = auto or estimate the largest relative "
       "error of a single goal: the goals cannot cancel each other, a goal's space and "
       "time parts can (config/hemker.json, doc/configs.md#hemker)."},
      {"adaptivity", "tolerance_drift", "1", m(&S::tolerance_drift), real(0.),
       "The tolerance stop's second condition: the goals' corrected values J_i(u_h) + "
       "eta_i (J_w + eta_tau h without estimates per goal) may have moved since the "
       "previous loop by at most tolerance_drift * tolerance, summed over the goals "
       "with weights |w_i| (loops.csv eta_drift). If both loops' estimates were exact "
       "the corrected values would agree; a drift above the tolerance says that one of "
       "them missed the error by more than the tolerance (an adjoint that does not yet "
       "resolve its goal, a pre-asymptotic mesh), so the loop goes on. 0: not checked "
       "(the estimate alone stops the run). Loop 1 never stops by the tolerance; not "
       "checked where the weights changed and the goals have no estimates of their "
       "own (goal.weights = auto with tolerance_measure = parts or eta: the weighted "
       "goals of two loops differ; eta_drift empty)."},
      {"adaptivity", "max_dofs", "0", m(&S::max_dofs), real(0.),
       "Stop before a loop whose N_tot would exceed this (0: no budget)."},
      {"adaptivity", "max_memory_mb", "0", m(&S::max_memory_mb), real(0.),
       "Memory budget in MB (0: the physical memory). Before each DWR loop (and "
       "before a single run or convergence level) the peak memory is estimated from "
       "the DoFs of the primal and adjoint spaces, r, the number of slabs and the "
       "solver (DWR: scaled by the last loop's measured/estimated peak when that is "
       "above 1); a loop whose estimate exceeds the budget is not started: exit code "
       "2, summary.json status 'stopped'."},
      {"adaptivity", "max_wall_time", "0", m(&S::max_wall_time), real(0.),
       "Wall-time budget in seconds (0: none): no new loop starts when the time so far "
       "plus twice the last loop's time would exceed it."},
      {"adaptivity", "time_indicator", "higher_order", m(&S::time_indicator), by_name,
       "Form of eta_tau. average: 1/2 rho(u)(E z - z) + 1/2 rho*(u,z)(E u - u); "
       "adjoint_residual: rho*(u,z)(E u - u), exact up to the reconstruction of the "
       "primal alone; use it when the adjoint is not resolved in time (point goals at T "
       "with |b| tau >> goal.radius, see doc/results.md); higher_order: rho*(u,z)(u' - "
       "u) "
       "with u' the primal solved once more in dG(r+1) (one more primal solve per loop), "
       "which does not rely on dG(r)'s nodal superconvergence and sees the temporal "
       "error "
       "at T."},
      {"adaptivity", "per_goal_estimates", "false", m(&S::per_goal_estimates), boolean,
       "Solve one adjoint per goal (one factorization serves them all) and report each "
       "goal's own eta_tau h and I_eff (loops.csv: eta_<goal>, I_eff_<goal>), so that "
       "cancellation between goals in the combined estimate is visible. The combined "
       "indicators are then the weighted sum of the goals' own; costs one adjoint solve "
       "per goal and each goal's own terms in the estimator (one pass over the cells: "
       "the terms of u_h alone are formed once for all goals)."},
      {"adaptivity", "goal_estimate", "dwr", m(&S::goal_estimate), by_name,
       "Each goal's own estimate (loops.csv eta_<goal>, I_eff_<goal>; the tolerance "
       "measures goals and parts and the drift use it). dwr: the goal's DWR indicators "
       "summed; enriched: J_i(u_q) - J_i(u_h) + eta_tau,i, u_q the primal solved once "
       "more in the adjoint's degree q on the loop's mesh and slabs with the same "
       "stabilization, delta_K within the inverse bound where adjoint_inverse_bound is "
       "on (loops.csv J_hi_<goal>; one more primal march per loop: with "
       "concurrent_marches in the primal thread beside the adjoints, else after the "
       "adjoint's factors are freed; where it fails, e.g. grows, a warning and that loop keeps "
       "the DWR's estimates). Without stabilization the two agree; with SUPG the DWR "
       "sum carries the mismatch of the primal's and the adjoint's stabilization, the "
       "enriched estimate needs the primal of degree q to be much closer to u than "
       "u_h is (doc/results.md, 'Goal estimates from the enriched primal': better on "
       "Hemker, worse where the layer is unresolved and the goal smooth). consistent: the "
       "same with u_q solving the adjoint's own slab operator (degree q, the adjoint's "
       "stabilization and boundary faces) untransposed, with the adjoint's factorization "
       "(no factorization of its own): J_i(u_q) - J_i(u_h) is then the residual of u_h "
       "in the adjoint's stabilized form of degree q weighted by z_i, the DWR identity "
       "without the interpolant and without the two stabilizations' mismatch. With "
       "concurrent_marches the primal thread marches u_q beside the adjoints' solves "
       "once the adjoint is factorized, where one factorization serves every slab "
       "(coefficients constant in time, slabs of one length; time in t_primal), else "
       "the adjoint's thread after its solves (time in t_adjoint) (doc/results.md, 'Goal "
       "estimates from the enriched primal'). Both leave out of u_q a crosswind term "
       "that no solution switches (s_K = 1 on every cell: crosswind_form = linear, or "
       "the first loop of residual), an O(h) inconsistent diffusion whose error u_q "
       "would share; consistent then solves the adjoint's operator without it by a "
       "factorization of its own (doc/method.md §8). both: enriched's and consistent's u_q "
       "on the same loop, each goal's estimate the larger in size of the two (loops.csv "
       "J_hi_<goal> the u_q it took): two references stabilized differently, so that "
       "a pre-asymptotic loop that one of them does not see still has its error "
       "estimated; costs enriched's march besides consistent's. All but dwr imply "
       "per_goal_estimates; the DWR indicators still mark the cells and the combined "
       "columns eta_h, I_eff stay theirs."},
      {"adaptivity", "concurrent_marches", "true", m(&S::concurrent_marches), boolean,
       "March the adjoint(s) in a second thread while the primal marches (with "
       "goal.weights = auto and one adjoint for the weighted goal: assemble and "
       "factorize the adjoint's slab operator there, and march once the primal has "
       "given the weights), when one MPI rank "
       "and more than one thread run, both slab systems are predicted to be solved without "
       "Trilinos (UMFPACK, or GMRES preconditioned by a frozen operator's modes, which "
       "runs on deal.II's GMRES), "
       "and the loop's memory estimate with both factorizations held at once fits the "
       "memory limit; otherwise (and with false) the primal, then the adjoint. The "
       "results are the same either way (with the frozen modes' GMRES up to round-off: "
       "UMFPACK's BLAS runs on one thread then); t_primal and t_adjoint then overlap."},
      {"adaptivity", "measure_time_error", "false", m(&S::measure_time_error), boolean,
       "Diagnostic: on every loop solve the primal on the loop's spatial mesh with its "
       "slabs, bisected once and bisected twice, all with the SUPG parameters of the "
       "finest (delta_K <= supg_tau_factor * tau_n / 4), and report the extrapolated "
       "temporal goal error next to eta_tau (loops.csv: err_tau, err_tau_order; "
       "err_time_<goal> per goal); costs 7 primal solves per slab."},
      {"adaptivity", "adjoint_degree", "0", m(&S::adjoint_degree), integer(0, 8),
       "Polynomial degree q of the adjoint; 0 (the default) means q = p + 1 (doc/results.md, "
       "'Error control without tuning')."},
      {"adaptivity", "space_indicator", "primal_residual", m(&S::space_indicator), by_name,
       "Form of eta_h,i. average: 1/2 rho(u)(z - R_i z) + 1/2 rho*(u, R_h z)(I_2h,i u - "
       "u) + SUPG terms (doc/method.md §8; where a cell has no directional lift only the primal "
       "half); primal_residual: rho(u)(z - R_i z) + S(u)(R_h z), the primal residual "
       "alone, which needs no lift of u (the default: doc/results.md, 'Error control "
       "without tuning'). Both carry the Dirichlet data's share -int eps (g_tau - u_h) d_n z "
       "on Gamma_D, g_tau interpolating g at the slab's temporal nodes (loops.csv "
       "eta_h_data)."},
      {"adaptivity", "adjoint_stabilization", "transposed", m(&S::adjoint_stabilization),
       by_name,
       "transposed: the adjoint is the transpose of the SUPG-stabilized primal operator "
       "in degree q (doc/method.md §5); none: the adjoint is the Galerkin (delta = 0) discretization "
       "of the continuous adjoint, consistent with it; the estimator's S terms still use "
       "the primal's delta_K."},
      {"adaptivity", "adjoint_outflow", "goals", m(&S::adjoint_outflow), by_name,
       "The adjoint's condition on the outflow part of the Dirichlet boundary (b.n > 0 at "
       "the face's centre at t = 0, T/2 and T), the adjoint's inflow boundary. goals (the "
       "default): where a goal's support (a point goal's disk, a mean goal's rectangle) is "
       "at the wall (within its own extent across it), meets a wall cell and is thinner "
       "across the wall than that cell, the face's DoFs are free and the weak form imposes "
       "eps d_n z + (b.n) z = 0 (z = O(eps)): the goal's mass then reaches the wall's DoFs "
       "and the estimate sees the error of the layer the cell smears (I_eff 0.06 -> 0.72 "
       "on boundary_layer's strip goal at loop 1); once the cells there are thinner than "
       "the support, and everywhere else, z = 0 as with dirichlet, which imposes it on "
       "every Dirichlet DoF. The estimator's R_h z vanishes on Gamma_D either way "
       "(doc/method.md §5, doc/results.md 'Goals inside an outflow layer')."},
      {"adaptivity", "adjoint_delta0", "0.1", m(&S::adjoint_delta0), real(-1.),
       "delta0 of the transposed SUPG adjoint (adjoint_stabilization = transposed), "
       "delta_K = adjoint_delta0 |K|^(1/d) within adjoint_inverse_bound (the default 0.1: "
       "doc/results.md, 'Error control without tuning'), at most discretization.delta0 "
       "(a Galerkin primal has a Galerkin adjoint); negative (-1): discretization.delta0. "
       "The estimator's S terms always use the primal's delta_K."},
      {"adaptivity", "adjoint_inverse_bound", "true", m(&S::adjoint_inverse_bound), boolean,
       "Bound the transposed SUPG adjoint's delta_K <= h_min,K^2 / (eps q^4) (h_min,K the "
       "shortest vertex distance of K): the inverse estimate's bound that keeps the SUPG "
       "term's eps Lap part below the diffusion. Without it the adjoint of degree q = 4 "
       "grows without bound on thin cells (doc/results.md, 'Error control without "
       "tuning'); false: delta_K = adjoint_delta0 h_K alone."},
      {"adaptivity", "adjoint_crosswind", "true", m(&S::adjoint_crosswind), boolean,
       "The adjoint carries the primal's crosswind term (discretization.crosswind0 > 0, in "
       "its form and with its switch). The term is not consistent: on the adjoint it "
       "spreads a goal's streak across b by about |b| h_perp / 2 (the first loop's switch "
       "is 1), and the estimate then weights the residual with the spread adjoint; false: "
       "the adjoint has SUPG alone (the estimate still carries the primal's term in S). "
       "No effect without the crosswind term."},
      {"adaptivity", "bound_refinement", "0", m(&S::bound_refinement), real(0.),
       "Refinement where u_h leaves its bounds (probes.csv's u_min, u_max: the scene's, "
       "the exact solution's or the data's by the maximum principle): a cell with a "
       "nodal value at a slab end outside [u_min - f R, u_max + f R] (f this value, R = "
       "u_max - u_min) that is at least 10 times longer along b than across is also "
       "halved along b, beside the marking (loops.csv `bound_cuts`). SUPG oscillates on "
       "such cells where the solution changes along the flow (Hemker: the top of the "
       "circle, doc/results.md). 0: off; no effect without bounds."},
      {"adaptivity", "data_rule_copies", "3", m(&S::data_rule_copies), integer(1, 8),
       "The estimator integrates f (where the scene's f is separable in x and t, as the "
       "built-in scenes' are) and u_0 (coefficients constant in time) by QGauss(deg W + 2) "
       "iterated this many times per direction (once per cell, so it costs little); other "
       "loads on QGauss(deg W + 2). The primal integrates its data by QGauss(p + 2): its "
       "quadrature error is part of the error the estimate must see (doc/method.md §6)."},
      {"adaptivity", "data_quadrature_error", "true", m(&S::data_quadrature_error), boolean,
       "eta_h carries the primal's quadrature error in f and u_0: (f, R_h z + delta b.grad "
       "R_h z) on the estimator's rule minus the same on the primal's QGauss(p + 2) "
       "(loops.csv eta_h_quad). Without it the estimate misses errors of the primal's load "
       "where f varies within a cell (the moving hump's front: doc/results.md, 'Error "
       "control without tuning')."},
      {"adaptivity", "conforming_weights", "true", m(&S::conforming_weights), boolean,
       "At hanging nodes the spatial weights z - I_h z use the conforming interpolant of "
       "the primal space (the hanging-node constraint's value), so that Galerkin "
       "orthogonality holds and eta_h is exact up to the adjoint's own error; the defect's "
       "part stays on the fine cell, in the direction along the coarse face (doc/method.md "
       "§7). false: the cell-wise interpolant R_h z, discontinuous at hanging nodes (the "
       "shipped moving-hump and Hemker configs keep it for their documented runs: "
       "doc/configs.md)."},
  };
}
} // namespace anisodwr::config::table
