// Marking and mesh closure: the cell marking cuts each marked cell only in the
// directions it needs, the statistics count what was flagged, and the closure of a
// hanging-node chain on an anisotropic mesh refines the coarser cell only in the
// direction the chain needs; cells where u_h leaves its bounds are halved along b; the
// a priori wall layer thins the cells at outflow Dirichlet faces to eps / (b.n).
#include "adaptivity/refinement.h"
#include "base/errors.h"
#include "config/parameters.h"
#include "scene/scene_registry.h"

#include <deal.II/dofs/dof_accessor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <iostream>

using namespace dealii;
using namespace anisodwr;

namespace
{
/// Indicators on a mesh with n active cells: cell c gets (x[c], y[c]).
Indicators<2> indicators(const std::vector<std::array<double, 2>> &eta)
{
  Indicators<2> ind;
  ind.eta_h_cell = eta;
  ind.eta_tau_cell.assign(eta.size(), 0.);
  return ind;
}

std::vector<RefinementCase<2>> flags(const Triangulation<2> &tria)
{
  std::vector<RefinementCase<2>> f(tria.n_active_cells());
  for (const auto &cell : tria.active_cell_iterators())
    f[cell->active_cell_index()] = cell->refine_flag_set();
  return f;
}
} // namespace

TEST(Marking, CellMarkingCutsOnlyTheDirectionsACellNeeds)
{
  Triangulation<2> tria;
  GridGenerator::subdivided_hyper_rectangle(tria, {8, 1}, Point<2>(0, 0), Point<2>(8, 1));
  // four strong cells with different directional balance, four weak ones; signs mixed
  const std::vector<std::array<double, 2>> eta{
      {{1., 0.1}},   {{-0.05, 0.9}}, {{0.6, -0.5}},   {{0.02, 0.02}},
      {{0.8, 0.45}}, {{1e-3, 0.}},   {{0.01, -0.03}}, {{0., 0.}}};
  MarkingOptions opt;
  opt.marking = Marking::cell;
  opt.theta_h = 0.5; // four cells
  opt.kappa = 0.5;
  const MarkingStats s = mark_cells(tria, indicators(eta), opt);
  const auto f = flags(tria);
  EXPECT_EQ(f[0], RefinementCase<2>::cut_x);
  EXPECT_EQ(f[1], RefinementCase<2>::cut_y);
  EXPECT_EQ(f[2], RefinementCase<2>::cut_xy) << "0.5 >= 0.5 * 0.6";
  EXPECT_EQ(f[3], RefinementCase<2>::no_refinement) << "weak cell";
  EXPECT_EQ(f[4], RefinementCase<2>::cut_xy) << "0.45 >= 0.5 * 0.8";
  EXPECT_EQ(s.marked, 4u);
  EXPECT_EQ(s.cut_x, 1u);
  EXPECT_EQ(s.cut_y, 1u);
  EXPECT_EQ(s.cut_both, 2u);
  EXPECT_EQ(s.closure, 0u) << "no hanging-node chain on a one-row mesh";
  EXPECT_EQ(s.refined, 4u);
}

TEST(Marking, KappaOneCutsOnlyTheDominantDirectionAndZeroIsIsotropic)
{
  const std::vector<std::array<double, 2>> eta{
      {{1., 0.9}}, {{0.2, 0.7}}, {{0., 0.}}, {{0., 0.}}};
  for (double kappa : {1., 0.})
  {
    Triangulation<2> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {4, 1}, Point<2>(0, 0),
                                              Point<2>(4, 1));
    MarkingOptions opt;
    opt.marking = Marking::cell;
    opt.theta_h = 0.5;
    opt.kappa = kappa;
    mark_cells(tria, indicators(eta), opt);
    const auto f = flags(tria);
    EXPECT_EQ(f[0], kappa == 1. ? RefinementCase<2>::cut_x : RefinementCase<2>::cut_xy);
    EXPECT_EQ(f[1], kappa == 1. ? RefinementCase<2>::cut_y : RefinementCase<2>::cut_xy);
    EXPECT_EQ(f[2], RefinementCase<2>::no_refinement);
  }
}

