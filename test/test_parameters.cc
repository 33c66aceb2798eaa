// The options table: struct defaults equal the table's, enums read and print by name,
// and the errors name key, source and value.
#include "base/errors.h"
#include "config/parameters.h"

#include <gtest/gtest.h>

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
  EXPECT_EQ(p.scene.name, SceneName::hemker);
  EXPECT_EQ(p.discretization.supg_length, SupgLength::streamline);
  EXPECT_EQ(p.study.mode, StudyMode::dwr);
  EXPECT_EQ(p.study.refine, StudyRefine::time);
  EXPECT_EQ(p.goal.kind, GoalKind::mean);
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
  EXPECT_NE(error_of({"adaptivity.kappa=2"}).find("expected a fraction in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error_of({"scene.epsilon=0"}).find("expected a number with 0 < v <= 1e6"),
            std::string::npos);
}

TEST(Parameters, DefaultsListEveryChoice)
{
  std::ostringstream out;
  Parameters::print_defaults(out);
  EXPECT_NE(out.str().find("Allowed: Any one of average, adjoint_residual, higher_order"),
            std::string::npos);
  EXPECT_NE(out.str().find("\"time_indicator\": \"average\""), std::string::npos);
}
