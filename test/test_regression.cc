// Regression and behaviour tests that run the real program (ANISODWR_BIN) on the
// shipped configs and read its loops.csv:
//  - moving_hump_paper, first 6 DWR loops: N_space and N_t exactly; J error, eta_h,x,
//    eta_h,y, eta_tau, I_eff to 1e-6 relative (+1e-12 absolute) against
//    test/reference/moving_hump_paper.csv (regenerate: ANISODWR_WRITE_REFERENCE=1);
//  - moving_hump (the default config), first 8 loops: the same, plus the goals' errors
//    (test/reference/moving_hump.csv);
//  - hemker (10 loops), hemker_count and hemker_paper (3 loops each): N_space (14,425,
//    196 and 196 at loop 1) and N_t exactly; J_1, J_2, eta values, layer width,
//    over-/undershoot (hemker: also each goal's degree-2 value J_hi and own estimate)
//    to 1e-6 relative (test/reference/hemker.csv); the cut-line CSVs
//    are written;
//  - boundary_layer: the layer-normal indicator eta_h,x dominates and anisotropic
//    refinement produces thin cells (ar_max >= 16 by loop 6);
//  - a DoF budget stops the loop cleanly and keeps the finished rows;
//  - goal.weights = estimate: the weighted estimate is the sum of the goals' |eta_i| /
//    |J_i|, and the weighted error takes each goal's error with the sign of its eta_i.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Table = std::vector<std::map<std::string, double>>;

/// ANISODWR_BIN / ANISODWR_SOURCE from the environment, else the build's paths.
std::string env(const std::string &name)
{
  if (const char *v = std::getenv(name.c_str()); v && *v)
    return v;
  if (name == "ANISODWR_BIN")
    return ANISODWR_BIN_PATH;
  if (name == "ANISODWR_SOURCE")
    return ANISODWR_SOURCE_DIR;
  return "";
}

Table read_csv(const std::string &file)
{
  std::ifstream in(file);
  std::string line, cell;
  std::vector<std::string> header;
  Table rows;
  if (std::getline(in, line))
  {
    std::istringstream h(line);
    while (std::getline(h, cell, ','))
      header.push_back(cell);
  }
  while (std::getline(in, line))
  {
    std::istringstream r(line);
    std::map<std::string, double> row;
    for (const auto &name : header)
    {
      if (!std::getline(r, cell, ','))
        cell.clear();
      row[name] = cell.empty() ? std::nan("") : std::stod(cell);
    }
    rows.push_back(row);
  }
  return rows;
}

/// Runs `anisodwr run CONFIG --output DIR --set ...`; returns the exit code.
int run(const std::string &config, const std::string &dir, const std::string &sets)
{
  const std::string cmd = env("ANISODWR_BIN") + " run " + env("ANISODWR_SOURCE") +
                          "/config/" + config + " --output " + dir + " " + sets + " > " +
                          dir + ".log 2>&1";
  std::filesystem::remove_all(dir);
  return WEXITSTATUS(std::system(cmd.c_str()));
}

/// Compares `got` with test/reference/NAME.csv: `exact` columns equal, `close` columns
/// to 1e-6 relative (+1e-12 absolute). ANISODWR_WRITE_REFERENCE=1 rewrites the file.
void check_reference(const Table &got, const std::string &name,
                     const std::vector<std::string> &exact,
                     const std::vector<std::string> &close)
{
  const std::string ref_file =
      env("ANISODWR_SOURCE") + "/test/reference/" + name + ".csv";
  if (env("ANISODWR_WRITE_REFERENCE") == "1")
  {
    std::ofstream out(ref_file);
    out.precision(12);
    out << "loop";
    for (const auto *cols : {&exact, &close})
      for (const auto &k : *cols)
        out << "," << k;
    out << "\n";
    for (const auto &r : got)
    {
      out << r.at("loop");
      for (const auto *cols : {&exact, &close})
        for (const auto &k : *cols)
          out << "," << r.at(k);
      out << "\n";
    }
    GTEST_SKIP() << "reference written to " << ref_file;
  }
  const Table ref = read_csv(ref_file);
  ASSERT_EQ(ref.size(), got.size()) << ref_file;
  for (std::size_t l = 0; l < ref.size(); ++l)
  {
    for (const auto &k : exact)
      EXPECT_EQ(got[l].at(k), ref[l].at(k)) << "loop " << l + 1 << ", " << k;
    for (const auto &k : close)
      if (std::isnan(ref[l].at(k))) // an undefined output (hemker: no layer crossing)
        EXPECT_TRUE(std::isnan(got[l].at(k))) << "loop " << l + 1 << ", " << k;
      else
        EXPECT_NEAR(got[l].at(k), ref[l].at(k), 1e-6 * std::abs(ref[l].at(k)) + 1e-12)
            << "loop " << l + 1 << ", " << k;
  }
}
} // namespace

