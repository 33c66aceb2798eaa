// The custom scene (scene.name = custom): its expressions give the built-in moving
// hump's data, the check against the exact solution catches wrong data, the boundary ids
// and expressions are checked, and the Gmsh domain answers contains().
#include "base/errors.h"
#include "config/parameters.h"
#include "goal/goal_input.h"
#include "scene/custom_scene.h"
#include "scene/separable.h"
#include "space/crosswind_scale.h"
#include "space/space.h"
#include "study/options.h"

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/vector_tools.h>
#include <deal.II/base/function.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace anisodwr;
using dealii::Point;

namespace
{
const std::string src = ANISODWR_SOURCE_DIR;

std::unique_ptr<Scene<2>> scene_of(const std::string &config,
                                   const std::vector<std::string> &overrides = {})
{
  return create_scene<2>(Parameters::read(src + "/config/" + config, overrides));
}

/// The message of the InputError the config with the overrides raises ("" if none).
std::string error_of(const std::string &config, const std::vector<std::string> &overrides)
{
  try
  {
    scene_of(config, overrides);
  }
  catch (const InputError &e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(CustomScene, ReproducesTheMovingHumpsData)
{
  const auto custom = scene_of("custom_moving_hump.json");
  const auto hump = scene_of("moving_hump.json");
  ASSERT_NE(custom->exact(), nullptr);
  EXPECT_FALSE(custom->coefficients_depend_on_time());
  for (const double t : {0., 0.13, 0.37, 0.5})
    for (const double x : {0.05, 0.3, 0.5, 0.71, 0.99})
      for (const double y : {0.02, 0.26, 0.5, 0.8})
      {
        const Point<2> p(x, y);
        const double f = hump->rhs(p, t), u = hump->exact()->value(p, t);
        EXPECT_NEAR(custom->rhs(p, t), f, 1e-12 * std::max(1., std::abs(f)))
            << p << " " << t;
        EXPECT_NEAR(custom->exact()->value(p, t), u, 1e-14) << p << " " << t;
        EXPECT_EQ(custom->convection(p, t), hump->convection(p, t));
        EXPECT_EQ(custom->reaction(p, t), hump->reaction(p, t));
        EXPECT_EQ(custom->initial_value(p), hump->initial_value(p));
      }
  GoalInput in; // goal.kind = scene: scene.goals parsed by the goal layer, radius 0.01
  in.radius = 0.01;
  const auto a = make_goals(in, *custom), b = make_goals(in, *hump);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t g = 0; g < a.size(); ++g)
  {
    EXPECT_EQ(a[g].name, b[g].name);
    EXPECT_EQ(a[g].location, b[g].location);
    EXPECT_EQ(a[g].radius, b[g].radius);
    EXPECT_EQ(a[g].over_time, b[g].over_time);
  }
}

// f(x, t) as sum_k a_k(t) g_k(x): found with the fewest terms where f has that form,
// reproducing f between the sampled times; refused where it has not
TEST(SeparateInTime, FindsTheRankAndReproducesF)
{
  std::vector<Point<2>> points;
  for (int i = 0; i < 40; ++i)
    points.emplace_back(0.025 * i, std::fmod(0.37 * i, 1.));
  const auto rank3 = [](const Point<2> &x, double t)
  { return std::sin(M_PI * t) * x[0] * x[0] + std::cos(3 * t) * std::exp(x[1]) + t * t; };
  std::vector<LoadTerm<2>> terms;
  ASSERT_TRUE(separate_in_time(rank3, true, points, {}, 2., terms));
  EXPECT_EQ(terms.size(), 3u);
  for (const double t : {0., 0.011, 0.73, 1.999})
    for (const Point<2> x : {Point<2>(0.3, 0.9), Point<2>(-0.5, 2.), Point<2>(0.77, 0.01)})
    {
      double f = 0;
      for (const auto &term : terms)
        f += term.a(t) * term.g(x);
      EXPECT_NEAR(f, rank3(x, t), 1e-11) << x << " " << t;
    }
  // a pulse travelling with t is not a short sum of products
  const auto pulse = [](const Point<2> &x, double t)
  { return std::exp(-(x[0] - t) * (x[0] - t) / 0.01); };
  EXPECT_FALSE(separate_in_time(pulse, true, points, {}, 1., terms));
  // a narrow source between the sample points is seen at the dense check points
  const Point<2> x0(0.0125, 0.5);
  const auto hidden = [&](const Point<2> &x, double t)
  { return std::sin(t) * x[0] + std::cos(t) * std::exp(-x.distance_square(x0) / 1e-6); };
  EXPECT_TRUE(separate_in_time(hidden, true, points, {}, 1., terms));
  EXPECT_FALSE(separate_in_time(hidden, true, points, {x0}, 1., terms));
  // no t: one term
  ASSERT_TRUE(separate_in_time(pulse, false, points, {}, 1., terms));
  ASSERT_EQ(terms.size(), 1u);
  EXPECT_EQ(terms[0].a(0.7) * terms[0].g(Point<2>(0.2, 0.)), pulse(Point<2>(0.2, 0.), 0.));
  // the custom moving hump's f (900 characters) is two products
  ASSERT_TRUE(scene_of("custom_moving_hump.json")->separable_rhs(terms));
  EXPECT_EQ(terms.size(), 2u);
}

// config/hemker.msh with scene.manifolds is the built-in Hemker scene's coarse mesh,
// and refines onto the same circle
TEST(CustomScene, MeshFileWithManifoldsGivesHemkersMesh)
{
  const auto custom = scene_of("custom_hemker.json");
  const auto hemker = scene_of("hemker.json");
  dealii::Triangulation<2> a, b;
  custom->make_coarse_grid(a);
  hemker->make_coarse_grid(b);
  a.refine_global(3);
  b.refine_global(3);
  ASSERT_EQ(a.n_active_cells(), b.n_active_cells());
  double on_circle = 0;
  for (auto ca = a.begin_active(), cb = b.begin_active(); ca != a.end(); ++ca, ++cb)
    for (unsigned int v = 0; v < 4; ++v)
    {
      EXPECT_LT(ca->vertex(v).distance(cb->vertex(v)), 1e-14) << ca->vertex(v);
      if (ca->vertex(v).norm() < 1.01)
        on_circle = std::max(on_circle, std::abs(ca->vertex(v).norm() - 1.));
    }
  EXPECT_LT(on_circle, 1e-14);
  // bad items: each message names the key and what was expected
  struct Bad
  {
    std::string config, item, message;
  };
  const std::vector<Bad> bad{
      {"custom_hemker.json", "boundary 7: polar 0, 0",
       "boundary id 7 in key 'scene.manifolds' is not one of the domain"},
      // the inflow line x = -3 is no circle about the origin
      {"custom_hemker.json", "boundary 1: polar 0, 0", "expected one circle about the centre"},
      {"custom_hemker.json", "boundary 4: polar 0.1, 0", "expected one circle about the centre"},
      {"custom_hemker.json", "boundary 4: transfinite", "in key 'scene.manifolds'; expected"},
      // polar cells about a wrong centre would bend the walls; about the right one the
      // square (-3,3)^2 around the hole is still neither arcs nor radial lines
      {"custom_hemker.json", "boundary 4: polar 0, 0; cells 10: polar 5, 5",
       "is neither an arc about (5, 5)"},
      {"custom_hemker.json", "boundary 4: polar 0, 0; cells 10: polar 0, 0",
       "expected cells whose lines are arcs about the centre or radial"},
      {"custom_example.json", "cells 0: transfinite", "key 'scene.manifolds' is for a mesh file"}};
  for (const auto &[config, item, message] : bad)
  {
    const std::string error = error_of(config, {"scene.manifolds=" + item});
    EXPECT_NE(error.find(message), std::string::npos) << item << ": " << error;
  }
}

TEST(CustomScene, ConsistentDataPassTheCheck)
{
  EXPECT_EQ(error_of("custom_example.json", {}), "");
  EXPECT_EQ(error_of("custom_moving_hump.json", {}), "");
}

TEST(CustomScene, CheckCatchesAWrongRhs)
{
  // f without the convection term b.grad u
  const std::string e =
      error_of("custom_example.json",
               {"scene.rhs=exp(-t)*(-eps*sin(a*pi*x)*(2-(a*pi)^2*(1+y^2)))"});
  EXPECT_NE(e.find("key 'scene.rhs' does not match scene.exact_solution"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("PDE residual"), std::string::npos) << e;
  EXPECT_NE(e.find("at (x, y, t) = ("), std::string::npos) << e;
  // a relative error of 1e-4 in f is found at the default tolerance, and accepted at 1e-3
  const std::string f_scaled =
      "scene.rhs=1.0001*exp(-t)*(-eps*sin(a*pi*x)*(2-(a*pi)^2*(1+y^2)) + "
      "bx*a*pi*cos(a*pi*x)*(1+y^2) + by*sin(a*pi*x)*2*y)";
  EXPECT_NE(error_of("custom_example.json", {f_scaled}).find("scene.rhs"),
            std::string::npos);
  EXPECT_EQ(error_of("custom_example.json", {f_scaled, "scene.check_tolerance=1e-3"}),
            "");
}

TEST(CustomScene, CheckCatchesWrongInitialAndBoundaryData)
{
  EXPECT_NE(error_of("custom_example.json", {"scene.initial_value=sin(a*pi*x)"})
                .find("key 'scene.initial_value' does not match"),
            std::string::npos);
  // u vanishes on x = 0, 2: 0 is right there, 1e-3 y is not
  EXPECT_EQ(error_of("custom_example.json", {"scene.dirichlet=0, 1: 0"}), "");
  EXPECT_NE(error_of("custom_example.json", {"scene.dirichlet=0, 1: 1e-3*y"})
                .find("key 'scene.dirichlet' does not match"),
            std::string::npos);
  // the flux with the sign of the inward normal
  EXPECT_NE(error_of("custom_example.json",
                     {"scene.neumann=2, 3: -eps*exp(-t)*(nx*a*pi*cos(a*pi*x)*(1+y^2) + "
                      "ny*sin(a*pi*x)*2*y)"})
                .find("key 'scene.neumann' does not match"),
            std::string::npos);
}

TEST(CustomScene, TimeDependenceFollowsFromTheExpressions)
{
  const std::vector<std::string> steady{"scene.name=custom", "scene.convection=1; x"};
  EXPECT_FALSE(
      create_scene<2>(Parameters::from_overrides(steady))->coefficients_depend_on_time());
  EXPECT_TRUE(create_scene<2>(Parameters::from_overrides(
                                  {"scene.name=custom", "scene.convection=1; sin(t)"}))
                  ->coefficients_depend_on_time());
  EXPECT_TRUE(create_scene<2>(
                  Parameters::from_overrides({"scene.name=custom", "scene.reaction=1+t"}))
                  ->coefficients_depend_on_time());
}

TEST(CustomScene, BoundaryIdsAndExpressionsAreChecked)
{
  const std::string missing = error_of("custom_mesh.json", {"scene.neumann=2: 0"});
  EXPECT_NE(missing.find("boundary id 3 of the domain"), std::string::npos) << missing;
  EXPECT_NE(missing.find("has no condition"), std::string::npos) << missing;
  const std::string unknown = error_of("custom_mesh.json", {"scene.neumann=2, 3, 7: 0"});
  EXPECT_NE(unknown.find("boundary id 7 in key 'scene.neumann' is not a boundary id"),
            std::string::npos)
      << unknown;
  const std::string twice = error_of("custom_mesh.json", {"scene.neumann=1, 2, 3: 0"});
  EXPECT_NE(twice.find("has a condition already"), std::string::npos) << twice;
  const std::string bad = error_of("custom_mesh.json", {"scene.rhs=sin(x"});
  EXPECT_NE(bad.find("invalid expression 'sin(x' for key 'scene.rhs'"), std::string::npos)
      << bad;
  const std::string var = error_of("custom_mesh.json", {"scene.reaction=z*2"});
  EXPECT_NE(var.find("for key 'scene.reaction'"), std::string::npos) << var;
  EXPECT_NE(var.find("\"z\""), std::string::npos) << var;
  const std::string constant =
      error_of("custom_mesh.json", {"scene.constants=t_on = 1/"});
  EXPECT_NE(constant.find("scene.constants"), std::string::npos) << constant;
}

TEST(CustomScene, GmshDomain)
{
  const auto scene = scene_of("custom_mesh.json");
  dealii::Triangulation<2> tria;
  scene->make_coarse_grid(tria);
  EXPECT_EQ(tria.n_active_cells(), 17u);
  const auto box = scene->bounding_box();
  EXPECT_EQ(box[0], Point<2>(0., 0.));
  EXPECT_EQ(box[1], Point<2>(3., 1.));
  EXPECT_TRUE(scene->contains(Point<2>(0.5, 0.5)));
  EXPECT_TRUE(scene->contains(Point<2>(0.75, 0.5))); // on the obstacle's side
  EXPECT_FALSE(scene->contains(Point<2>(1., 0.5)));  // in the obstacle
  EXPECT_FALSE(scene->contains(Point<2>(3.5, 0.5)));
  EXPECT_TRUE(scene->contains_box(Point<2>(1.5, 0.), Point<2>(3., 1.)));
  EXPECT_FALSE(
      scene->contains_box(Point<2>(0.5, 0.), Point<2>(2., 1.))); // holds the hole
  EXPECT_EQ(scene->dirichlet_ids, (std::set<dealii::types::boundary_id>{1, 4}));
  EXPECT_EQ(scene->neumann_ids, (std::set<dealii::types::boundary_id>{2, 3}));
  EXPECT_EQ(scene->boundary_value(Point<2>(1., 0.375), 0.05, 4), 1. - std::exp(-1.));
  EXPECT_EQ(scene->boundary_value(Point<2>(0., 0.5), 0.05, 1), 0.);
  EXPECT_EQ(scene->exact(), nullptr);
}

TEST(CustomScene, GeneratorWithCurvedBoundary)
{
  // deal.II's channel_with_cylinder: (0, 2.2) x (0, 0.41) without the disc of radius
  // 0.05 at (0.2, 0.2), a TransfiniteInterpolationManifold around it; colorized ids 0
  // inflow, 1 outflow, 2 cylinder, 3 walls
  const auto scene = create_scene<2>(Parameters::from_overrides(
      {"scene.name=custom", "scene.grid=channel_with_cylinder",
       "scene.grid_arguments=0.03 : 2 : 2.0 : true", "scene.dirichlet=0: 0; 2: 1",
       "scene.neumann=1, 3: 0"}));
  dealii::Triangulation<2> tria;
  scene->make_coarse_grid(tria);
  tria.refine_global(2);
  double r_min = 1;
  for (const auto &face : tria.active_face_iterators())
    if (face->at_boundary() && face->boundary_id() == 2)
      r_min = std::min(r_min, face->center().distance(Point<2>(0.2, 0.2)));
  EXPECT_NEAR(r_min, 0.05, 1e-3); // face centres on the refined circle
  const auto box = scene->bounding_box();
  EXPECT_NEAR(box[1][0], 2.2, 1e-12);
  EXPECT_NEAR(box[1][1], 0.41, 1e-12);
  EXPECT_FALSE(scene->contains(Point<2>(0.2, 0.2)));
  EXPECT_FALSE(scene->contains(Point<2>(0.2, 0.245)));
  EXPECT_TRUE(scene->contains(Point<2>(0.2, 0.26)));
  EXPECT_TRUE(scene->contains(Point<2>(1., 0.2)));
}

// The cells' map follows the circle between its vertices: the area of Hemker's domain,
// 66 - pi, converges at O(h^2) with MappingQ(1) (the polygon) and at O(h^4) with
// MappingQ(2); auto (discretization.mapping_degree = 0) is isoparametric on curved meshes
// and 1 on straight ones.
TEST(Mapping, CurvedBoundaryAreaConvergesAtTheMapsOrder)
{
  const auto hemker = scene_of("hemker.json");
  const double exact = 66 - M_PI;
  std::vector<double> error[3];
  for (unsigned int k = 1; k <= 3; ++k)
  {
    dealii::Triangulation<2> tria;
    hemker->make_coarse_grid(tria);
    tria.refine_global(k);
    if (k == 1)
    {
      EXPECT_EQ(auto_mapping_degree(tria, 1), 1u);
      EXPECT_EQ(auto_mapping_degree(tria, 2), 2u);
    }
    for (unsigned int m = 1; m <= 2; ++m)
    {
      const Space<2> space(*hemker, tria, 1, Stabilization{}, m);
      EXPECT_EQ(space.mapping_degree(), m);
      dealii::FEValues<2> fv(space.mapping(), space.finite_element(), dealii::QGauss<2>(4),
                             dealii::update_JxW_values);
      double area = 0;
      for (const auto &cell : tria.active_cell_iterators())
      {
        fv.reinit(cell);
        for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
          area += fv.JxW(q);
      }
      error[m].push_back(std::abs(area - exact));
    }
  }
  for (unsigned int k = 0; k + 1 < 3; ++k)
  {
    const double q1 = error[1][k] / error[1][k + 1], q2 = error[2][k] / error[2][k + 1];
    EXPECT_NEAR(q1, 4, 0.4) << "MappingQ(1), refinement " << k + 1;
    EXPECT_GT(q2, 12) << "MappingQ(2), refinement " << k + 1;
    EXPECT_LT(error[2][k + 1], 1e-2 * error[1][k + 1]);
  }
  dealii::Triangulation<2> square;
  dealii::GridGenerator::hyper_cube(square);
  EXPECT_EQ(auto_mapping_degree(square, 3), 1u);
}

namespace
{
/// u(x, y, t) interpolated at the ends t_1, ..., t_N of the slabs (t_0 = times[0]).
std::vector<dealii::Vector<double>>
slab_ends(const Space<2> &space, const std::vector<double> &times,
          const std::function<double(double, double, double)> &u)
{
  std::vector<dealii::Vector<double>> ends;
  for (std::size_t n = 1; n < times.size(); ++n)
  {
    dealii::Vector<double> v(space.n_dofs());
    const double t = times[n];
    dealii::VectorTools::interpolate(
        space.mapping(), space.dof_handler(),
        dealii::ScalarFunctionFromFunctionObject<2>([&](const Point<2> &x)
                                                    { return u(x[0], x[1], t); }),
        v);
    ends.push_back(v);
  }
  return ends;
}
} // namespace

// discretization.crosswind_form = residual: s_K = |R(u_h)| / (|b| |grad u_h|) is 0 where
// u_h solves the transport (a front moving with b, a layer along b), 1 where u_h changes
// along b against the equation and 1/sqrt(2) for a gradient at 45 degrees to b.
TEST(CrosswindScale, ResidualOverTransportHasKnownValues)
{
  const auto check = [](const std::string &u0, const std::function<double(double, double,
                                                                          double)> &u,
                        double expected)
  {
    const auto scene = create_scene<2>(Parameters::from_overrides(
        {"scene.name=custom", "scene.convection=1; 0", "scene.epsilon=1e-3",
         "scene.initial_value=" + u0}));
    dealii::Triangulation<2> tria;
    scene->make_coarse_grid(tria);
    tria.refine_global(2);
    Space<2> space(*scene, tria, 1, Stabilization{});
    space.setup();
    const std::vector<double> times{0., 0.25, 0.5};
    const auto ends = slab_ends(space, times, u);
    const std::vector<double> s = crosswind_scale(space, times, ends);
    ASSERT_EQ(s.size(), tria.n_active_cells());
    for (const double v : s)
      EXPECT_NEAR(v, expected, 1e-12) << "u_0 = " << u0;
    // discretization.crosswind_exponent q: the same ratio, raised to q
    const std::vector<double> s2 = crosswind_scale(space, times, ends, 2.);
    for (const double v : s2)
      EXPECT_NEAR(v, expected * expected, 1e-12) << "u_0 = " << u0 << ", q = 2";
  };
  check("x", [](double x, double, double t) { return x - t; }, 0.); // moves with b
  check("y", [](double, double y, double) { return y; }, 0.);       // a layer along b
  check("x", [](double x, double, double) { return x; }, 1.);       // steady against b
  check("x + y", [](double x, double y, double) { return x + y; }, 1. / std::sqrt(2.));
  check("1", [](double, double, double) { return 1.; }, 0.); // constant: no gradient
}

// The cells are summed on the threads in fixed chunks, each with its own FEValues: the
// factors do not depend on the order in which the threads take the chunks (two threaded
// runs agree bit for bit; a race on the per-cell sums would not), and one thread gives
// them up to round-off (measured: 4e-15).
TEST(CrosswindScale, SameInAnyThreadOrder)
{
  const auto scene = create_scene<2>(Parameters::from_overrides(
      {"scene.name=custom", "scene.convection=1; 0.5", "scene.epsilon=1e-3",
       "scene.initial_value=sin(3*x)*cos(2*y)"}));
  dealii::Triangulation<2> tria;
  scene->make_coarse_grid(tria);
  tria.refine_global(5); // 1,024 cells: four chunks
  Space<2> space(*scene, tria, 1, Stabilization{});
  space.setup();
  const std::vector<double> times{0., 0.25, 0.5};
  const auto ends = slab_ends(space, times, [](double x, double y, double t)
                             { return std::sin(3 * x - t) * std::cos(2 * y); });
  const std::vector<double> all = crosswind_scale(space, times, ends, 2.);
  for (int repeat = 0; repeat < 5; ++repeat)
    EXPECT_EQ(crosswind_scale(space, times, ends, 2.), all) << "repeat " << repeat;
  dealii::MultithreadInfo::set_thread_limit(1);
  const std::vector<double> one = crosswind_scale(space, times, ends, 2.);
  dealii::MultithreadInfo::set_thread_limit();
  ASSERT_EQ(all.size(), one.size());
  for (std::size_t k = 0; k < all.size(); ++k)
    EXPECT_NEAR(all[k], one[k], 1e-13) << "cell " << k;
  // and the factors are not all alike (the field changes along and across b)
  EXPECT_LT(*std::min_element(all.begin(), all.end()),
            *std::max_element(all.begin(), all.end()));
}
