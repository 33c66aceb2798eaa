#include "config/parameters.h"

#include "config/errors.h"

#include <deal.II/base/patterns.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

namespace anisodwr
{
namespace
{
using dealii::Patterns::PatternBase;
namespace P = dealii::Patterns;

enum class Kind
{
  integer,
  real,
  boolean,
  text
};

struct Entry
{
  std::string section, key, default_value;
  Kind kind;
  std::shared_ptr<PatternBase> pattern;
  std::string doc;
  /// What the value must be, in words (overrides the pattern's description).
  std::string range = "";

  std::string expected() const
  {
    return range.empty() ? pattern->description(PatternBase::OutputStyle::Text) : range;
  }
};

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
       "with solver.preconditioner, Trilinos), or auto: UMFPACK while one factorization "
       "serves all slabs (coefficients constant in time, equal slabs) and its predicted "
       "factors fit in solver.auto_memory_mb; otherwise iterative iff N_space (r+1)^2 >= "
       "solver.auto_threshold."},
      {"solver", "dof_numbering", "native", Kind::text, choice("native|downstream"),
       "Spatial DoF order: native (deal.II's cell-wise order) or downstream (sorted along "
       "the convection b at the domain's centre; ILU and Gauss-Seidel then sweep with the "
       "flow, which keeps them effective on convection-dominated, anisotropic meshes). "
       "Direct solves are unaffected up to round-off."},
      {"solver", "reuse_factorization", "true", Kind::boolean, boolean,
       "Reuse the LU factorization (or the preconditioner) while the slab matrix is "
       "unchanged (same tau, coefficients constant in time)."},
      {"solver", "auto_threshold", "1e6", Kind::real, real(0.),
       "solver.type = auto: iterative iff N_space (r+1)^2 (slab unknowns times the "
       "temporal block size, which UMFPACK's cost follows) reaches this (README 'Slab "
       "solvers': from there gmres+kronecker_presb is faster and 2-4x smaller)."},
      {"solver", "auto_memory_mb", "0", Kind::real, real(0.),
       "solver.type = auto: largest predicted UMFPACK factor size (MB) for which a "
       "factorization reused over the slabs is preferred to a Krylov solver (measured "
       "150 n log2(n) bytes for Q1, 200 for Q2+, n = slab unknowns); 0 = a third of the "
       "physical memory."},
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
       "with |b| tau >> goal.radius, see doc/results.md); higher_order: rho*(u,z)(u' - u) "
       "with u' the primal solved once more in dG(r+1) (one more primal solve per loop), "
       "which does not rely on dG(r)'s nodal superconvergence and sees the temporal error "
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

const std::vector<Entry> &entries()
{
  static const std::vector<Entry> table = make_entries();
  return table;
}

std::size_t edit_distance(const std::string &a, const std::string &b)
{
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] =
          std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string suggestion(const std::string &word, const std::vector<std::string> &known)
{
  std::string best;
  std::size_t best_d = 3;
  for (const auto &k : known)
    if (const auto d = edit_distance(word, k); d < best_d)
    {
      best_d = d;
      best = k;
    }
  std::string list;
  for (const auto &k : known)
    list += (list.empty() ? "" : ", ") + k;
  return (best.empty() ? "" : " (did you mean '" + best + "'?)") +
         "; expected one of: " + list;
}

/// Holds the values while reading; checks each value against its pattern.
class Reader
{
public:
  Reader()
  {
    for (const auto &e : entries())
      values[e.section + "." + e.key] = e.default_value;
  }

  void set(const std::string &section, const std::string &key, const std::string &value,
           const std::string &origin)
  {
    std::vector<std::string> sections, keys;
    const Entry *found = nullptr;
    for (const auto &e : entries())
    {
      if (std::find(sections.begin(), sections.end(), e.section) == sections.end())
        sections.push_back(e.section);
      if (e.section == section)
      {
        keys.push_back(e.key);
        if (e.key == key)
          found = &e;
      }
    }
    if (keys.empty())
      throw InputError(origin + ": unknown section '" + section + "'" +
                       suggestion(section, sections));
    if (!found)
      throw InputError(origin + ": unknown key '" + section + "." + key + "'" +
                       suggestion(key, keys));
    if (!found->pattern->match(value))
      throw InputError(origin + ": invalid value '" + value + "' for key '" + section +
                       "." + key + "'; expected " + found->expected() + " (" +
                       found->doc + ")");
    values[section + "." + key] = value;
    origins[section + "." + key] = origin;
  }