TEST(Regression, MovingHumpPaperFirstSixLoops)
{
  const std::string dir = "regression_moving_hump_paper";
  ASSERT_EQ(run("moving_hump_paper.json", dir, "--set adaptivity.loops=6"), 0);
  const Table got = read_csv(dir + "/loops.csv");
  ASSERT_EQ(got.size(), 6u);
  check_reference(got, "moving_hump_paper", {"N_space", "N_t"},
                  {"J_error", "eta_hx", "eta_hy", "eta_tau", "I_eff"});
}

TEST(Regression, MovingHumpDefaultFirstEightLoops)
{
  // config/moving_hump.json (Q2 primal, Q3 adjoint, dG(2), estimate weights, the dG(3)
  // temporal indicator): loops 1-8, up to N_tot 1.4e5
  const std::string dir = "regression_moving_hump";
  ASSERT_EQ(run("moving_hump.json", dir, "--set adaptivity.loops=8 --set output.vtu_loops=0"),
            0);
  const Table got = read_csv(dir + "/loops.csv");
  ASSERT_EQ(got.size(), 8u);
  check_reference(got, "moving_hump", {"N_space", "N_t"},
                  {"J_error", "eta_hx", "eta_hy", "eta_tau", "I_eff", "err_u_xe1_T",
                   "err_u_xe2_T"});
}

namespace
{
/// config/CONFIG for `loops` loops against test/reference/REF.csv, with the probes and
/// the cut-line files of every loop.
void check_hemker(const std::string &config, const std::string &ref, unsigned int loops,
                  double first_n_space = 196, const std::vector<std::string> &extra = {})
{
  const std::string dir = "regression_" + ref;
  ASSERT_EQ(run(config, dir,
                "--set adaptivity.loops=" + std::to_string(loops) +
                    " --set output.vtu_loops=0"),
            0);
  Table got = read_csv(dir + "/loops.csv");
  const Table probes = read_csv(dir + "/probes.csv");
  ASSERT_EQ(got.size(), loops);
  ASSERT_EQ(probes.size(), loops);
  EXPECT_EQ(got[0].at("N_space"), first_n_space)
      << "doc/method.md §10: two global refinements give 196 Q1 DoFs, four 2,704, four "
         "and the wall layer 14,425";
  for (std::size_t l = 0; l < got.size(); ++l)
  {
    got[l].insert(probes[l].begin(), probes[l].end());
    char loop[24];
    std::snprintf(loop, sizeof loop, "%04zu", l + 1);
    for (const char *line : {"x4", "normal"})
    {
      std::ifstream cut(dir + "/cut_" + line + "_loop-" + loop + ".csv");
      std::string header, first;
      EXPECT_TRUE(std::getline(cut, header) && header == "s,x,y,u") << line;
      EXPECT_TRUE(std::getline(cut, first)) << line << ": no samples";
    }
  }
  std::vector<std::string> close = {"J_u_xe1_I", "J_u_xe2_I", "eta_hx",     "eta_hy",
                                     "eta_tau",   "layer_width", "overshoot", "undershoot"};
  close.insert(close.end(), extra.begin(), extra.end());
  check_reference(got, ref, {"N_space", "N_t"}, close);
}
} // namespace

