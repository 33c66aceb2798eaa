// The options table: struct defaults equal the table's, enums read and print by name,
// and the errors name key, source and value.
#include "base/errors.h"
#include "config/parameters.h"
#include "goal/goal_type.h"
#include "scene/scene.h"
#include "space/space.h"
#include "study/options.h"

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>

using namespace anisodwr;

namespace
{
std::string error_of(const std::vector<std::string> &overrides)
{
  try
  {
    Parameters::from_overrides(overrides);
  }
  catch (const InputError &e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(Parameters, MemberDefaultsEqualTheTable)
{
  EXPECT_EQ(Parameters().to_json(0), Parameters::from_overrides({}).to_json(0));
}

TEST(Parameters, EnumsReadAndPrintByName)
{
  const Parameters p = Parameters::from_overrides(
      {"scene.name=hemker", "discretization.supg_length=streamline", "study.mode=dwr",
       "study.refine=time", "goal.kind=mean", "adaptivity.mode=isotropic",
       "adaptivity.marking=per_direction", "adaptivity.time_indicator=higher_order",
       "adaptivity.space_indicator=primal_residual",
       "adaptivity.adjoint_stabilization=none"});
  EXPECT_EQ(p.scene.name, "hemker");
  EXPECT_EQ(p.discretization.supg_length, SupgLength::streamline);
  EXPECT_EQ(p.study.mode, StudyMode::dwr);
  EXPECT_EQ(p.study.refine, StudyRefine::time);
  EXPECT_EQ(p.goal.kind, "mean");
  EXPECT_EQ(p.adaptivity.mode, AdaptivityMode::isotropic);
  EXPECT_EQ(p.adaptivity.marking, Marking::per_direction);
  EXPECT_EQ(p.adaptivity.time_indicator, TimeIndicator::higher_order);
  EXPECT_EQ(p.adaptivity.space_indicator, SpaceIndicator::primal_residual);
  EXPECT_EQ(p.adaptivity.adjoint_stabilization, AdjointStabilization::none);
  const std::string json = p.to_json(0);
  for (const char *v : {"\"hemker\"", "\"streamline\"", "\"per_direction\"",
                        "\"higher_order\"", "\"primal_residual\"", "\"isotropic\""})
    EXPECT_NE(json.find(v), std::string::npos) << v;
  EXPECT_EQ(p.source("study.mode"), "--set");
  EXPECT_EQ(p.source("study.levels"), "default");
}

// goal.kind accepts scene and every registered goal kind, documents each, and refuses
// other names; an unknown kind cannot reach any kind's code.
TEST(Parameters, GoalKindsFollowTheRegistry)
{
  std::ostringstream printed;
  Parameters::print_defaults(printed);
  const std::string defaults = printed.str();
  for (const GoalType *type : goal_types())
  {
    const auto p = Parameters::from_overrides({"goal.kind=" + type->name()});
    EXPECT_EQ(p.goal.kind, type->name());
    EXPECT_EQ(&goal_type(type->name()), type);
    EXPECT_NE(defaults.find(type->name() + ": " + type->doc()), std::string::npos)
        << type->name();
  }
  EXPECT_THROW(Parameters::from_overrides({"goal.kind=flux_of_nothing"}), InputError);
  EXPECT_THROW(goal_type("flux_of_nothing"), InputError);
  EXPECT_THROW(goal_type("scene"), InputError);
}

TEST(Parameters, NumbersAndStrings)
{
  const Parameters p = Parameters::from_overrides(
      {"adaptivity.theta_h=0.5", "discretization.p=3", "output.progress=false",
       "solver.krylov=bicgstab", "goal.locations=0.5,0.5"});
  EXPECT_EQ(p.adaptivity.theta_h, 0.5);
  EXPECT_EQ(p.discretization.p, 3u);
  EXPECT_FALSE(p.output.progress);
  EXPECT_EQ(p.solver.iterative.krylov, Krylov::bicgstab);
  EXPECT_EQ(p.goal.locations, "0.5,0.5");
}

TEST(Parameters, Errors)
{
  EXPECT_NE(error_of({"adaptivity.time_indicater=average"})
                .find("--set: unknown key 'adaptivity.time_indicater' (did you mean "
                      "'time_indicator'?)"),
            std::string::npos);
  EXPECT_NE(error_of({"adaptivty.loops=2"}).find("(did you mean 'adaptivity'?)"),
            std::string::npos);
  const std::string bad = error_of({"adaptivity.marking=cells"});
  EXPECT_NE(bad.find("invalid value 'cells' for key 'adaptivity.marking'"),
            std::string::npos);
  EXPECT_NE(bad.find("expected Any one of joint, per_direction, cell (Anisotropic"),
            std::string::npos)
      << bad;
  // scene.name: the names of the scene registry, documented by its one-liners
  const std::string scene = error_of({"scene.name=hemkerr"});
  EXPECT_NE(scene.find("--set: invalid value 'hemkerr' for key 'scene.name'; expected Any "
                       "one of moving_hump, manufactured, heat, boundary_layer, hemker, "
                       "custom (The scene"),
            std::string::npos)
      << scene;
  EXPECT_NE(scene.find("hemker: flow past the unit circle"), std::string::npos) << scene;
  EXPECT_NE(error_of({"adaptivity.kappa=2"}).find("expected a fraction in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error_of({"scene.epsilon=0"}).find("expected a number with 0 < v <= 1e6"),
            std::string::npos);
}

TEST(Parameters, WarnsOfTheUnboundedSupgUnderTheHigherOrderTimeIndicator)
{
  const auto warnings = [](std::vector<std::string> o) {
    return dwr_warnings(Parameters::from_overrides(o));
  };
  EXPECT_TRUE(warnings({}).empty());
  EXPECT_TRUE(warnings({"adaptivity.time_indicator=higher_order"}).empty());
  EXPECT_TRUE(warnings({"adaptivity.time_indicator=average", "discretization.supg_tau_factor=0"})
                  .empty());
  // higher_order is the default
  EXPECT_EQ(warnings({"discretization.supg_tau_factor=0"}).size(), 1u);
  const auto w = warnings(
      {"adaptivity.time_indicator=higher_order", "discretization.supg_tau_factor=0"});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("discretization.supg_tau_factor = 0"), std::string::npos) << w[0];
  // without SUPG the bound does not matter
  EXPECT_TRUE(warnings({"adaptivity.time_indicator=higher_order",
                        "discretization.supg_tau_factor=0", "discretization.delta0=0"})
                  .empty());
}

TEST(Parameters, DefaultsListEveryChoice)
{
  std::ostringstream out;
  Parameters::print_defaults(out);
  EXPECT_NE(out.str().find("Allowed: Any one of average, adjoint_residual, higher_order"),
            std::string::npos);
  EXPECT_NE(out.str().find("\"time_indicator\": \"higher_order\""), std::string::npos);
}

// adaptivity.adjoint_delta0 sets the adjoint's SUPG delta0 (negative: the primal's);
// adjoint_stabilization = none overrides it with 0; adjoint_inverse_bound caps it on
// cells where the diffusion dominates. The primal space keeps its own.
TEST(Parameters, AdjointDelta0ReachesTheAdjointSpace)
{
  dealii::Triangulation<2> tria;
  dealii::GridGenerator::hyper_cube(tria);
  tria.refine_global(2);
  const auto delta = [&](const std::vector<std::string> &overrides, bool adjoint)
  {
    std::vector<std::string> o = {"discretization.delta0=0.8",
                                  "discretization.supg_tau_factor=0"};
    o.insert(o.end(), overrides.begin(), overrides.end());
    const Parameters p = Parameters::from_overrides(o);
    const auto scene = create_scene<2>(p);
    const auto space = adjoint ? make_adjoint_space(p, *scene, tria, 2)
                               : make_space(p, *scene, tria, 1);
    const auto cell = tria.begin_active();
    return space->delta(cell, 1.) / std::sqrt(cell->measure());
  };
  EXPECT_NEAR(delta({}, false), 0.8, 1e-14);
  EXPECT_NEAR(delta({}, true), 0.1, 1e-14); // the adjoint's own default, 0.1
  EXPECT_NEAR(delta({"adaptivity.adjoint_delta0=-1"}, true), 0.8, 1e-14); // the primal's
  EXPECT_NEAR(delta({"adaptivity.adjoint_delta0=0.3"}, true), 0.3, 1e-14);
  EXPECT_NEAR(delta({"adaptivity.adjoint_delta0=0.3"}, false), 0.8, 1e-14);
  // never more than the primal's: a Galerkin primal has a Galerkin adjoint
  EXPECT_EQ(delta({"discretization.delta0=0"}, true), 0.);
  EXPECT_NEAR(delta({"discretization.delta0=0.05"}, true), 0.05, 1e-14);
  EXPECT_NEAR(delta({"discretization.delta0=0.05", "adaptivity.adjoint_delta0=-1"}, true),
              0.05, 1e-14);
  EXPECT_EQ(delta({"adaptivity.adjoint_delta0=0.1", "adaptivity.adjoint_stabilization=none"},
                  true),
            0.);
  EXPECT_NE(error_of({"adaptivity.adjoint_delta0=-2"}), "");
  // adjoint_inverse_bound (default true): delta_K <= h_min^2 / (eps q^4); with eps = 1,
  // h_min = 1/4, q = 2: 1/256, i.e. delta_K / h_K = 1/64; the primal keeps 0.8
  EXPECT_NEAR(delta({"scene.epsilon=1"}, true), 1. / 64., 1e-14);
  EXPECT_NEAR(delta({"scene.epsilon=1", "adaptivity.adjoint_inverse_bound=false"}, true),
              0.1, 1e-14);
  EXPECT_NEAR(delta({"scene.epsilon=1"}, false), 0.8, 1e-14);
}

// adaptivity.adjoint_outflow = goals: on boundary_layer (b = (1, 0), Dirichlet at x = 0
// (inflow) and x = 1 (outflow), 4 x 4 cells of 1/4) the adjoint's DoFs on x = 1 are
// free exactly on the wall faces of the cells that a goal's support meets and that are
// thicker across the wall than the support; every other Dirichlet DoF stays constrained,
// and the primal's space is untouched.
TEST(Parameters, AdjointOutflowFreesTheWallDofsUnderAThinGoal)
{
  const auto free_wall_dofs = [](const std::string &outflow, const GoalSpec &goal,
                                 bool adjoint = true)
  {
    const Parameters p = Parameters::from_overrides(
        {"scene.name=boundary_layer", "scene.epsilon=1e-3",
         "adaptivity.adjoint_outflow=" + outflow});
    const auto scene = create_scene<2>(p);
    dealii::Triangulation<2> tria;
    scene->make_coarse_grid(tria);
    tria.refine_global(2);
    const auto space = adjoint ? make_adjoint_space(p, *scene, tria, 2, {goal})
                               : make_space(p, *scene, tria, 2);
    // Q2 DoFs on x = 0 and x = 1: 9 per line; count the unconstrained ones
    std::vector<dealii::Point<2>> x(space->n_dofs());
    dealii::DoFTools::map_dofs_to_support_points(space->mapping(), space->dof_handler(), x);
    std::array<unsigned int, 2> free{};
    for (dealii::types::global_dof_index i = 0; i < x.size(); ++i)
      for (const unsigned int side : {0u, 1u})
        if (std::abs(x[i][0] - side) < 1e-12 && !space->constraints().is_constrained(i))
          ++free[side];
    return std::make_pair(free, space->has_natural_outflow());
  };
  GoalSpec strip; // the mean over (0.98, 1) x (0.3, 0.45): the wall cell y in (0.25, 0.5)
  strip.kind = "mean";
  strip.location = {0.98, 0.3, 1., 0.45};
  // one wall face, 3 Q2 DoFs on it; its end vertices are shared with constrained faces
  EXPECT_EQ(free_wall_dofs("goals", strip), std::make_pair(std::array<unsigned int, 2>{{0, 1}},
                                                           true));
  EXPECT_EQ(free_wall_dofs("dirichlet", strip),
            std::make_pair(std::array<unsigned int, 2>{{0, 0}}, false));
  EXPECT_EQ(free_wall_dofs("goals", strip, false),
            std::make_pair(std::array<unsigned int, 2>{{0, 0}}, false));
  // the whole height: all 4 wall faces, all 9 DoFs on x = 1 (the corners' other faces
  // are Neumann)
  GoalSpec tall = strip;
  tall.location = {0.98, 0., 1., 1.};
  EXPECT_EQ(free_wall_dofs("goals", tall).first, (std::array<unsigned int, 2>{{0, 9}}));
  // a support thicker than the cell (0.4 against 0.25 across the wall): Dirichlet
  GoalSpec thick = strip;
  thick.location = {0.6, 0.3, 1., 0.45};
  EXPECT_EQ(free_wall_dofs("goals", thick).first, (std::array<unsigned int, 2>{{0, 0}}));
  // a point goal of radius 0.01 at the inflow wall: nothing (x = 0 is not an outflow)
  GoalSpec point;
  point.kind = "point";
  point.radius = 0.01;
  point.location = {0.005, 0.6};
  EXPECT_EQ(free_wall_dofs("goals", point).first, (std::array<unsigned int, 2>{{0, 0}}));
  // at the outflow wall, inside the cell y in (0.5, 0.75): that face
  point.location = {0.995, 0.6};
  EXPECT_EQ(free_wall_dofs("goals", point).first, (std::array<unsigned int, 2>{{0, 1}}));
  // in the same wall cell but 0.15 from the wall (more than its extent 0.02): nothing
  point.location = {0.85, 0.6};
  EXPECT_EQ(free_wall_dofs("goals", point).first, (std::array<unsigned int, 2>{{0, 0}}));
  EXPECT_NE(error_of({"adaptivity.adjoint_outflow=natural"}), "");
}

TEST(Parameters, AdjointCrosswindFalseLeavesTheTermToThePrimal)
{
  // boundary_layer, eps = 1e-3, cells of 1/4: the crosswind Peclet number |b| h / (2 eps)
  // is 125, so the term acts on every cell of a space that carries it
  const auto acts_on = [](const Space<2> &space)
  {
    unsigned int n = 0;
    for (const auto &cell : space.dof_handler().get_triangulation().active_cell_iterators())
      n += space.cell_diffusion(cell).active;
    return n;
  };
  for (const std::string value : {"true", "false"})
  {
    const Parameters p = Parameters::from_overrides(
        {"scene.name=boundary_layer", "scene.epsilon=1e-3", "discretization.crosswind0=1",
         "adaptivity.adjoint_crosswind=" + value});
    const auto scene = create_scene<2>(p);
    dealii::Triangulation<2> tria;
    scene->make_coarse_grid(tria);
    tria.refine_global(2);
    EXPECT_EQ(acts_on(*make_space(p, *scene, tria, 1)), 16u);
    EXPECT_EQ(acts_on(*make_adjoint_space(p, *scene, tria, 2, scene->default_goals(0.))),
              value == "true" ? 16u : 0u)
        << value;
  }
}