TEST(Marking, JointMarkingTakesTheWeakDirectionOfStrongCellsFirst)
{
  // the contrast that motivates `cell`: with joint ranking over (cell, direction)
  // pairs, the weak y indicator of cell 0 (0.5) outranks the only indicator of cell 1
  // (0.4), so cell 0 is cut isotropically and cell 1 not at all
  const std::vector<std::array<double, 2>> eta{
      {{1., 0.5}}, {{0.4, 0.}}, {{0., 0.}}, {{0., 0.}}};
  Triangulation<2> tria;
  GridGenerator::subdivided_hyper_rectangle(tria, {4, 1}, Point<2>(0, 0), Point<2>(4, 1));
  MarkingOptions opt;
  opt.marking = Marking::joint;
  opt.theta_h = 0.25; // 2 of the 8 pairs
  const MarkingStats s = mark_cells(tria, indicators(eta), opt);
  const auto f = flags(tria);
  EXPECT_EQ(f[0], RefinementCase<2>::cut_xy);
  EXPECT_EQ(f[1], RefinementCase<2>::no_refinement);
  EXPECT_EQ(s.cut_both, 1u);
}

TEST(Marking, BulkCriterionMarksTheFewestCellsThatCarryTheFraction)
{
  // cell sums 2, 1, 0.5, 0.3, 0.2, 0 (total 4): theta 0.5 needs the first cell only,
  // 0.75 the first two (3 >= 3), 0.8 the first three; count would take ceil(theta 6)
  const std::vector<std::array<double, 2>> eta{
      {{-1.5, 0.5}}, {{0.1, 0.9}}, {{0.3, -0.2}}, {{0.3, 0.}}, {{0., 0.2}}, {{0., 0.}}};
  for (const auto &[theta, expected] :
       std::vector<std::pair<double, unsigned int>>{{0.5, 1}, {0.75, 2}, {0.8, 3},
                                                    {1., 5}, {0., 0}})
  {
    Triangulation<2> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {6, 1}, Point<2>(0, 0),
                                              Point<2>(6, 1));
    MarkingOptions opt;
    opt.marking = Marking::cell;
    opt.marking_criterion = MarkingCriterion::bulk;
    opt.theta_h = theta;
    opt.kappa = 0.5;
    const MarkingStats s = mark_cells(tria, indicators(eta), opt);
    const auto f = flags(tria);
    EXPECT_EQ(s.marked, expected) << "theta " << theta;
    for (unsigned int c = 0; c < 6; ++c)
      EXPECT_EQ(f[c] != RefinementCase<2>::no_refinement, c < expected)
          << "theta " << theta << ", cell " << c;
    if (expected >= 2)
    {
      EXPECT_EQ(f[1], RefinementCase<2>::cut_y) << "kappa still chooses the directions";
    }
  }
  // the same criterion over the per-direction rankings: x sums 2.2 (1.5 first), y 1.8
  Triangulation<2> tria;
  GridGenerator::subdivided_hyper_rectangle(tria, {6, 1}, Point<2>(0, 0), Point<2>(6, 1));
  MarkingOptions opt;
  opt.marking = Marking::per_direction;
  opt.marking_criterion = MarkingCriterion::bulk;
  opt.theta_h = 0.5; // x: cell 0 (1.5 >= 1.1); y: cell 1 (0.9 >= 0.9)
  mark_cells(tria, indicators(eta), opt);
  const auto f = flags(tria);
  EXPECT_EQ(f[0], RefinementCase<2>::cut_x);
  EXPECT_EQ(f[1], RefinementCase<2>::cut_y);
  EXPECT_EQ(f[2], RefinementCase<2>::no_refinement);
}

namespace
{
/// Two unit cells side by side: L = [0,1]x[0,1], R = [1,2]x[0,1]. L is refined
/// isotropically, then the two children of L that touch R are flagged cut_y (a
/// horizontal cut halves their faces with R), and the flags are closed. R's left face
/// would carry three hanging nodes, so the closure must refine R; the right closure
/// cuts that face only (cut_y), not R isotropically.
void flag_hanging_node_chain(Triangulation<2> &tria)
{
  GridGenerator::subdivided_hyper_rectangle(tria, {2, 1}, Point<2>(0, 0), Point<2>(2, 1));
  tria.begin_active()->set_refine_flag(RefinementCase<2>::cut_xy);
  tria.execute_coarsening_and_refinement();
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->center()[0] > 0.5 && cell->center()[0] < 1.)
      cell->set_refine_flag(RefinementCase<2>::cut_y);
  tria.prepare_coarsening_and_refinement();
}
} // namespace

