// The hemker scene's mesh and the derived-output routines (dwr/probes.h), on
// functions with known answers:
//  - coarse mesh: 10 cells, 196 Q1 DoFs after 2 refinements, boundary ids 0 (x = -3),
//    1 (circle), 2 (rest), refined circle vertices on the circle, area -> 66 - pi;
//  - first crossings and layer width for a linear profile (exact in Q1: to 1e-12) and a
//    tanh profile across the circle's normal (Q2: error < 5e-3 relative, falling
//    by > 5 per refinement);
//  - over-/undershoots of bumps placed at mesh vertices, whole domain and strip.
#include <gtest/gtest.h>

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/vector_tools.h>

#include "scene/scenes.h"
#include "dwr/probes.h"

#include <cmath>
#include <functional>
#include <map>

using namespace dealii;
using namespace anisodwr;

namespace
{
struct Interpolated
{
  Triangulation<2> tria;
  FE_Q<2> fe;
  MappingQ<2> mapping{1};
  DoFHandler<2> dofs;
  Vector<double> u;
  Interpolated(unsigned int degree, unsigned int refinements,
               const std::function<double(const Point<2> &)> &f, bool hemker = true)
      : fe(degree), dofs(tria)
  {
    if (hemker)
      Hemker(1e-6, "").make_coarse_grid(tria);
    else
      GridGenerator::hyper_cube(tria, 0., 1., true);
    tria.refine_global(refinements);
    dofs.distribute_dofs(fe);
    u.reinit(dofs.n_dofs());
    VectorTools::interpolate(
        mapping, dofs,
        ScalarFunctionFromFunctionObject<2>([&](const Point<2> &x) { return f(x); }), u);
  }
};
} // namespace

TEST(HemkerMesh, CoarseMeshBoundaryIdsAndCircle)
{
  Triangulation<2> tria;
  const Hemker scene(1e-6, "");
  scene.make_coarse_grid(tria);
  EXPECT_EQ(tria.n_active_cells(), 10u);
  tria.refine_global(2);
  DoFHandler<2> dofs(tria);
  dofs.distribute_dofs(FE_Q<2>(1));
  EXPECT_EQ(dofs.n_dofs(), 196u);

  std::map<types::boundary_id, double> length;
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
      {
        const auto id = face->boundary_id();
        length[id] += face->measure();
        const Point<2> c = face->center();
        if (id == 0)
          EXPECT_NEAR(c[0], -3., 1e-12);
        else if (id == 1)
          for (unsigned int v = 0; v < 2; ++v)
            EXPECT_NEAR(face->vertex(v).norm(), 1., 1e-12) << "vertex off the circle";
        else
        {
          EXPECT_EQ(id, 2);
          EXPECT_TRUE(std::abs(std::abs(c[1]) - 3.) < 1e-12 ||
                      std::abs(c[0] - 8.) < 1e-12);
        }
      }
  EXPECT_EQ(length.size(), 3u);
  EXPECT_NEAR(length[0], 6., 1e-12);
  EXPECT_NEAR(length[2], 6. + 2. * 11., 1e-12);
  // 2 refinements: the circle is a 32-gon with vertices on it
  EXPECT_NEAR(length[1], 64. * std::sin(M_PI / 32.), 1e-12);
  EXPECT_EQ(scene.dirichlet_ids, (std::set<types::boundary_id>{0, 1}));
  EXPECT_EQ(scene.neumann_ids, (std::set<types::boundary_id>{2}));
  EXPECT_EQ(scene.dirichlet_value(Point<2>(-3., 1.), 0.5), 0.);
  EXPECT_EQ(scene.dirichlet_value(Point<2>(0., 1.), 0.5), 1.);

  // the refined mesh approaches the curved domain: area -> 66 - pi
  tria.refine_global(3);
  EXPECT_NEAR(GridTools::volume(tria), 66. - 256. / 2. * std::sin(2. * M_PI / 256.),
              1e-10);
}