  /// Deepest nesting of [ and { accepted in a config (sections hold values: depth 2).
  static constexpr unsigned int max_depth = 64;

  /// The top level must be an object and the nesting at most max_depth deep (the JSON
  /// reader recurses once per level; without the limit deep input overflows the stack).
  static void check_structure(const std::string &file, const std::string &text)
  {
    std::size_t start = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    start = text.find_first_not_of(" \t\r\n", start);
    if (start == std::string::npos || text[start] != '{')
      throw InputError(file + ": the top level of a config must be a JSON object "
                              "{\"section\": {\"key\": value}}, found " +
                       (start == std::string::npos
                            ? std::string("an empty file")
                            : "'" + text.substr(start, std::min<std::size_t>(
                                                           20, text.find_first_of(
                                                                   "\r\n", start) -
                                                                   start)) +
                                  "'"));
    unsigned int depth = 0;
    bool in_string = false;
    for (std::size_t i = start; i < text.size(); ++i)
    {
      const char c = text[i];
      if (in_string)
      {
        if (c == '\\')
          ++i;
        else if (c == '"')
          in_string = false;
      }
      else if (c == '"')
        in_string = true;
      else if (c == '[' || c == '{')
      {
        if (++depth > max_depth)
          throw InputError(file + ": JSON nested deeper than " +
                           std::to_string(max_depth) +
                           " levels (a config is {\"section\": {\"key\": value}})");
      }
      else if ((c == ']' || c == '}') && depth > 0)
        --depth;
    }
  }

  void read_file(const std::string &file)
  {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
      throw InputError(file + ": is a directory, not a config file");
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw InputError(file + ": cannot open the config file for reading: " +
                       std::strerror(errno));
    std::string text;
    try
    {
      in.exceptions(std::ios::badbit);
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    catch (const std::exception &)
    {
      throw InputError(file + ": cannot read the config file: " + std::strerror(errno));
    }
    check_structure(file, text);
    boost::property_tree::ptree tree;
    try
    {
      std::istringstream stream(text);
      boost::property_tree::read_json(stream, tree);
    }
    catch (const boost::property_tree::json_parser_error &e)
    {
      throw InputError(file + ": invalid JSON at line " + std::to_string(e.line()) +
                       ": " + e.message());
    }
    for (const auto &[section, sub] : tree)
    {
      if (!section.empty() && section[0] == '#')
        continue;
      if (sub.empty())
        throw InputError(file + ": top-level key '" + section +
                         "' must be a section object like {\"key\": value}");
      for (const auto &[key, leaf] : sub)
      {
        if (!key.empty() && key[0] == '#')
          continue;
        if (!leaf.empty())
          throw InputError(
              file + ": key '" + section + "." + key +
              "' must hold a number, boolean or string, not an object or list");
        set(section, key, leaf.data(), file);
      }
    }
  }

  void apply_override(const std::string &assignment)
  {
    const auto eq = assignment.find('='), dot = assignment.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq)
      throw InputError("--set '" + assignment + "': expected the form section.key=value");
    set(assignment.substr(0, dot), assignment.substr(dot + 1, eq - dot - 1),
        assignment.substr(eq + 1), "--set");
  }