TEST(Closure, HangingNodeChainIsClosedAnisotropically)
{
  Triangulation<2> tria(Triangulation<2>::allow_anisotropic_smoothing);
  flag_hanging_node_chain(tria);
  unsigned int checked = 0;
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->center()[0] > 1.)
    {
      EXPECT_EQ(cell->refine_flag_set(), RefinementCase<2>::cut_y)
          << "the coarse neighbour is closed in the direction the chain needs";
      ++checked;
    }
  EXPECT_EQ(checked, 1u);
  tria.execute_coarsening_and_refinement();
  // R's two children are stacked in y, each of height 1/2 and width 1
  unsigned int right = 0;
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->center()[0] > 1.)
    {
      EXPECT_NEAR(cell->extent_in_direction(0), 1., 1e-14);
      EXPECT_NEAR(cell->extent_in_direction(1), 0.5, 1e-14);
      ++right;
    }
  EXPECT_EQ(right, 2u);
}

TEST(Closure, DealIIDefaultClosesTheSameChainIsotropically)
{
  // why the DWR triangulation sets allow_anisotropic_smoothing: without it deal.II
  // 9.4 closes the same chain by refining R isotropically
  Triangulation<2> tria;
  flag_hanging_node_chain(tria);
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->center()[0] > 1.)
    {
      EXPECT_EQ(cell->refine_flag_set(), RefinementCase<2>::cut_xy);
    }
}

TEST(Closure, AnisotropicClosureNeedsFewerCellsOnAGradedMesh)
{
  // cuts in x only towards x = 0 and in y only towards y = 0, six times: with the
  // anisotropic closure the mesh stays valid, the closure adds fewer cells than
  // deal.II's isotropic closure, and cells are cut isotropically only where a chain
  // needs both directions
  std::array<unsigned int, 2> cells{}, closure_xy{};
  for (unsigned int variant = 0; variant < 2; ++variant)
  {
    Triangulation<2> tria(variant == 0 ? Triangulation<2>::allow_anisotropic_smoothing
                                       : Triangulation<2>::none);
    GridGenerator::subdivided_hyper_cube(tria, 4);
    for (unsigned int loop = 0; loop < 6; ++loop)
    {
      for (const auto &cell : tria.active_cell_iterators())
      {
        const auto c = cell->center();
        if (c[0] < 0.3 && c[1] > 0.3)
          cell->set_refine_flag(RefinementCase<2>::cut_x);
        else if (c[1] < 0.3 && c[0] > 0.3)
          cell->set_refine_flag(RefinementCase<2>::cut_y);
      }
      tria.prepare_coarsening_and_refinement();
      for (const auto &cell : tria.active_cell_iterators())
        closure_xy[variant] += cell->refine_flag_set() == RefinementCase<2>::cut_xy;
      tria.execute_coarsening_and_refinement();
    }
    cells[variant] = tria.n_active_cells();
  }
  EXPECT_LT(cells[0], cells[1]);
  EXPECT_LT(closure_xy[0], closure_xy[1]);
  std::cout << "active cells: anisotropic closure " << cells[0] << ", isotropic "
            << cells[1] << "; cells closed isotropically " << closure_xy[0] << " vs "
            << closure_xy[1] << "\n";
}

// max_hanging_gap: zero on a straight-sided mesh; on a shell whose cells follow the
// circles, the hanging vertex on the arc r = 1.5 lies the sagitta 1.5 (1 - cos(pi/8))
// off the coarse cell's straight face (45 degree cells), over the fine cells' smallest
// vertex distance, their radial width 0.25.
TEST(Closure, HangingGapIsTheSagittaOverTheFineCellThickness)
{
  Triangulation<2> flat;
  GridGenerator::hyper_cube(flat);
  flat.refine_global(1);
  flat.begin_active()->set_refine_flag();
  flat.execute_coarsening_and_refinement();
  EXPECT_EQ(max_hanging_gap(flat), 0.);

  Triangulation<2> shell;
  GridGenerator::hyper_shell(shell, Point<2>(), 1., 2., 4);
  shell.refine_global(1);
  shell.begin_active()->set_refine_flag();
  shell.execute_coarsening_and_refinement();
  EXPECT_NEAR(max_hanging_gap(shell), 1.5 * (1. - std::cos(M_PI / 8.)) / 0.25, 1e-12);
}