TEST(Regression, HemkerFirstTenLoops)
{
  // config/hemker.json (four global refinements and the wall layer, delta0 = 1, bulk
  // marking, theta_h = 0.7): loops 1-10, up to N_space ~18,400
  // (goal_estimate = both: each goal's value of degree 2 and its estimate too)
  check_hemker("hemker.json", "hemker", 10, 14425,
               {"J_hi_u_xe1_I", "J_hi_u_xe2_I", "eta_u_xe1_I", "eta_u_xe2_I"});
}

TEST(Regression, HemkerCountFirstThreeLoops)
{
  // config/hemker_count.json (theta_h = 1/3 of the cells)
  check_hemker("hemker_count.json", "hemker_count", 3);
}

TEST(Regression, HemkerPaperFirstThreeLoops)
{
  // config/hemker_paper.json (the reference paper's setting: per-direction marking of
  // 1/3, w = 1, delta0 = 0.1 with |K|^(1/2)); loop 1 is the identical 196-DoF mesh
  check_hemker("hemker_paper.json", "hemker_paper", 3);
}

TEST(Anisotropy, BoundaryLayerRefinesAcrossTheLayerOnly)
{
  const std::string dir = "regression_boundary_layer";
  ASSERT_EQ(run("boundary_layer.json", dir, "--set adaptivity.loops=6"), 0);
  const Table t = read_csv(dir + "/loops.csv");
  ASSERT_EQ(t.size(), 6u);
  for (std::size_t l = 1; l < t.size(); ++l)
    EXPECT_GT(std::abs(t[l].at("eta_hx")), 5 * std::abs(t[l].at("eta_hy")))
        << "loop " << l + 1;
  EXPECT_GE(t.back().at("ar_max"), 16.);
  EXPECT_LT(t.back().at("J_error"), 0.1 * t.front().at("J_error"));
}

TEST(WallLayer, BoundaryLayerIsResolvedBeforeTheFirstLoop)
{
  // discretization.wall_layer = 1 on boundary_layer (eps = 1e-3, b = (1, 0), Dirichlet
  // outflow at x = 1): the 4 cells at x = 1 of the 4 x 4 mesh are halved 8 times (0.25 /
  // 2^8 <= 1e-3 < 0.25 / 2^7): 48 cells, 5 x 5 + 8 x 5 = 65 Q1 DoFs at loop 1
  const std::string plain = "regression_wall_layer_off", layered = "regression_wall_layer";
  ASSERT_EQ(run("boundary_layer.json", plain, "--set adaptivity.loops=4"), 0);
  ASSERT_EQ(run("boundary_layer.json", layered,
                "--set adaptivity.loops=4 --set discretization.wall_layer=1"),
            0);
  const Table p = read_csv(plain + "/loops.csv"), w = read_csv(layered + "/loops.csv");
  ASSERT_EQ(w.size(), 4u);
  EXPECT_EQ(w[0].at("N_space"), 65.);
  EXPECT_EQ(p[0].at("N_space"), 25.);
  // the layer resolved: loop 1's error a twentieth of the plain mesh's or less, and the
  // estimate of the right size from loop 1 on
  EXPECT_LT(w[0].at("J_error"), 0.05 * p[0].at("J_error"));
  for (const auto &row : w)
  {
    EXPECT_GT(row.at("I_eff"), 0.8) << "loop " << row.at("loop");
    EXPECT_LT(row.at("I_eff"), 2.5) << "loop " << row.at("loop");
  }
}