TEST(Probes, LinearProfileCrossingsAreExact)
{
  // u = 1 - 2 (x + y)/sqrt2 / L along the diagonal ray from (0.1, 0.1)
  const Tensor<1, 2> n({1. / std::sqrt(2.), 1. / std::sqrt(2.)});
  const Point<2> a(0.1, 0.1);
  const double L = 1.;
  Interpolated I(
      1, 3, [&](const Point<2> &x) { return 1. - ((x - a) * n) / L; }, false);
  const LineEvaluator<2> line(I.dofs, I.mapping, I.u, a, a + 1.2 * n);
  EXPECT_NEAR(line.length(), 1.2, 1e-14);
  EXPECT_NEAR(line.first_crossing(0.9), 0.1, 1e-12);
  EXPECT_NEAR(line.first_crossing(0.1), 0.9, 1e-12);
  EXPECT_TRUE(std::isnan(line.first_crossing(-0.5))) << "the level is beyond the segment";
  // breakpoints: the diagonal crosses the 8x8 grid at multiples of 1/8 in x and y
  const auto bp = line.breakpoints();
  ASSERT_GE(bp.size(), 2u);
  EXPECT_NEAR(bp.front(), 0., 1e-14);
  for (std::size_t k = 1; k + 1 < bp.size(); ++k)
  {
    const double x = a[0] + bp[k] * n[0];
    EXPECT_NEAR(std::round(8 * x), 8 * x, 1e-10) << "breakpoint " << bp[k];
  }
}

TEST(Probes, TanhLayerWidthAcrossTheCircle)
{
  // u = (1 - tanh((|x| - 1 - c)/w))/2: 0.9 and 0.1 at |x| - 1 = c -+ w atanh(0.8), along
  // the radial ray from x_Gamma. Q2 interpolation: the width error falls like h^3.
  const double c = 0.3, w = 0.08, width = 2. * w * std::atanh(0.8);
  Hemker scene(1e-6, "");
  std::vector<double> error;
  for (unsigned int refinements : {4u, 5u})
  {
    Interpolated I(2, refinements,
                   [&](const Point<2> &x)
                   { return 0.5 * (1. - std::tanh((x.norm() - 1. - c) / w)); });
    const auto r = evaluate_probes(I.dofs, I.mapping, I.u, scene.probes(), scene, 9.);
    error.push_back(std::abs(r.layer_width - width));
    EXPECT_NEAR(r.s_hi, c - w * std::atanh(0.8), 0.06 * width);
    EXPECT_NEAR(r.s_lo, c + w * std::atanh(0.8), 0.06 * width);
    EXPECT_LT(r.overshoot, 1e-12);
    EXPECT_LT(r.undershoot, 1e-12);
  }
  EXPECT_LT(error[1], 5e-3 * width);
  EXPECT_GT(error[0] / error[1], 5.) << "errors " << error[0] << ", " << error[1];
}

TEST(Probes, OverAndUndershootsOfBumpsAtVertices)
{
  // bumps at the vertices (5.5, 0) (+0.3 over 1), (-3, 0) (-0.2 under 0) and (0, 3)
  // (-0.1 under 0, inside the strip -1.5 < x < 1.5)
  auto bump = [](const Point<2> &x, const Point<2> &c)
  { return std::exp(-(x - c).norm_square()); };
  Interpolated I(1, 3,
                 [&](const Point<2> &x)
                 {
                   return 0.5 + 0.8 * bump(x, Point<2>(5.5, 0.)) -
                          0.7 * bump(x, Point<2>(-3., 0.)) -
                          0.6 * bump(x, Point<2>(0., 3.));
                 });
  Hemker scene(1e-6, "");
  const auto r = evaluate_probes(I.dofs, I.mapping, I.u, scene.probes(), scene, 9.);
  EXPECT_NEAR(r.overshoot, 0.3, 1e-6);
  EXPECT_NEAR(r.undershoot, 0.2, 1e-6);
  EXPECT_NEAR(r.undershoot_strip, 0.1, 1e-6);
  EXPECT_EQ(r.overshoot_strip, 0.);
  // the box -1.5 < x < 4.5, 0 < y < 3 holds (0, 3) only on its boundary: the bump's
  // largest value inside is at the vertex below it
  EXPECT_GT(r.undershoot_box, 0.);
  EXPECT_LT(r.undershoot_box, 0.1);
  EXPECT_EQ(r.overshoot_box, 0.);
  EXPECT_NEAR(r.undershoot_x, -3., 1e-12); // the vertex of the deepest bump
  EXPECT_NEAR(r.undershoot_y, 0., 1e-12);
  EXPECT_NEAR(r.overshoot_x, 5.5, 1e-12); // the raised bump's vertex, outside the box
  EXPECT_NEAR(r.overshoot_y, 0., 1e-12);
  EXPECT_TRUE(std::isnan(r.overshoot_goals_x)); // no overshoot in the box
  // the box's deepest point is the vertex below (0, 3) on the line x = 0
  EXPECT_NEAR(r.undershoot_goals_x, 0., 1e-12);
  EXPECT_GT(r.undershoot_goals_y, 2.);
  EXPECT_LT(r.undershoot_goals_y, 3.);
  EXPECT_EQ(r.u_min, 0.);
  EXPECT_EQ(r.u_max, 1.);
}