// adaptivity.bound_refinement: the cells around a nodal value outside the bounds are
// halved along b, and only where they are long along b
namespace
{
struct OutOfBounds
{
  Triangulation<2> tria;
  FE_Q<2> fe{1};
  DoFHandler<2> dofs;
  Vector<double> u;
  OutOfBounds()
  {
    // 2 x 8 cells of 1 x 1/16 on [0, 2] x [0, 1/2]: 16 times longer in x than in y
    GridGenerator::subdivided_hyper_rectangle(tria, {2, 8}, Point<2>(0, 0),
                                              Point<2>(2, 0.5));
    dofs.reinit(tria);
    dofs.distribute_dofs(fe);
    u.reinit(dofs.n_dofs());
    u = 0.5;
  }
  /// sets u = value at the vertex nearest to p; returns the number of cells around it
  unsigned int set(const Point<2> &p, double value)
  {
    unsigned int around = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      for (unsigned int v = 0; v < 4; ++v)
        if (cell->vertex(v).distance(p) < 1e-12)
        {
          u[cell->vertex_dof_index(v, 0)] = value;
          ++around;
        }
    return around;
  }
  std::vector<unsigned char> cuts(const Tensor<1, 2> &b) const
  {
    return cells_out_of_bounds<2>(dofs, {u}, 0., 1., 0.05, 10.,
                                  [b](const Point<2> &) { return b; });
  }
};
unsigned int count(const std::vector<unsigned char> &c, unsigned char value)
{
  return std::count(c.begin(), c.end(), value);
}
} // namespace

TEST(BoundRefinement, CellsAroundAnUndershootAreHalvedAlongB)
{
  OutOfBounds m;
  const unsigned int around = m.set(Point<2>(1, 0.25), -0.2);
  ASSERT_EQ(around, 4u);
  const auto cuts = m.cuts(Tensor<1, 2>({1., 0.1}));
  EXPECT_EQ(count(cuts, 1), 4u); // axis 0 (x) + 1
  EXPECT_EQ(count(cuts, 0), m.tria.n_active_cells() - 4);
  const unsigned int before = m.tria.n_active_cells();
  EXPECT_EQ(add_cuts(m.tria, cuts), 4u);
  for (const auto &cell : m.tria.active_cell_iterators())
  {
    if (cell->refine_flag_set())
    {
      EXPECT_EQ(cell->refine_flag_set(), RefinementCase<2>::cut_x);
    }
  }
  m.tria.execute_coarsening_and_refinement();
  EXPECT_EQ(m.tria.n_active_cells(), before + 4);
}

TEST(BoundRefinement, NothingWithinTheThresholdOrOnCellsShortAlongB)
{
  OutOfBounds m;
  m.set(Point<2>(1, 0.25), -0.04); // within 0.05 (u_max - u_min)
  m.set(Point<2>(0, 0.5), 1.04);
  EXPECT_EQ(count(m.cuts(Tensor<1, 2>({1., 0.})), 0), m.tria.n_active_cells());
  m.set(Point<2>(1, 0.25), 1.5);
  // b across the long side: the cells are 16 times shorter along b than across
  EXPECT_EQ(count(m.cuts(Tensor<1, 2>({0., 1.})), 0), m.tria.n_active_cells());
}

TEST(BoundRefinement, AFlagSetByTheMarkingGetsTheUnionOfBothCuts)
{
  OutOfBounds m;
  m.set(Point<2>(2, 0.5), -1.);
  const auto cuts = m.cuts(Tensor<1, 2>({1., 0.}));
  ASSERT_EQ(count(cuts, 1), 1u);
  for (const auto &cell : m.tria.active_cell_iterators())
    if (cuts[cell->active_cell_index()])
      cell->set_refine_flag(RefinementCase<2>::cut_y);
  EXPECT_EQ(add_cuts(m.tria, cuts), 1u);
  for (const auto &cell : m.tria.active_cell_iterators())
  {
    if (cuts[cell->active_cell_index()])
    {
      EXPECT_EQ(cell->refine_flag_set(), RefinementCase<2>::cut_xy);
    }
  }
  EXPECT_EQ(add_cuts(m.tria, cuts), 0u); // nothing left to add
}

