#include "config/parameter_table.h"

#include "base/parse_number.h"
#include "goal/goal_type.h"
#include "scene/scene_registry.h"

#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace anisodwr::config
{
namespace
{
namespace P = dealii::Patterns;

/// The member of Parameters that `ref` (a generic callable: Parameters & -> T &, also
/// for const) refers to, read from and printed to text (numbers as in to_json: 17
/// significant digits; enums by their names).
template <class T, class Ref> Binding bind(Ref ref)
{
  Binding b;
  b.set = [ref](Parameters &p, const std::string &v)
  {
    T &x = ref(p);
    if constexpr (std::is_same_v<T, double>)
    {
      if (parse_double(v, x) != NumberStatus::ok)
        throw std::logic_error("'" + v +
                               "' is not a finite double (checked by the reader)");
    }
    else if constexpr (std::is_same_v<T, unsigned int>)
      x = std::stoul(v);
    else if constexpr (std::is_same_v<T, bool>)
      x = v == "true" || v == "True" || v == "yes";
    else if constexpr (std::is_same_v<T, std::string>)
      x = v;
    else if (const auto e = parse_choice<T>(v))
      x = *e;
    else
      throw std::logic_error("no name '" + v + "' in the table of an enum");
  };
  b.get = [ref](const Parameters &p) -> std::string
  {
    const T &x = ref(p);
    if constexpr (std::is_same_v<T, double>)
    {
      std::ostringstream s;
      s.precision(17);
      s << x;
      return s.str();
    }
    else if constexpr (std::is_same_v<T, unsigned int>)
      return std::to_string(x);
    else if constexpr (std::is_same_v<T, bool>)
      return x ? "true" : "false";
    else if constexpr (std::is_same_v<T, std::string>)
      return x;
    else
      return name(x);
  };
  if constexpr (std::is_same_v<T, double>)
    b.kind = Kind::real;
  else if constexpr (std::is_same_v<T, unsigned int>)
    b.kind = Kind::integer;
  else if constexpr (std::is_same_v<T, bool>)
    b.kind = Kind::boolean;
  else
    b.kind = Kind::text;
  if constexpr (std::is_enum_v<T>)
    b.choices = std::make_shared<P::Selection>(choice_list<T>("|"));
  return b;
}

/// The member `member` of the section `section` (a member of the section's struct or
/// of one of its bases).
template <class Section, class Base, class T>
Binding at(Section Parameters::*section, T Base::*member)
{
  return bind<T>([section, member](auto &p) -> auto & { return p.*section.*member; });
}

/// The member `member` of the sub-struct `sub` of the section `section`.
template <class Section, class Base, class Sub, class T>
Binding at(Section Parameters::*section, Sub Base::*sub, T Sub::*member)
{
  return bind<T>([section, sub, member](auto &p) -> auto &
                 { return (p.*section.*sub).*member; });
}

std::shared_ptr<PatternBase> integer(int lo, int hi)
{
  return std::make_shared<P::Integer>(lo, hi);
}
std::shared_ptr<PatternBase> real(double lo)
{
  return std::make_shared<P::Double>(lo);
}
std::shared_ptr<PatternBase> real(double lo, double hi)
{
  return std::make_shared<P::Double>(lo, hi);
}
const std::shared_ptr<PatternBase> boolean = std::make_shared<P::Bool>();
const std::shared_ptr<PatternBase> text = std::make_shared<P::Anything>();
/// the pattern of an enum member: the Selection of its names (Binding::choices)
const std::shared_ptr<PatternBase> by_name = nullptr;

// One function per section; each entry: section, key, default (as printed by
// `anisodwr defaults`), member, pattern (by_name for an enum), documentation,
// and optionally the range in words and a check of the typed value.

std::vector<Entry> scene_entries()
{
  using S = SceneSection;
  using C = CustomSceneOptions;
  const auto m = [](auto member) { return at(&Parameters::scene, member); };
  const auto c = [](auto member) { return at(&Parameters::scene, &S::custom, member); };
  return {
      {"scene", "name", "moving_hump", m(&S::name),
       std::make_shared<P::Selection>(scene_names("|")), scene_key_doc()},
      {"scene", "variant", "", m(&S::variant), text,
       "Scene variant. manufactured: constant (default), rotating (time-dependent b and "
       "alpha), poly_space (rotating coefficients, spatial part in Q2). heat: poly "
       "(default) or trig. moving_hump: none."},
      {"scene", "epsilon", "1e-6", m(&S::epsilon), real(0.),
       "Diffusion coefficient, 0 < eps <= 1e6 (the scenes are scaled to unit size and "
       "unit speed; larger values are rejected as meaningless).",
       "a number with 0 < v <= 1e6", Check::bounded_positive},
      {"scene", "end_time", "0.5", m(&S::end_time), real(0.),
       "Final time, 0 < T <= 1e6 (larger values are rejected as meaningless).",
       "a number with 0 < v <= 1e6", Check::bounded_positive},
      // the custom scene (scene.name = custom; ignored by the other scenes)
      {"scene", "constants", "", c(&C::constants), text,
       "custom: named constants of the expressions, 'name = value, ...'; a value is an "
       "expression in the constants before it, eps (scene.epsilon) and pi."},
      {"scene", "grid", "hyper_cube", c(&C::grid), text,
       "custom: the domain from a deal.II GridGenerator function by name (hyper_cube, "
       "hyper_rectangle, subdivided_hyper_rectangle, hyper_shell, channel_with_cylinder, "
       "plate_with_a_hole, ...), with the arguments scene.grid_arguments; its boundary ids "
       "are the generator's (colorize = true numbers the sides)."},
      {"scene", "grid_arguments", "0 : 1 : true", c(&C::grid_arguments), text,
       "custom: the arguments of scene.grid after the triangulation, separated by ':', "
       "points as 'x, y' (e.g. hyper_rectangle: '0, 0 : 2, 1 : true')."},
      {"scene", "mesh_file", "", c(&C::mesh_file), text,
       "custom: a Gmsh .msh file of quadrilaterals (ASCII, format 2 or 4) as the domain, "
       "instead of scene.grid; the physical tags of its lines are the boundary ids. A "
       "relative path is relative to the config file's directory (to the working "
       "directory with --set)."},
      {"scene", "manifolds", "", c(&C::manifolds), text,
       "custom with scene.mesh_file: the curved parts of the mesh, which a .msh file "
       "cannot carry, so that refinement follows them: 'boundary ids: polar x, y' (faces "
       "on a circle about (x, y)), 'cells ids: polar x, y' or 'cells ids: transfinite' "
       "(cells by material id, the physical tag of a quadrilateral: transfinite "
       "interpolation from their curved faces), separated by ';'. Empty: all flat."},
      {"scene", "convection", "0; 0", c(&C::convection), text,
       "custom: b = (b_x; b_y), two expressions in x, y, t separated by ';'. The "
       "coefficients depend on time if t appears in b or alpha."},
      {"scene", "reaction", "0", c(&C::reaction), text,
       "custom: alpha, an expression in x, y, t."},
      {"scene", "rhs", "0", c(&C::rhs), text, "custom: f, an expression in x, y, t."},
      {"scene", "initial_value", "0", c(&C::initial_value), text,
       "custom: u_0, an expression in x, y (t = 0)."},
      {"scene", "dirichlet", "0, 1, 2, 3: 0", c(&C::dirichlet), text,
       "custom: Dirichlet data u = g_D by boundary id, 'ids: expression; ...' with "
       "comma-separated ids and expressions in x, y, t. Every boundary id of the domain "
       "is in scene.dirichlet or scene.neumann."},
      {"scene", "neumann", "", c(&C::neumann), text,
       "custom: Neumann data eps grad u.n = g_N by boundary id, 'ids: expression; ...', "
       "expressions in x, y, t and the outward normal nx, ny."},
      {"scene", "exact_solution", "", c(&C::exact_solution), text,
       "custom: the exact solution u(x, y, t) if known (empty: none): then J_exact, the "
       "error norms and I_eff are computed, and f, u_0 and the boundary data are checked "
       "against u at sample points (scene.check_tolerance)."},
      {"scene", "goals", "", c(&C::goals), text,
       "custom: the scene's goals (goal.kind = scene), '[name =] kind numbers' separated "
       "by ';', a kind of goal.kind with its numbers as in goal.locations (e.g. 'u_mid = "
       "point 0.5, 0.5; heat = flux 4'; names default to point_1, mean_2, ...); empty: "
       "the value at the centre of the bounding box at T."},
      {"scene", "goals_over_time", "false", c(&C::goals_over_time), boolean,
       "custom: scene.goals are integrals over (0, T) (true) or values at T (false)."},
      {"scene", "check_tolerance", "1e-6", c(&C::check_tolerance), real(0.),
       "custom with scene.exact_solution: largest accepted mismatch of the data, relative "
       "to the largest sum of |terms| of the PDE (f), max|u| (u_0, g_D) or max|eps grad "
       "u.n| (g_N) over the sample points; the PDE residual uses difference quotients of "
       "u."},
  };
}

std::vector<Entry> discretization_entries()
{
  using S = DiscretizationSection;
  const auto m = [](auto member) { return at(&Parameters::discretization, member); };
  return {
      {"discretization", "p", "1", m(&S::p), integer(1, 4),
       "Polynomial degree of FE_Q in space (1..4)."},
      {"discretization", "r", "0", m(&S::r), integer(0, 10),
       "Polynomial degree dG(r) in time (>= 0)."},
      {"discretization", "delta0", "1.0", m(&S::delta0), real(0.),
       "SUPG parameter: delta_K = delta0 * |K|^(1/d); 0 turns SUPG off."},
      {"discretization", "supg_length", "volume", m(&S::supg_length), by_name,
       "Cell length h_K in delta_K = delta0 h_K: volume = |K|^(1/d) (doc/method.md §3); streamline = "
       "the "
       "length of K along b at its centre (t = 0), for anisotropic cells across layers."},
      {"discretization", "crosswind0", "0", m(&S::crosswind0), real(0.),
       "Crosswind diffusion beside SUPG: eps_cw,K (P grad u, P grad v)_K with P the "
       "projection across b and eps_cw,K = crosswind0 max(0, |b| h_cw,K / 2 - eps), "
       "h_cw,K the cell's length across b at its centre (zero on cells that resolve "
       "the crosswind direction). Damps oscillations at characteristic layers; not "
       "consistent (doc/method.md §3). 0: off."},
      {"discretization", "crosswind_form", "linear", m(&S::crosswind_form), by_name,
       "Where the crosswind term acts: linear = on every cell as crosswind0 says; "
       "residual = scaled per cell by s_K = min(1, |R(u_h)| / (|b| |grad u_h|)) of the "
       "previous DWR loop's solution (R the strong residual, integrated over the cell and "
       "the slab ends), so that it stays where u_h changes along b against the equation "
       "and vanishes on layers along b and on resolved solutions (doc/method.md §3). The "
       "first loop, and runs outside study.mode = dwr, use linear."},
      {"discretization", "supg_tau_factor", "1", m(&S::supg_tau_factor), real(0.),
       "Bound delta_K <= supg_tau_factor * tau_n on each slab (tau_n its length), the "
       "stability condition of SUPG whose test function also multiplies du/dt; 0 drops "
       "the bound (small slabs on strongly anisotropic meshes then blow up)."},
      {"discretization", "growth_limit", "1e4", m(&S::growth_limit), real(0.),
       "Blow-up check of the primal march: a slab solution whose largest coefficient "
       "exceeds growth_limit times the data bound max|u_0| + max|g| + int_0^T max|f| dt "
       "(the maximum-principle bound, sampled on a 33 x 33 grid over the domain and on the "
       "Dirichlet boundary's vertices) stops the run as a numerical failure naming the "
       "loop and slab (exit 3); 0 = off."},
      {"discretization", "initial_refinements", "2", m(&S::initial_refinements),
       integer(0, 14),
       "Global refinements of the scene's coarse mesh (unit square: 2 gives 4x4 cells)."},
      {"discretization", "n_slabs", "5", m(&S::n_slabs), integer(1, 1000000),
       "Number of equal time slabs."},
      {"discretization", "mapping_degree", "0", m(&S::mapping_degree), integer(0, 4),
       "Polynomial degree of the cells' map (MappingQ) through the mesh's manifolds, for "
       "the primal and the adjoint alike. 1: straight edges, a curved boundary becomes "
       "the polygon through its vertices; 2 and more follow it between the vertices. "
       "0 (auto): p (isoparametric) if the mesh carries a curved manifold (hemker, custom "
       "scene.manifolds), else 1: Q_p on a curved domain keeps its order (the polygon's "
       "error is O(h^2)). hemker at p = 1 with 2 is measured in doc/results.md ('Hemker: "
       "the circle's polygon and the layer')."},
  };
}

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
       "4 Chebyshev points of [0, T] (per slab length where delta_K depends on it, for "
       "the first two slab lengths met) and, "
       "where their cubic interpolant reproduces the matrices assembled at two further "
       "times to 1e-12 relative (b and alpha polynomial in t of degree <= 3 with the "
       "SUPG terms), build each slab operator from them (the 4 node matrices as its "
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
       "bicgstab (Belos)."},
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

std::vector<Entry> study_entries()
{
  using S = StudySection;
  const auto m = [](auto member) { return at(&Parameters::study, member); };
  return {
      {"study", "mode", "single", m(&S::mode), by_name,
       "single: one primal run; convergence: uniform refinement over study.levels "
       "levels; "
       "dwr: the adaptive DWR loop (section adaptivity, goals from section goal)."},
      {"study", "refine", "both", m(&S::refine), by_name,
       "Convergence study: refine h (space), tau (time) or both per level."},
      {"study", "levels", "4", m(&S::levels), integer(1, 20),
       "Number of levels of a convergence study."},
  };
}

std::vector<Entry> goal_entries()
{
  using S = GoalSection;
  const auto m = [](auto member) { return at(&Parameters::goal, member); };
  return {
      {"goal", "kind", "scene", m(&S::kind),
       std::make_shared<P::Selection>(goal_kind_choices("|")), goal_kind_doc()},
      {"goal", "locations", "", m(&S::locations), text, goal_locations_doc()},
      {"goal", "over_time", "false", m(&S::over_time), boolean,
       "Custom goals: integrate over I (true) or evaluate at T (false)."},
      {"goal", "radius", "0.01", m(&S::radius), real(0.),
       "Mollifier radius s of point goals; 0 = exact point evaluation (Dirac).",
       "a number >= 0 (and at most the diameter of the scene's domain)"},
      {"goal", "weights", "estimate", m(&S::weights), text,
       "Weights w_i of J_w = sum w_i J_i: one number for all goals, a comma list (one "
       "per goal), auto (w_i = sign(J_i(I_2h u) - J_i(u_h)) / max(|J_i(u_h)|, 1e-12); "
       "+1 / |J_i(u_h)| where |J_i(I_2h u) - J_i(u_h)| <= 1e-8 |J_i(u_h)|, the lift not "
       "seeing the goal) or "
       "estimate (the default: w_i = sign(eta_i) / max(|J_i(u_h)|, 0.01 |J_i(1)| max|u_h|, "
       "1e-12), eta_i from each goal's own adjoint, max|u_h| the largest nodal value of "
       "u_h over the slabs: one adjoint march per goal with one factorization, one "
       "estimate per goal; the indicators of J_w are sum_i w_i times goal i's, so the "
       "goals' estimates add up without cancelling, and each goal's error counts "
       "relative to its value, or to 1% of the solution's size where the value is "
       "smaller)."},
      {"goal", "reference", "", m(&S::reference), text,
       "Reference values of the goals for scenes without an exact solution: one value "
       "per goal, comma-separated, each optionally with its uncertainty as value+-u "
       "(e.g. '2.605+-0.003, 1.2e-3+-1e-4'), or empty for a goal without one (e.g. "
       "'2.605+-0.003, , 1.2e-3'). loops.csv and summary.json then report "
       "J_error, I_eff, err_<goal> and I_eff_<goal> against these values; summary.json "
       "says so (\"error_reference\": \"goal.reference\") and lists the uncertainties. "
       "Empty: no reference; an error for scenes with an exact solution."},
  };
}

std::vector<Entry> adaptivity_entries()
{
  using S = AdaptivitySection;
  const auto m = [](auto member) { return at(&Parameters::adaptivity, member); };
  return {
      {"adaptivity", "mode", "anisotropic", m(&S::mode), by_name,
       "anisotropic: mark per direction by |eta_h,i|; isotropic: mark by |eta_h|, refine "
       "isotropically; uniform: refine every cell."},
      {"adaptivity", "marking", "cell", m(&S::marking), by_name,
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
       "(0: no tolerance). It bounds the error of the combined goal J_w = sum_i w_i J_i "
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
       "and estimate per goal instead of one in all."},
      {"adaptivity", "concurrent_marches", "true", m(&S::concurrent_marches), boolean,
       "March the adjoint(s) in a second thread while the primal marches (with "
       "goal.weights = auto and one adjoint for the weighted goal: assemble and "
       "factorize the adjoint's slab operator there, and march once the primal has "
       "given the weights), when one MPI rank "
       "and more than one thread run, both slab systems are predicted to go to UMFPACK, "
       "and the loop's memory estimate with both factorizations held at once fits the "
       "memory limit; otherwise (and with false) the primal, then the adjoint. The "
       "results are the same either way; t_primal and t_adjoint then overlap."},
      {"adaptivity", "measure_time_error", "false", m(&S::measure_time_error), boolean,
       "Diagnostic: on every loop solve the primal on the loop's spatial mesh with its "
       "slabs, bisected once and bisected twice, all with the SUPG parameters of the "
       "finest (delta_K <= supg_tau_factor * tau_n / 4), and report the extrapolated "
       "temporal goal error next to eta_tau (loops.csv: err_tau, err_tau_order; "
       "err_time_<goal> per goal); costs 7 primal solves per slab."},
      {"adaptivity", "adjoint_degree", "0", m(&S::adjoint_degree), integer(0, 8),
       "Polynomial degree q of the adjoint; 0 means q = 2p."},
      {"adaptivity", "space_indicator", "primal_residual", m(&S::space_indicator), by_name,
       "Form of eta_h,i. average: 1/2 rho(u)(z - R_i z) + 1/2 rho*(u, R_h z)(I_2h,i u - "
       "u) + SUPG terms (doc/method.md §8; where a cell has no directional lift only the primal "
       "half); primal_residual: rho(u)(z - R_i z) + S(u)(R_h z), the primal residual "
       "alone, which needs no lift of u (the default: doc/results.md, 'Error control "
       "without tuning'). Both carry the Dirichlet data's share -int eps (g - u_h) d_n z "
       "on Gamma_D (loops.csv eta_h_data)."},
      {"adaptivity", "adjoint_stabilization", "transposed", m(&S::adjoint_stabilization),
       by_name,
       "transposed: the adjoint is the transpose of the SUPG-stabilized primal operator "
       "in degree q (doc/method.md §5); none: the adjoint is the Galerkin (delta = 0) discretization "
       "of the continuous adjoint, consistent with it; the estimator's S terms still use "
       "the primal's delta_K."},
      {"adaptivity", "adjoint_delta0", "-1", m(&S::adjoint_delta0), real(-1.),
       "delta0 of the transposed SUPG adjoint (adjoint_stabilization = transposed); negative "
       "(default -1): discretization.delta0. The estimator's S terms always use the primal's delta_K."},
      {"adaptivity", "adjoint_inverse_bound", "true", m(&S::adjoint_inverse_bound), boolean,
       "Bound the transposed SUPG adjoint's delta_K <= h_min,K^2 / (eps q^4) (h_min,K the "
       "shortest vertex distance of K): the inverse estimate's bound that keeps the SUPG "
       "term's eps Lap part below the diffusion. Without it the adjoint of degree q = 4 "
       "grows without bound on thin cells (doc/results.md, 'Error control without "
       "tuning'); false: delta_K = adjoint_delta0 h_K alone."},
      {"adaptivity", "bound_refinement", "0", m(&S::bound_refinement), real(0.),
       "Refinement where u_h leaves its bounds (probes.csv's u_min, u_max: the scene's, "
       "the exact solution's or the data's by the maximum principle): a cell with a "
       "nodal value at a slab end outside [u_min - f R, u_max + f R] (f this value, R = "
       "u_max - u_min) that is at least 10 times longer along b than across is also "
       "halved along b, beside the marking (loops.csv `bound_cuts`). SUPG oscillates on "
       "such cells where the solution changes along the flow (Hemker: the top of the "
       "circle, doc/results.md). 0: off; no effect without bounds."},
  };
}

std::vector<Entry> output_entries()
{
  using S = OutputSection;
  const auto m = [](auto member) { return at(&Parameters::output, member); };
  return {
      {"output", "directory", "results/moving_hump", m(&S::directory), text,
       "Output directory (created if missing); --output overrides it."},
      {"output", "vtu_every", "1", m(&S::vtu_every), integer(0, 1000000),
       "Write VTU of u(t_n^-) every k-th slab (and at T); 0 writes none."},
      {"output", "progress", "true", m(&S::progress), boolean,
       "Print one progress line per slab to stdout."},
      {"output", "vtu_loops", "1", m(&S::vtu_loops), integer(0, 1000000),
       "DWR: write VTU (mesh, u(T), indicators, aspect ratio) every k-th loop and at the "
       "last loop; 0 writes none."},
      {"output", "dump_slab_loop", "0", m(&S::dump_slab_loop), integer(0, 1000000),
       "DWR: in this loop write the first slab's system matrix K_n of the primal and of "
       "the adjoint (condensed as solved; the adjoint solves with K_n^T) in Matrix Market "
       "format to slab-primal-loop-NNNN.mtx and slab-adjoint-loop-NNNN.mtx, for solver "
       "benchmarks outside anisodwr; 0 writes none."},
  };
}

std::vector<Entry> make_entries()
{
  std::vector<Entry> all;
  for (auto section : {scene_entries, discretization_entries, solver_entries,
                       study_entries, goal_entries, adaptivity_entries, output_entries})
    for (auto &e : section())
    {
      if (!e.pattern)
        e.pattern = e.member.choices;
      // a real bounded below only: "a number >= lo", not "lo <= v <= MAX_DOUBLE"
      const std::string text = e.pattern->description(PatternBase::OutputStyle::Text),
                        unbounded = " <= v <= MAX_DOUBLE", head = "such that ";
      if (e.range.empty() && e.kind() == Kind::real && text.size() > unbounded.size() &&
          text.compare(text.size() - unbounded.size(), unbounded.size(), unbounded) ==
              0 &&
          text.find(head) != std::string::npos)
      {
        const auto from = text.find(head) + head.size();
        e.range =
            "a number >= " + text.substr(from, text.size() - unbounded.size() - from);
      }
      all.push_back(std::move(e));
    }
  return all;
}
} // namespace

const std::vector<Entry> &entries()
{
  static const std::vector<Entry> table = make_entries();
  return table;
}
} // namespace anisodwr::config