namespace
{
/// u_0 = x, g_D = 2 on id 0 (x = 0), f = -1, alpha as given, Neumann flux as given on
/// the other sides (ids 1-3 of a colorized unit square), T = 0.5.
class DataScene : public Scene<2>
{
public:
  DataScene(double alpha, double flux) : alpha(alpha), flux(flux)
  {
    end_time = 0.5;
    dirichlet_ids = {0};
    neumann_ids = {1, 2, 3};
  }
  std::string name() const override { return "data"; }
  void make_coarse_grid(Triangulation<2> &tria) const override
  {
    GridGenerator::hyper_cube(tria, 0., 1., true);
  }
  Tensor<1, 2> convection(const Point<2> &, double) const override { return {}; }
  double reaction(const Point<2> &x, double) const override { return alpha * x[1]; }
  bool coefficients_depend_on_time() const override { return false; }
  double rhs(const Point<2> &, double) const override { return -1.; }
  double initial_value(const Point<2> &x) const override { return x[0]; }
  double dirichlet_value(const Point<2> &, double) const override { return 2.; }
  double neumann_value(const Point<2> &x, const Tensor<1, 2> &, double t) const override
  {
    return flux * x[1] * t;
  }
  double alpha, flux;
};
} // namespace

TEST(Probes, BoundsFromTheDataByTheMaximumPrinciple)
{
  // data in [0, 2], alpha > 0 somewhere (0 is a bound), f = -1 over T = 0.5:
  // -0.5 <= u <= 2; u_h = 2.3 - 3.1 x ranges over [-0.8, 2.3]
  // (the colorized unit square of DataScene::make_coarse_grid)
  Interpolated I(1, 3, [](const Point<2> &x) { return 2.3 - 3.1 * x[0]; }, false);
  {
    DataScene scene(1., 0.);
    const auto b = data_bounds(I.dofs, scene);
    ASSERT_TRUE(b.applies) << b.reason;
    EXPECT_DOUBLE_EQ(b.u_min, -0.5);
    EXPECT_DOUBLE_EQ(b.u_max, 2.);
    const auto r = evaluate_probes(I.dofs, I.mapping, I.u, ProbeSpec<2>(), scene, 0.5);
    EXPECT_EQ(r.bounds, "data");
    EXPECT_NEAR(r.overshoot, 0.3, 1e-12);
    EXPECT_NEAR(r.undershoot, 0.3, 1e-12);
    EXPECT_NEAR(r.undershoot_x, 1., 1e-12);
  }
  // alpha < 0 somewhere, or Neumann data not zero: no bounds, NaN over-/undershoots
  for (const auto &[alpha, flux] : {std::pair{-1., 0.}, std::pair{0., 1.}})
  {
    DataScene scene(alpha, flux);
    const auto b = data_bounds(I.dofs, scene);
    EXPECT_FALSE(b.applies);
    const auto r = evaluate_probes(I.dofs, I.mapping, I.u, ProbeSpec<2>(), scene, 0.5);
    EXPECT_EQ(r.bounds.rfind("none", 0), 0u) << r.bounds;
    EXPECT_TRUE(std::isnan(r.overshoot));
  }
}