  Parameters typed() const
  {
    Parameters p;
    p.scene = get("scene.name");
    p.variant = get("scene.variant");
    p.epsilon = real("scene.epsilon");
    p.end_time = real("scene.end_time");
    p.p = integer("discretization.p");
    p.r = integer("discretization.r");
    p.delta0 = real("discretization.delta0");
    p.supg_length = get("discretization.supg_length");
    p.supg_tau_factor = real("discretization.supg_tau_factor");
    p.initial_refinements = integer("discretization.initial_refinements");
    p.n_slabs = integer("discretization.n_slabs");
    p.solver_type = get("solver.type");
    p.reuse_factorization = boolean("solver.reuse_factorization");
    p.solver_auto_threshold = real("solver.auto_threshold");
    p.solver_auto_memory_mb = real("solver.auto_memory_mb");
    p.krylov = get("solver.krylov");
    p.preconditioner = get("solver.preconditioner");
    p.solver_tolerance = real("solver.tolerance");
    p.restart = integer("solver.restart");
    p.max_iterations = integer("solver.max_iterations");
    p.ilu_fill = real("solver.ilu_fill");
    p.spatial_preconditioner = get("solver.spatial_preconditioner");
    p.amg_smoother = get("solver.amg_smoother");
    p.stagnation_window = integer("solver.stagnation_window");
    p.stagnation_factor = real("solver.stagnation_factor");
    p.fallback = get("solver.fallback");
    p.mode = get("study.mode");
    p.refine = get("study.refine");
    p.levels = integer("study.levels");
    p.goal_kind = get("goal.kind");
    p.goal_locations = get("goal.locations");
    p.goal_over_time = boolean("goal.over_time");
    p.goal_radius = real("goal.radius");
    p.goal_weights = get("goal.weights");
    p.adaptivity_mode = get("adaptivity.mode");
    p.marking = get("adaptivity.marking");
    p.kappa = fraction("adaptivity.kappa");
    p.loops = integer("adaptivity.loops");
    p.theta_h = fraction("adaptivity.theta_h");
    p.theta_tau = fraction("adaptivity.theta_tau");
    p.theta_coarsen = fraction("adaptivity.theta_coarsen");
    p.tolerance = real("adaptivity.tolerance");
    p.max_dofs = real("adaptivity.max_dofs");
    p.max_memory_mb = real("adaptivity.max_memory_mb");
    p.max_wall_time = real("adaptivity.max_wall_time");
    p.adjoint_degree = integer("adaptivity.adjoint_degree");
    p.adjoint_stabilization = get("adaptivity.adjoint_stabilization");
    p.space_indicator = get("adaptivity.space_indicator");
    p.dof_numbering = get("solver.dof_numbering");
    p.measure_time_error = boolean("adaptivity.measure_time_error");
    p.time_indicator = get("adaptivity.time_indicator");
    p.per_goal_estimates = boolean("adaptivity.per_goal_estimates");
    p.vtu_loops = integer("output.vtu_loops");
    p.output_directory = get("output.directory");
    p.vtu_every = integer("output.vtu_every");
    p.progress = boolean("output.progress");
    bounded_positive("scene.epsilon", p.epsilon);
    bounded_positive("scene.end_time", p.end_time);
    for (const auto &[key, value] : values)
      p.sources[key] = origin(key);
    return p;
  }

private:
  std::map<std::string, std::string> values, origins;

  std::string origin(const std::string &k) const
  {
    const auto it = origins.find(k);
    return it == origins.end() ? "default" : it->second;
  }

  std::string get(const std::string &k) const { return values.at(k); }
  double real(const std::string &k) const { return std::stod(get(k)); }
  unsigned int integer(const std::string &k) const { return std::stoul(get(k)); }
  bool boolean(const std::string &k) const
  {
    return get(k) == "true" || get(k) == "True" || get(k) == "yes";
  }
  double fraction(const std::string &k) const
  {
    const double v = real(k);
    if (v > 1.)
      throw InputError(origin(k) + ": invalid value '" + get(k) + "' for key '" + k +
                       "'; expected a fraction in [0, 1]");
    return v;
  }
  /// 0 < v <= 1e6 (scene.epsilon, scene.end_time)
  void bounded_positive(const std::string &k, double v) const
  {
    if (!(v > 0.) || !(v <= 1e6))
      throw InputError(origin(k) + ": invalid value '" + get(k) + "' for key '" + k +
                       "'; expected a number with 0 < v <= 1e6");
  }
};

std::string json_value(const Entry &e, const std::string &value)
{
  if (e.kind == Kind::text)
    return "\"" + value + "\"";
  if (e.kind == Kind::boolean)
    return (value == "true" || value == "True" || value == "yes") ? "true" : "false";
  return value;
}

std::string format(const std::map<std::string, std::string> &values, bool with_docs,
                   unsigned int indent)
{
  const std::string pad(indent, ' ');
  std::ostringstream out;
  out << "{";
  std::string section;
  for (const auto &e : entries())
  {
    if (e.section != section)
    {
      out << (section.empty() ? "\n" : "\n" + pad + "  },\n") << pad << "  \""
          << e.section << "\": {";
      section = e.section;
    }
    else
      out << ",";
    if (with_docs)
      out << "\n"
          << pad << "    \"#" << e.key << "\": \"" << e.doc
          << " Allowed: " << e.expected()
          << "\",";
    out << "\n"
        << pad << "    \"" << e.key
        << "\": " << json_value(e, values.at(e.section + "." + e.key));
  }
  out << "\n" << pad << "  }\n" << pad << "}";
  return out.str();
}
} // namespace