// adaptivity.adjoint_outflow = goals (doc/method.md §5): a goal inside the outflow layer
// of boundary_layer (eps = 1e-3; the mean of u(T) over the strip 0.98 < x < 1, whose u
// falls from about 1 to 0 within eps of the wall) on 4 x 4 cells of 1/4. With z = 0
// imposed at the wall the Q2 adjoint's test functions vanish where the goal sits and the
// estimate is a fraction of the error (measured: I_eff 0.06, 0.08, 0.14 on loops 1-3);
// with the wall's DoFs free under the goal it has the error's sign and 0.51-1.08 of its
// size on every loop (loops 1-8; z = 0 again from loop 5, where the wall cells are
// thinner than the strip). The default goal (the mean over 0.5 < x < 1, thicker than
// the cells) is untouched.
TEST(AdjointOutflow, GoalInsideTheOutflowLayerIsEstimatedOnCoarseMeshes)
{
  // boundary_layer.json for `loops` loops with adjoint_outflow = `outflow` (and the strip
  // goal unless `own_goal`): its loops.csv
  const auto loops = [](unsigned int loops, const std::string &outflow, bool own_goal)
  {
    const std::string dir = "regression_outflow_" + outflow + (own_goal ? "_own" : "");
    const std::string goal =
        own_goal ? "" : " --set goal.kind=mean --set goal.locations=0.98,0,1,1";
    EXPECT_EQ(run("boundary_layer.json", dir,
                  "--set adaptivity.loops=" + std::to_string(loops) +
                      " --set adaptivity.adjoint_outflow=" + outflow + goal),
              0);
    const Table t = read_csv(dir + "/loops.csv");
    EXPECT_EQ(t.size(), loops);
    return t;
  };
  for (const auto &row : loops(8, "goals", false))
  {
    EXPECT_GT(row.at("I_eff"), 0.45) << "loop " << row.at("loop");
    EXPECT_LT(row.at("I_eff"), 1.5) << "loop " << row.at("loop");
  }
  for (const auto &row : loops(3, "dirichlet", false))
    EXPECT_LT(row.at("I_eff"), 0.3) << "loop " << row.at("loop");
  // the default goal: no wall face qualifies, the run is the dirichlet one
  const Table a = loops(2, "goals", true), b = loops(2, "dirichlet", true);
  for (std::size_t l = 0; l < std::min(a.size(), b.size()); ++l)
    for (const char *k : {"N_space", "J", "eta_hx", "eta_hy", "eta_tau"})
      EXPECT_EQ(a[l].at(k), b[l].at(k)) << "loop " << l + 1 << ", " << k;
}

namespace
{
/// hemker.json's first loop without its wall layer (2,704 DoFs), with per-goal DWR
/// estimates (each goal's indicators summed, not the enriched estimate) and `--set
/// KEY=VALUE`: its loops.csv row.
std::map<std::string, double> hemker_first_loop(const std::string &key, const std::string &value)
{
  const std::string dir = "regression_first_loop_" + key + "_" + value;
  EXPECT_EQ(run("hemker.json", dir,
                "--set adaptivity.loops=1 --set adaptivity.tolerance=0 --set "
                "discretization.wall_layer=0 --set "
                "adaptivity.per_goal_estimates=true --set adaptivity.goal_estimate=dwr "
                "--set output.vtu_loops=0 --set " +
                    key + "=" + value),
            0);
  const Table t = read_csv(dir + "/loops.csv");
  EXPECT_EQ(t.size(), 1u);
  return t.empty() ? std::map<std::string, double>{} : t.at(0);
}
} // namespace

// hemker.json's first loop (without its wall layer): the crosswind term's switch is 1
// everywhere, and the adjoint that carries it spreads J_1's pulse (0.02 wide) across b by
// |b| h_perp / 2 = 0.085: J_1's own estimate is then 0.12 of its error (e_1 = -0.887).
// Without the term in the adjoint it is 1.25 of it (doc/results.md, "Hemker: the goals'
// streaks and the adjoint's crosswind term"). The primal, and so J_1, is the same either
// way.
TEST(AdjointCrosswind, HemkersFirstLoopEstimatesJ1WithoutTheTermInTheAdjoint)
{
  const auto with = hemker_first_loop("adaptivity.adjoint_crosswind", "true"),
             without = hemker_first_loop("adaptivity.adjoint_crosswind", "false");
  EXPECT_EQ(with.at("err_u_xe1_I"), without.at("err_u_xe1_I"));
  EXPECT_LT(with.at("err_u_xe1_I"), -0.5);
  const double r_with = with.at("eta_u_xe1_I") / with.at("err_u_xe1_I"),
               r_without = without.at("eta_u_xe1_I") / without.at("err_u_xe1_I");
  EXPECT_GT(r_with, 0.);
  EXPECT_LT(r_with, 0.3);
  EXPECT_GT(r_without, 0.8);
  EXPECT_LT(r_without, 1.6);
}

