#include "config/parameter_table.h"
#include "config/table_binding.h"

#include "goal/goal_type.h"
#include "scene/scene_registry.h"

#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace anisodwr::config
{
namespace
{
using namespace table;

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
      {"discretization", "crosswind_exponent", "1", m(&S::crosswind_exponent), real(1.),
       "crosswind_form = residual: the factor is s_K^q with q this exponent (>= 1). "
       "A layer that spreads by its own diffusion has s_K about its width over its "
       "length (1e-3 to 1e-2 in Hemker's wake), where q = 1 leaves eps_cw,K about eps "
       "and q = 2 s_K times that; where u_h oscillates s_K is near 1 either way "
       "(doc/method.md §3). Other values warn unless crosswind_form = residual and "
       "crosswind0 > 0."},
      {"discretization", "crosswind_first_solve", "false", m(&S::crosswind_first_solve),
       boolean,
       "crosswind_form = residual in study.mode = dwr: the first loop, which has no "
       "previous solution, takes its factor s_K from a primal march on its mesh without "
       "the term (one more march) instead of s_K = 1 on every cell. With s_K = 1 the "
       "first loop's u_h is smeared, its factor is small along the layers, and the second "
       "loop oscillates there (doc/history.md, 'Hemker: the goals' streaks and the "
       "adjoint's crosswind term'). Warns where the term is not residual-switched."},
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
      {"discretization", "wall_layer", "0", m(&S::wall_layer), real(0.),
       "A priori layer mesh where Dirichlet data meets outflow (b.n > 0 at a boundary "
       "face at t = 0, T/2 or T; there u has an exponential layer of width about "
       "eps / (b.n)): after the initial refinements the cells at such faces are halved "
       "across the wall until they are at most wall_layer * eps / (b.n) thick, so the "
       "first DWR loop already resolves the layer that a same-mesh adjoint cannot see "
       "(doc/method.md, 'A priori wall layer'). 0 = off; 1 resolves the layer's length "
       "scale. study.mode = dwr and single only."},
      {"discretization", "goal_streak", "0", m(&S::goal_streak), real(0.),
       "A priori mesh along the goals' upstream paths: a point goal's (radius r > 0) or "
       "mean goal's centre is traced back along -b from t = T to 0, and after the initial "
       "refinements (before the wall layer) the cells within the support's width w of the "
       "path (w = 2 r, or the rectangle's width across b) are halved across b until they "
       "are at most w / goal_streak thick across it, so that the first DWR loop's "
       "same-mesh adjoint can hold the goal's streak (where eps << |b| w the adjoint keeps "
       "the support's width upstream). 0 = off. study.mode = dwr only."},
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
       "last loop (the loop cap's, or the loop the tolerance or the wall-time budget stops "
       "after); 0 writes none."},
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