std::string Parameters::source(const std::string &key) const
{
  const auto it = sources.find(key);
  return it == sources.end() ? "default" : it->second;
}

Parameters Parameters::read(const std::string &file,
                            const std::vector<std::string> &overrides)
{
  Reader reader;
  reader.read_file(file);
  for (const auto &o : overrides)
    reader.apply_override(o);
  return reader.typed();
}

Parameters Parameters::from_overrides(const std::vector<std::string> &overrides)
{
  Reader reader;
  for (const auto &o : overrides)
    reader.apply_override(o);
  return reader.typed();
}

void Parameters::print_defaults(std::ostream &out)
{
  std::map<std::string, std::string> values;
  for (const auto &e : entries())
    values[e.section + "." + e.key] = e.default_value;
  out << format(values, true, 0) << std::endl;
}

std::string Parameters::to_json(unsigned int indent) const
{
  auto num = [](double v)
  {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  };
  std::map<std::string, std::string> v{
      {"scene.name", scene},
      {"scene.variant", variant},
      {"scene.epsilon", num(epsilon)},
      {"scene.end_time", num(end_time)},
      {"discretization.p", std::to_string(p)},
      {"discretization.r", std::to_string(r)},
      {"discretization.delta0", num(delta0)},
      {"discretization.supg_length", supg_length},
      {"discretization.supg_tau_factor", num(supg_tau_factor)},
      {"discretization.initial_refinements", std::to_string(initial_refinements)},
      {"discretization.n_slabs", std::to_string(n_slabs)},
      {"solver.type", solver_type},
      {"solver.reuse_factorization", reuse_factorization ? "true" : "false"},
      {"solver.auto_threshold", num(solver_auto_threshold)},
      {"solver.auto_memory_mb", num(solver_auto_memory_mb)},
      {"solver.krylov", krylov},
      {"solver.preconditioner", preconditioner},
      {"solver.tolerance", num(solver_tolerance)},
      {"solver.restart", std::to_string(restart)},
      {"solver.max_iterations", std::to_string(max_iterations)},
      {"solver.ilu_fill", num(ilu_fill)},
      {"solver.spatial_preconditioner", spatial_preconditioner},
      {"solver.amg_smoother", amg_smoother},
      {"solver.stagnation_window", std::to_string(stagnation_window)},
      {"solver.stagnation_factor", num(stagnation_factor)},
      {"solver.fallback", fallback},
      {"solver.dof_numbering", dof_numbering},
      {"study.mode", mode},
      {"study.refine", refine},
      {"study.levels", std::to_string(levels)},
      {"goal.kind", goal_kind},
      {"goal.locations", goal_locations},
      {"goal.over_time", goal_over_time ? "true" : "false"},
      {"goal.radius", num(goal_radius)},
      {"goal.weights", goal_weights},
      {"adaptivity.mode", adaptivity_mode},
      {"adaptivity.marking", marking},
      {"adaptivity.kappa", num(kappa)},
      {"adaptivity.loops", std::to_string(loops)},
      {"adaptivity.theta_h", num(theta_h)},
      {"adaptivity.theta_tau", num(theta_tau)},
      {"adaptivity.theta_coarsen", num(theta_coarsen)},
      {"adaptivity.tolerance", num(tolerance)},
      {"adaptivity.max_dofs", num(max_dofs)},
      {"adaptivity.max_memory_mb", num(max_memory_mb)},
      {"adaptivity.max_wall_time", num(max_wall_time)},
      {"adaptivity.adjoint_degree", std::to_string(adjoint_degree)},
      {"adaptivity.adjoint_stabilization", adjoint_stabilization},
      {"adaptivity.space_indicator", space_indicator},
      {"adaptivity.measure_time_error", measure_time_error ? "true" : "false"},
      {"adaptivity.time_indicator", time_indicator},
      {"adaptivity.per_goal_estimates", per_goal_estimates ? "true" : "false"},
      {"output.vtu_loops", std::to_string(vtu_loops)},
      {"output.directory", output_directory},
      {"output.vtu_every", std::to_string(vtu_every)},
      {"output.progress", progress ? "true" : "false"}};
  return format(v, false, indent);
}
} // namespace anisodwr
