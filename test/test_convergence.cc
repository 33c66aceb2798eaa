// Observed convergence orders on the manufactured scene (through the convergence
// study and its convergence.csv), the moving hump under uniform refinement, and
// the scenes' right-hand sides against the PDE residual of their exact solutions.
#include "config/parameters.h"
#include "scene/scene.h"
#include "scene/scene_registry.h"
#include "study/study.h"
#include "study/options.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

using namespace anisodwr;

namespace
{
using Table = std::vector<std::map<std::string, double>>;

Table read_csv(const std::string &file)
{
  std::ifstream in(file);
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream h(line);
  while (std::getline(h, cell, ','))
    names.push_back(cell);
  Table t;
  while (std::getline(in, line))
  {
    std::stringstream s(line);
    std::map<std::string, double> row;
    for (const auto &n : names)
    {
      std::getline(s, cell, ',');
      row[n] = cell.empty() ? NAN : std::stod(cell);
    }
    t.push_back(row);
  }
  return t;
}

Table run_convergence(const std::string &name, std::vector<std::string> settings)
{
  const std::string dir =
    (std::filesystem::temp_directory_path() / ("anisodwr_test_" + name)).string();
  settings.push_back("study.mode=convergence");
  settings.push_back("output.progress=false");
  settings.push_back("output.directory=" + dir);
  run_study(Parameters::from_overrides(settings));
  return read_csv(dir + "/convergence.csv");
}
} // namespace

class TimeOrders : public ::testing::TestWithParam<unsigned int>
{
};

TEST_P(TimeOrders, DgRConvergesWithOrderRPlus1AndNodal2RPlus1)
{
  // poly_space: the solution lies in Q2 for all t, so the error is purely temporal.
  const unsigned int r = GetParam();
  const auto t = run_convergence("time_r" + std::to_string(r),
                                 {"scene.name=manufactured", "scene.variant=poly_space",
                                  "scene.epsilon=0.01", "scene.end_time=1",
                                  "discretization.p=2", "discretization.r=" + std::to_string(r),
                                  "discretization.delta0=0", "discretization.initial_refinements=1",
                                  "discretization.n_slabs=2", "study.refine=time",
                                  "study.levels=5"});
  ASSERT_EQ(t.size(), 5u);
  const auto &fine = t.back();
  EXPECT_NEAR(fine.at("order_L2L2"), r + 1., 0.2);
  EXPECT_NEAR(fine.at("order_nodal"), 2. * r + 1., 0.2);
  EXPECT_LT(fine.at("err_L2L2"), t.front().at("err_L2L2"));
}

INSTANTIATE_TEST_SUITE_P(R, TimeOrders, ::testing::Values(0u, 1u, 2u));

class SpaceOrders : public ::testing::TestWithParam<unsigned int>
{
};

TEST_P(SpaceOrders, QpConvergesWithOrderPPlus1)
{
  const unsigned int p = GetParam();
  const auto t = run_convergence("space_p" + std::to_string(p),
                                 {"scene.name=manufactured", "scene.epsilon=1",
                                  "discretization.p=" + std::to_string(p), "discretization.r=2",
                                  "discretization.delta0=0", "discretization.initial_refinements=1",
                                  "discretization.n_slabs=16", "study.refine=space",
                                  "study.levels=4"});
  ASSERT_EQ(t.size(), 4u);
  EXPECT_NEAR(t.back().at("order_L2_T"), p + 1., 0.2);
  EXPECT_NEAR(t.back().at("order_L2L2"), p + 1., 0.2);
}

INSTANTIATE_TEST_SUITE_P(P, SpaceOrders, ::testing::Values(1u, 2u));

TEST(RotatingField, TimeDependentCoefficientsConverge)
{
  const auto t = run_convergence("rotating", {"scene.name=manufactured", "scene.variant=rotating",
                                              "scene.epsilon=0.01", "discretization.p=2",
                                              "discretization.r=1", "discretization.delta0=0",
                                              "discretization.initial_refinements=1",
                                              "discretization.n_slabs=2", "study.refine=both",
                                              "study.levels=4"});
  // Both refined by 2: the error behaves like h^3 + tau^2, so the order is >= 2.
  EXPECT_GT(t.back().at("order_L2L2"), 1.8);
}

TEST(MovingHump, ConvergesUnderUniformRefinement)
{
  const auto t =
    run_convergence("hump", {"scene.name=moving_hump", "discretization.p=1", "discretization.r=0",
                             "discretization.delta0=1", "discretization.initial_refinements=3",
                             "discretization.n_slabs=5", "study.refine=both", "study.levels=4"});
  ASSERT_EQ(t.size(), 4u);
  for (std::size_t l = 1; l < t.size(); ++l)
    EXPECT_LT(t[l].at("err_L2_T"), t[l - 1].at("err_L2_T")) << "level " << l;
  EXPECT_LT(t.back().at("err_L2_T"), 0.5 * t.front().at("err_L2_T"));
}