// discretization.crosswind_first_solve on hemker.json's first loop (no wall layer): the
// factor s_K from a march without the term instead of 1 everywhere. With s_K = 1 the
// wake's layer is smeared and u_h(x_e1) integrates to J_1 = 3.4920; with the factor of
// the SUPG solution the term acts only where that solution oscillates and J_1 = 2.4728
// (reference 2.605; measured 2026-12-05, regression tolerance 2e-3).
TEST(CrosswindFirstSolve, HemkersFirstLoopTakesItsSwitchFromAMarchWithoutTheTerm)
{
  const auto J1 = [](const std::string &value)
  {
    const auto row = hemker_first_loop("discretization.crosswind_first_solve", value);
    return row.count("err_u_xe1_I") ? 2.605 - row.at("err_u_xe1_I") : 0.;
  };
  EXPECT_NEAR(J1("false"), 3.4920, 2e-3);
  EXPECT_NEAR(J1("true"), 2.4728, 2e-3);
}

TEST(Budget, DofBudgetStopsCleanlyAndKeepsRows)
{
  const std::string dir = "regression_budget";
  ASSERT_EQ(run("boundary_layer.json", dir,
                "--set adaptivity.loops=20 --set adaptivity.max_dofs=1200"),
            0);
  const Table t = read_csv(dir + "/loops.csv");
  ASSERT_GE(t.size(), 3u);
  EXPECT_LE(t.back().at("N_tot"), 1200.);
  std::ifstream s(dir + "/summary.json");
  const std::string summary((std::istreambuf_iterator<char>(s)),
                            std::istreambuf_iterator<char>());
  EXPECT_NE(summary.find("\"stop_reason\": \"DoF budget"), std::string::npos);
  EXPECT_NE(summary.find("\"mean_T\""), std::string::npos);
  std::ifstream tex(dir + "/loops.tex");
  std::string line;
  unsigned int rows = 0;
  while (std::getline(tex, line))
    rows += line.find("\\\\") != std::string::npos;
  EXPECT_EQ(rows, t.size() + 1) << "header + one LaTeX row per loop";
}

TEST(Goals, EstimateWeightsAddTheGoalsEstimatesWithoutCancelling)
{
  // w_i = sign(eta_i) / |J_i(u_h)| with eta_i from goal i's own adjoint: eta of J_w (its
  // indicators are sum_i w_i times goal i's) is sum_i |eta_i| / |J_i(u_h)|, and the
  // error of J_w is sum_i sign(eta_i) (J_i(u) - J_i(u_h)) / |J_i(u_h)|; each goal's
  // eta_hx_, eta_hy_, eta_tau_ columns add up to its eta_. Moving hump, 6 loops, to 1e-7
  // relative (loops.csv prints 8 digits).
  const std::string dir = "regression_estimate_weights";
  ASSERT_EQ(run("moving_hump.json", dir,
                "--set goal.weights=estimate --set adaptivity.loops=6 "
                "--set output.vtu_loops=0"),
            0);
  const Table t = read_csv(dir + "/loops.csv");
  const Table p = read_csv(dir + "/probes.csv");
  ASSERT_EQ(t.size(), 6u);
  ASSERT_EQ(p.size(), 6u);
  for (std::size_t l = 0; l < t.size(); ++l)
  {
    double eta = 0, err = 0;
    for (const std::string g : {"u_xe1_T", "u_xe2_T"})
    {
      const double Ji = std::abs(p[l].at("J_" + g)), eta_i = t[l].at("eta_" + g);
      ASSERT_GT(Ji, 0.);
      eta += std::abs(eta_i) / Ji;
      err += (eta_i >= 0 ? 1. : -1.) * t[l].at("err_" + g) / Ji;
      // each goal's parts add up to its estimate
      const double parts =
          t[l].at("eta_hx_" + g) + t[l].at("eta_hy_" + g) + t[l].at("eta_tau_" + g);
      EXPECT_NEAR(parts, eta_i, 1e-7 * std::abs(eta_i) + 1e-14) << "loop " << l + 1;
    }
    EXPECT_NEAR(t[l].at("eta_tauh"), eta, 1e-7 * eta) << "loop " << l + 1;
    EXPECT_NEAR(t[l].at("J_error"), std::abs(err), 1e-7 * std::abs(err) + 1e-12)
        << "loop " << l + 1;
  }
}