// discretization.wall_layer on Hemker's mesh: eps = 1e-6, b = (1, 0); u = 1 on the
// circle. The front half of the circle is outflow for the domain (b.n = -x/|x| > 0),
// the rear half and the inflow x = -3 are not.
namespace
{
struct WallCell
{
  double thickness, bn;
  dealii::types::boundary_id id;
};
/// Every (active cell, Dirichlet face) pair: the cell's thickness across the face and
/// b.n with n the outward normal (the circle's at the face centre).
std::vector<WallCell> wall_cells(const Triangulation<2> &tria)
{
  std::vector<WallCell> w;
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() <= 1)
      {
        const double bn = -cell->face(f)->center()[0] / cell->face(f)->center().norm();
        w.push_back({cell->face(f)->center().distance(cell->face(f ^ 1u)->center()),
                     cell->face(f)->boundary_id() == 1 ? bn : -1., // x = -3: inflow
                     cell->face(f)->boundary_id()});
      }
  return w;
}
} // namespace

TEST(WallLayer, OutflowDirichletCellsGetTheLayerScaleAndNothingElseChanges)
{
  const auto scene = create_scene<2>(
      Parameters::from_overrides({"scene.name=hemker", "scene.epsilon=1e-6"}).scene);
  Triangulation<2> plain, layered;
  for (Triangulation<2> *t : {&plain, &layered})
  {
    scene->make_coarse_grid(*t);
    t->refine_global(2);
  }
  EXPECT_EQ(refine_wall_layer(layered, *scene, 0.).passes, 0u);
  EXPECT_EQ(layered.n_active_cells(), plain.n_active_cells());

  const WallLayer w = refine_wall_layer(layered, *scene, 2.);
  EXPECT_EQ(w.cells_before, plain.n_active_cells());
  EXPECT_EQ(w.cells_after, layered.n_active_cells());
  // the thinnest target is 2 eps / max b.n over the circle's face centres (< 1)
  EXPECT_GE(w.thinnest_target, 2e-6);
  EXPECT_LT(w.thinnest_target, 2e-6 / 0.99);
  // cells of about 0.5 at the front: log2(0.5 / 2e-6) = 17.9 halvings
  EXPECT_GE(w.passes, 17u);
  EXPECT_LE(w.passes, 19u);

  double front_min = 1., rear_min_plain = 1., rear_min = 1., inflow_min_plain = 1.,
         inflow_min = 1.;
  for (const WallCell &c : wall_cells(layered))
  {
    if (c.id == 1 && c.bn > 0.)
    {
      EXPECT_LE(c.thickness, 2e-6 / c.bn * (1. + 1e-9));
      front_min = std::min(front_min, c.thickness);
    }
    else if (c.id == 1 && c.bn < -0.2) // the closure grades the cells near the top
      rear_min = std::min(rear_min, c.thickness);
    else if (c.id == 0)
      inflow_min = std::min(inflow_min, c.thickness);
  }
  for (const WallCell &c : wall_cells(plain))
    if (c.id == 0)
      inflow_min_plain = std::min(inflow_min_plain, c.thickness);
    else if (c.bn < -0.2)
      rear_min_plain = std::min(rear_min_plain, c.thickness);
  // halved until just below the target, not further (a factor 2 per pass)
  EXPECT_GT(front_min, 0.5e-6);
  // the inflow boundary and the rear half of the circle (away from its top, where
  // deal.II's closure grades the cells next to the thinned ones): as without the layer
  EXPECT_DOUBLE_EQ(inflow_min, inflow_min_plain);
  EXPECT_DOUBLE_EQ(rear_min, rear_min_plain);
}