TEST(Scenes, RhsMatchesPdeResidualOfExactSolution)
{
  // f = u_t - eps Lap u + b.grad u + alpha u, checked with central differences of u.
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> d(0.05, 0.95);
  // every registered scene with an exact solution (the custom scene has none with its
  // default keys; custom scenes are checked by their own test)
  unsigned int checked = 0;
  for (const SceneEntry &entry : scene_registry())
    for (const std::string variant : {"", "x"})
    {
      const std::string scene = entry.name;
      std::vector<std::string> s{"scene.name=" + scene, "scene.epsilon=0.01"};
      std::string v = variant;
      if (variant == "x")
        v = scene == "manufactured" ? "rotating" : scene == "heat" ? "trig" : "";
      s.push_back("scene.variant=" + v);
      const auto sc = create_scene<2>(Parameters::from_overrides(s));
      if (!sc->exact())
        continue;
      ++checked;
      const auto &u = *sc->exact();
      // the separable form of f, where the scene gives one (loads and estimator use it)
      std::vector<LoadTerm<2>> terms;
      const bool separable = sc->separable_rhs(terms);
      for (int i = 0; i < 20; ++i)
      {
        const dealii::Point<2> x(d(gen), d(gen));
        const double t = d(gen) * 0.5, h = 1e-4;
        auto U = [&](double dx, double dy, double dt) {
          return u.value(x + dealii::Point<2>(dx, dy), t + dt);
        };
        const double ut = (U(0, 0, h) - U(0, 0, -h)) / (2 * h);
        const double ux = (U(h, 0, 0) - U(-h, 0, 0)) / (2 * h);
        const double uy = (U(0, h, 0) - U(0, -h, 0)) / (2 * h);
        const double lap = (U(h, 0, 0) + U(-h, 0, 0) + U(0, h, 0) + U(0, -h, 0) - 4 * U(0, 0, 0)) /
                           (h * h);
        const auto b = sc->convection(x, t);
        const double f_fd = ut - sc->epsilon * lap + b[0] * ux + b[1] * uy +
                            sc->reaction(x, t) * U(0, 0, 0);
        EXPECT_NEAR(sc->rhs(x, t), f_fd, 1e-4 * (1 + std::abs(f_fd))) << scene << " " << v;
        // Scene::rhs takes a separable u's factors once each: the same value as from the
        // four pointwise derivatives
        const double f_pw = u.time_derivative(x, t) - sc->epsilon * u.laplacian(x, t) +
                            b * u.gradient(x, t) + sc->reaction(x, t) * u.value(x, t);
        EXPECT_NEAR(sc->rhs(x, t), f_pw, 1e-14 * (1 + std::abs(f_pw))) << scene << " " << v;
        if (separable)
        {
          double f = 0;
          for (const auto &term : terms)
            f += term.a(t) * term.g(x);
          EXPECT_NEAR(f, sc->rhs(x, t), 1e-12 * (1 + std::abs(f))) << scene << " " << v;
        }
      }
    }
  // at least moving_hump, manufactured, heat (2 variants each), boundary_layer (2)
  EXPECT_GE(checked, 8u);
}

TEST(Scenes, MovingHumpRhsInsideTheLayerAtEpsilon1e6)
{
  // f against the PDE residual of u at eps = 1e-6, at points inside the circular layer
  // (width ~1e-3), with sixth-order central differences (h = 2e-5: truncation ~(h /
  // 1e-3)^6 ~ 1e-10 relative, rounding ~1e-6 in Lap u, times eps): 1e-8 relative.
  const auto sc = create_scene<2>(
      Parameters::from_overrides({"scene.name=moving_hump", "scene.epsilon=1e-6"}));
  const auto &u = *sc->exact();
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), offset(-2e-3, 2e-3),
      time(0.01, 0.49);
  auto d1 = [](const std::function<double(double)> &g, double h)
  {
    return (-g(-3 * h) + 9 * g(-2 * h) - 45 * g(-h) + 45 * g(h) - 9 * g(2 * h) +
            g(3 * h)) /
           (60 * h);
  };
  auto d2 = [](const std::function<double(double)> &g, double h)
  {
    return (2 * g(-3 * h) - 27 * g(-2 * h) + 270 * g(-h) - 490 * g(0) + 270 * g(h) -
            27 * g(2 * h) + 2 * g(3 * h)) /
           (180 * h * h);
  };
  for (int i = 0; i < 40; ++i)
  {
    const double a = angle(gen), r = 0.25 + offset(gen), t = time(gen), h = 2e-5;
    const dealii::Point<2> x(0.5 + r * std::cos(a), 0.5 + r * std::sin(a));
    auto along = [&](unsigned int dir)
    {
      return [&, dir](double s)
      {
        dealii::Point<2> y = x;
        y[dir] += s;
        return u.value(y, t);
      };
    };
    const double ut = d1([&](double s) { return u.value(x, t + s); }, 1e-4);
    const double ux = d1(along(0), h), uy = d1(along(1), h);
    const double lap = d2(along(0), h) + d2(along(1), h);
    const auto b = sc->convection(x, t);
    const double f_fd = ut - sc->epsilon * lap + b[0] * ux + b[1] * uy +
                        sc->reaction(x, t) * u.value(x, t);
    EXPECT_NEAR(sc->rhs(x, t), f_fd, 1e-8 * (1 + std::abs(f_fd)))
        << "x = " << x << ", t = " << t;
  }
}