TEST(WallLayer, ALayerBeyondThirtyHalvingsIsAnInputErrorBeforeTheMeshGrows)
{
  const auto scene = create_scene<2>(
      Parameters::from_overrides({"scene.name=hemker", "scene.epsilon=1e-16"}).scene);
  Triangulation<2> tria;
  scene->make_coarse_grid(tria);
  tria.refine_global(2);
  const unsigned int cells = tria.n_active_cells();
  try
  {
    refine_wall_layer(tria, *scene, 1.); // log2(0.5 / 1e-16) = 52 halvings
    FAIL() << "expected an InputError";
  }
  catch (const InputError &e)
  {
    EXPECT_NE(std::string(e.what()).find("discretization.wall_layer"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("at most 30"), std::string::npos);
  }
  EXPECT_EQ(tria.n_active_cells(), cells);
}

// discretization.goal_streak on boundary_layer's unit square (b = (1, 0), T = 1), cells
// of 1/4: a goal at (0.5, 0.5) w = 0.1 wide across b is carried upstream to x = 0.
namespace
{
struct Streaked
{
  GoalStreak streak;
  Triangulation<2> tria;
};
std::unique_ptr<Streaked> streaked(const GoalSpec &goal, double factor)
{
  const auto scene = create_scene<2>(Parameters::from_overrides(
      {"scene.name=boundary_layer", "scene.epsilon=1e-3", "scene.end_time=1"}).scene);
  auto s = std::make_unique<Streaked>();
  scene->make_coarse_grid(s->tria);
  s->tria.refine_global(2);
  s->streak = refine_goal_streak(s->tria, *scene, {goal}, factor);
  return s;
}
} // namespace

TEST(GoalStreak, CellsOnTheUpstreamPathAreHalvedAcrossBToTheTarget)
{
  GoalSpec point;
  point.kind = "point";
  point.location = {0.5, 0.5};
  point.radius = 0.05;
  EXPECT_EQ(streaked(point, 0.)->streak.passes, 0u);
  const auto s = streaked(point, 4.); // target 0.1 / 4 = 0.025 across b
  EXPECT_EQ(s->streak.goals, 1u);
  EXPECT_DOUBLE_EQ(s->streak.thinnest_target, 0.025);
  // 0.25 -> 0.0156 needs four halvings in y; the closure's grading may take one more pass
  EXPECT_GE(s->streak.passes, 4u);
  EXPECT_LE(s->streak.passes, 5u);
  EXPECT_EQ(s->streak.cells_before, 16u);
  EXPECT_EQ(s->streak.cells_after, s->tria.n_active_cells());
  unsigned int on_path = 0;
  double thinnest = 1.;
  for (const auto &cell : s->tria.active_cell_iterators())
  {
    const auto box = cell->bounding_box();
    const double hx = box.side_length(0), hy = box.side_length(1);
    thinnest = std::min(thinnest, hy);
    // every cell that meets the streak 0 < x < 0.5, |y - 0.5| < 0.05 is at most the
    // target thick across b and keeps its length along b (the cuts are across b; only
    // deal.II's closure downstream of the goal's centre, x > 0.5, mixes in cuts along b)
    if (box.upper_bound(0) <= 0.5 + 1e-12 && box.lower_bound(1) < 0.55 &&
        box.upper_bound(1) > 0.45)
    {
      EXPECT_LE(hy, 0.025) << cell->center();
      EXPECT_DOUBLE_EQ(hx, 0.25) << cell->center();
      ++on_path;
    }
    // far across b (|y - 0.5| > 0.3) as before
    if (std::abs(cell->center()[1] - 0.5) > 0.3)
    {
      EXPECT_DOUBLE_EQ(hy, 0.25) << cell->center();
    }
  }
  EXPECT_DOUBLE_EQ(thinnest, 0.25 / 16); // halved just below the target, not further
  EXPECT_GE(on_path, 2u * 7u); // two columns, at least 7 cells across 0.45 < y < 0.55

  // a mean goal over a rectangle 0.1 wide across b is the same streak
  GoalSpec mean;
  mean.kind = "mean";
  mean.location = {0.45, 0.45, 0.55, 0.55};
  const auto m = streaked(mean, 4.);
  EXPECT_EQ(m->tria.n_active_cells(), s->tria.n_active_cells());
  // a flux goal has no streak
  GoalSpec flux;
  flux.kind = "flux";
  flux.location = {1};
  EXPECT_EQ(streaked(flux, 4.)->streak.goals, 0u);
}
