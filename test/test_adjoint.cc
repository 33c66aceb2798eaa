// Goal functionals and the adjoint march (doc/method.md §4-5): the mollifier integrates
// to 1, the transposed space-time operator is the transpose, and with q = p the goal
// value J(u_h) = <J, U> equals the adjoint form <F, Z>.
#include "adaptivity/lifted_goal.h"
#include "config/parameters.h"
#include "base/errors.h"
#include "goal/goal.h"
#include "slab/adjoint_march.h"
#include "study/options.h"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <future>
#include <random>
#include <sstream>

using namespace anisodwr;
using namespace dealii;

namespace
{
std::unique_ptr<Scene<2>> manufactured()
{
  return create_scene<2>(Parameters::from_overrides(
    {"scene.name=manufactured", "scene.variant=constant", "scene.epsilon=0.01"}));
}

void make_mesh(const Scene<2> &scene, Triangulation<2> &tria)
{
  scene.make_coarse_grid(tria);
  tria.refine_global(2);
  tria.begin_active()->set_refine_flag(RefinementCase<2>::cut_x);
  tria.execute_coarsening_and_refinement();
}

/// Every registered goal kind at its example location, at T (weight 1) and over I
/// (weight 0.5), and an exact point value (Dirac) over I.
std::vector<GoalSpec> goals()
{
  const auto scene = manufactured();
  std::vector<GoalSpec> out;
  for (const GoalType *type : goal_types())
    for (const bool over_time : {false, true})
    {
      GoalSpec g;
      g.kind = type->name();
      g.name = type->name() + (over_time ? "_I" : "_T");
      g.over_time = over_time;
      g.weight = over_time ? 0.5 : 1.;
      if (type->has_radius())
        g.radius = 0.15;
      std::vector<double> v;
      std::istringstream in(type->example());
      for (std::string x; std::getline(in, x, ',');)
        v.push_back(std::stod(x));
      try
      {
        type->set_location(v, *scene, type->name() + " example: ", g);
      }
      catch (const InputError &)
      {
        continue; // the kind has no goal of this time part (a flux: over I only)
      }
      out.push_back(g);
    }
  GoalSpec c;
  c.name = "dirac_I";
  c.location = {0.3, 0.3};
  c.over_time = true;
  out.push_back(c);
  return out;
}
} // namespace

TEST(Mollifier, IntegratesToOne)
{
  const auto scene = manufactured();
  Triangulation<2> tria;
  make_mesh(*scene, tria);
  for (unsigned int p : {1u, 2u})
    for (double s : {0.05, 0.2})
    {
      Space<2> space(*scene, tria, p, Stabilization{0., SupgLength::volume, 0.});
      space.setup();
      GoalSpec g;
      g.location = {0.45, 0.5};
      g.radius = s;
      Vector<double> j;
      assemble_goal_vector(space, g, j);
      // sum_i phi_i = 1, so sum_i j(phi_i) = int delta.
      double sum = 0;
      for (const double v : j)
        sum += v;
      EXPECT_NEAR(sum, 1., 1e-6) << "p = " << p << ", s = " << s;
    }
}

TEST(Mollifier, IntegratesToOneToRoundOffOnEveryRule)
{
  // The mollifier is smooth but no polynomial: each path of the goal's quadrature must
  // integrate it to round-off, for p = 1 to 3 (the primal's and the adjoint's spaces).
  // 1 x 1 cells, s = 0.01: a cell 100 s wide (capped; the rule on the support's box);
  // 8 x 8, s = 0.05: a cell 2.5 s wide (the support's box, not capped); 32 x 32 with
  // the goal on a vertex; 64 x 64, s = 0.2: cells of s/12.8 (the cached iterated rule).
  struct Case
  {
    unsigned int cells;
    double s;
    Point<2> c;
  };
  const auto scene = manufactured();
  for (const Case &k : {Case{1, 0.01, Point<2>(0.45, 0.52)}, Case{8, 0.05, Point<2>(0.45, 0.52)},
                        Case{32, 0.05, Point<2>(0.5, 0.5)}, Case{64, 0.2, Point<2>(0.45, 0.5)}})
  {
    Triangulation<2> tria;
    GridGenerator::subdivided_hyper_cube(tria, k.cells);
    for (unsigned int p : {1u, 2u, 3u})
    {
      Space<2> space(*scene, tria, p, Stabilization{0., SupgLength::volume, 0.});
      space.setup();
      GoalSpec g;
      g.location = {k.c[0], k.c[1]};
      g.radius = k.s;
      Vector<double> j;
      assemble_goal_vector(space, g, j);
      double sum = 0;
      for (const double v : j)
        sum += v;
      EXPECT_NEAR(sum, 1., 1e-11) << k.cells << " x " << k.cells << " cells, s = " << k.s
                                  << ", p = " << p;
    }
  }
}

namespace
{
/// j(f) - f(c) for the mollified point goal (center c, radius s) on a cells[0] x
/// cells[1] mesh of the unit square with Q_p and a linear f: the mollifier is radially
/// symmetric, so j(f) = f(c), and Q_p holds f exactly.
double mollified_linear_error(const std::array<unsigned int, 2> &cells, unsigned int p,
                              const Point<2> &c, double s)
{
  const auto scene = manufactured();
  const auto f = [](const Point<2> &x) { return 1. + 2. * x[0] - 3. * x[1]; };
  Triangulation<2> tria;
  GridGenerator::subdivided_hyper_rectangle(tria, {cells[0], cells[1]}, Point<2>(0., 0.),
                                            Point<2>(1., 1.));
  Space<2> space(*scene, tria, p, Stabilization{0., SupgLength::volume, 0.});
  space.setup();
  GoalSpec g;
  g.location = {c[0], c[1]};
  g.radius = s;
  Vector<double> j, fh(space.n_dofs());
  assemble_goal_vector(space, g, j);
  VectorTools::interpolate(space.mapping(), space.dof_handler(),
                           ScalarFunctionFromFunctionObject<2>(f), fh);
  return j * fh - f(c);
}
} // namespace

TEST(Mollifier, ThinCellsIntegrateLinearFunctionsExactly)
{
  // Cells of aspect ratio 64 and 1/64 around the goal (each cut along its own length
  // only, s/16 per sub-cell in each direction) and square cells.
  for (const std::array<unsigned int, 2> cells :
       {std::array<unsigned int, 2>{{4, 256}}, {{256, 4}}, {{32, 32}}})
    for (unsigned int p : {1u, 2u})
      EXPECT_NEAR(mollified_linear_error(cells, p, Point<2>(0.45, 0.52), 0.05), 0., 1e-9)
          << cells[0] << " x " << cells[1] << " cells, p = " << p;
}

TEST(Mollifier, LargeCellsIntegrateLinearFunctionsExactly)
{
  // Cells 25-100 times wider than the support (s = 0.01): the rule is restricted to the
  // part of the cell that holds the support, s/16 per sub-cell. A goal inside one
  // cell and one on a vertex shared by four cells.
  for (const auto &[cells, center] :
       {std::pair<std::array<unsigned int, 2>, Point<2>>{{{1, 1}}, Point<2>(0.45, 0.52)},
        {{{2, 2}}, Point<2>(0.497, 0.504)},
        {{{3, 2}}, Point<2>(0.61, 0.2)}})
    for (unsigned int p : {1u, 2u})
      EXPECT_NEAR(mollified_linear_error(cells, p, center, 0.01), 0., 1e-9)
          << cells[0] << " x " << cells[1] << " cells, p = " << p;
}

TEST(GoalQuadrature, SumFactorizationEqualsFEValuesOnBilinearCells)
{
  // With MappingQ(1) and FE_Q a goal's cell vectors are summed by factors (the bilinear
  // map of the cell's vertices, the FE's 1D Lagrange factors); MappingQ(2) on cells with
  // straight edges is the same map, evaluated through FEValues. Both must agree to
  // round-off on distorted cells, on cells thinned along y near the goal, on cells far
  // wider than the support (the rule on the support's box) and on cells smaller than
  // it (the iterated rule), for point goals of two radii and a mean goal.
  const auto scene = manufactured();
  Triangulation<2> tria;
  GridGenerator::subdivided_hyper_rectangle(tria, {8u, 4u}, Point<2>(0., 0.),
                                            Point<2>(1., 1.));
  GridTools::distort_random(0.3, tria, true, 7);
  for (unsigned int k = 0; k < 4; ++k)
  {
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->center().distance(Point<2>(0.45, 0.52)) < 0.25)
        cell->set_refine_flag(RefinementCase<2>::cut_y);
    tria.execute_coarsening_and_refinement();
  }
  std::vector<GoalSpec> specs(3);
  specs[0].location = {0.45, 0.52};
  specs[0].radius = 0.01;
  specs[1].location = {0.5, 0.5};
  specs[1].radius = 0.2;
  specs[2].kind = "mean";
  specs[2].location = {0.3, 0.4, 0.62, 0.55};
  for (unsigned int p : {1u, 2u, 3u})
  {
    const Stabilization none{0., SupgLength::volume, 0.};
    Space<2> factors(*scene, tria, p, none, 1), fe_values(*scene, tria, p, none, 2);
    factors.setup();
    fe_values.setup();
    for (const GoalSpec &g : specs)
    {
      Vector<double> a, b;
      assemble_goal_vector(factors, g, a);
      assemble_goal_vector(fe_values, g, b);
      ASSERT_EQ(a.size(), b.size());
      Vector<double> d = a;
      d -= b;
      EXPECT_GT(b.linfty_norm(), 0.);
      EXPECT_LE(d.linfty_norm(), 1e-10 * b.linfty_norm())
          << g.kind << " goal, radius " << g.radius << ", p = " << p;
    }
  }
}

// goal.weights = auto takes each goal's sign from d = J(I_2h u_h) - J(u_h). On cells
// without a patch the lift is u_h itself, so d must be exactly 0 there (not the
// difference of two quadratures), and a d at rounding level, whose sign depends on the
// summation order, must give the weight +1/|J|; a goal whose lift does see a
// difference keeps the sign of d.
TEST(AutoWeights, UnseenLiftDifferenceGivesPositiveWeight)
{
  const auto scene = manufactured();
  const TemporalBasis basis(1);
  const TimeMesh mesh = TimeMesh::uniform(0.5, 3);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> dist(0.5, 1.5);
  for (const bool patches : {false, true})
  {
    Triangulation<2> tria;
    if (patches)
      make_mesh(*scene, tria);
    else
      GridGenerator::hyper_cube(tria); // one cell: no sibling, no neighbour, no patch
    Space<2> space(*scene, tria, 1, Stabilization{1.0, SupgLength::volume, 0.});
    space.setup();
    std::vector<Vector<double>> U(mesh.n_slabs(),
                                  Vector<double>(space.n_dofs() * basis.n_dofs()));
    for (auto &x : U)
      for (auto &e : x)
        e = dist(gen);
    for (const GoalSpec &g : goals())
    {
      const double J =
          evaluate_goal(assemble_goal_vectors(space, {unweighted(g)}), mesh, basis, U);
      const double d = lift_difference(space, g, mesh, basis, U);
      const double w = signed_goal_weight(d, J, auto_weight_unseen);
      if (!patches || (g.kind == "point" && g.radius == 0))
      {
        // No patch (on the refined mesh the Dirac's cell lost its patch when its
        // sibling was cut in x): the lift changes nothing.
        EXPECT_EQ(d, 0.) << g.name;
        EXPECT_DOUBLE_EQ(w, 1 / std::abs(J)) << g.name;
        for (const double noise : {-1e-10, 1e-10})
          EXPECT_DOUBLE_EQ(signed_goal_weight(noise * J, J, auto_weight_unseen),
                           1 / std::abs(J));
      }
      else
      {
        EXPECT_GT(std::abs(d), 1e-6 * std::abs(J)) << g.name;
        EXPECT_DOUBLE_EQ(w, (d > 0 ? 1 : -1) / std::abs(J)) << g.name;
      }
    }
  }
  EXPECT_DOUBLE_EQ(signed_goal_weight(-1e-3, -2., auto_weight_unseen), -0.5);
}

TEST(Adjoint, TransposedSpaceTimeOperator)
{
  const auto scene = manufactured();
  Triangulation<2> tria;
  make_mesh(*scene, tria);
  Space<2> space(*scene, tria, 1, Stabilization{1.0, SupgLength::volume, 0.});
  space.setup();
  const TemporalBasis basis(2);
  const unsigned int m = basis.n_dofs(), N = 3;
  SlabOperator<2> op(space, basis, SlabSolverOptions::direct(true));
  op.prepare(0., 0.1);
  const auto &M = op.jump_mass();
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> d(-1., 1.);
  std::vector<Vector<double>> U(N, Vector<double>(space.n_dofs() * m)), Z = U;
  for (auto *v : {&U, &Z})
    for (auto &x : *v)
      for (auto &e : x)
        e = d(gen);
  // (K U)_n = K_n U_n - (e y^T (x) M) U_{n-1};  (K^T Z)_n = K_n^T Z_n - (y e^T (x) M^T) Z_{n+1}
  double lhs = 0, rhs = 0;
  Vector<double> y, trace, c(space.n_dofs());
  for (unsigned int n = 0; n < N; ++n)
  {
    vmult_kron(op.full_terms(), U[n], y);
    if (n > 0)
    {
      combine_blocks(U[n - 1], basis.right_trace(), trace);
      M.vmult(c, trace);
      for (unsigned int i = 0; i < c.size(); ++i)
        for (unsigned int k = 0; k < m; ++k)
          y(i * m + k) -= basis.left_trace()[k] * c(i);
    }
    lhs += y * Z[n];
    vmult_kron(op.full_terms(), Z[n], y, true);
    if (n + 1 < N)
    {
      combine_blocks(Z[n + 1], basis.left_trace(), trace);
      M.Tvmult(c, trace);
      for (unsigned int i = 0; i < c.size(); ++i)
        for (unsigned int k = 0; k < m; ++k)
          y(i * m + k) -= basis.right_trace()[k] * c(i);
    }
    rhs += y * U[n];
  }
  EXPECT_NEAR(lhs, rhs, 1e-11 * std::abs(lhs));
}

class AdjointGoal : public ::testing::TestWithParam<unsigned int>
{
};

TEST_P(AdjointGoal, PrimalGoalEqualsAdjointFormWithEqualSpaces)
{
  const unsigned int r = GetParam();
  const auto scene = manufactured();
  Triangulation<2> tria;
  make_mesh(*scene, tria);
  Space<2> space(*scene, tria, 2, Stabilization{1.0, SupgLength::volume, 0.});
  space.setup();
  const TemporalBasis basis(r);
  const TimeMesh mesh = TimeMesh::uniform(0.5, 4);
  SlabOperator<2> op(space, basis, SlabSolverOptions::direct(true));
  const auto U = march_primal(space, mesh, basis, op, MarchOptions{});
  const GoalVectors j = assemble_goal_vectors(space, goals());
  const auto Z = march_adjoint(space, mesh, basis, op, j, MarchOptions{});
  const double J_primal = evaluate_goal(j, mesh, basis, U);
  // <F, Z>: slab loads plus the SUPG initial term on the first slab.
  const unsigned int m = basis.n_dofs();
  Vector<double> F, u0;
  space.assemble_initial(mesh.tau(0), u0);
  double J_adjoint = 0;
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    assemble_slab_load(space, basis, mesh.start(n), mesh.tau(n), F);
    if (n == 0)
      for (unsigned int i = 0; i < u0.size(); ++i)
        for (unsigned int k = 0; k < m; ++k)
          F(i * m + k) += basis.left_trace()[k] * u0(i);
    J_adjoint += F * Z[n];
  }
  // the constant of affine goals (flux) is not part of the adjoint form
  J_adjoint += j.offset;
  EXPECT_NEAR(J_primal, J_adjoint, 1e-10 * std::abs(J_primal)) << "r = " << r;
  EXPECT_GT(std::abs(J_primal), 1e-2);
}

INSTANTIATE_TEST_SUITE_P(R, AdjointGoal, ::testing::Values(0u, 1u, 2u));

// goal_estimate = consistent with concurrent marches: a primal march by the adjoint's
// factors in a second thread, beside the adjoint's transposed solves on the same
// operator, gives the march of an operator of its own, and the adjoint is unchanged;
// with the coupled UMFPACK factorization and with the temporal modes' factors.
class PreparedMarch : public ::testing::TestWithParam<SolverType>
{
};

TEST_P(PreparedMarch, BesideTheAdjointEqualsItsOwn)
{
  SlabSolverOptions options = SlabSolverOptions::direct(true);
  options.type = GetParam();
  const auto scene = manufactured(); // (inhomogeneous Dirichlet values: the lift acts)
  Triangulation<2> tria;
  make_mesh(*scene, tria);
  Space<2> space(*scene, tria, 2, Stabilization{1.0, SupgLength::volume, 0.});
  space.setup();
  const TemporalBasis basis(1);
  const TimeMesh mesh = TimeMesh::uniform(0.5, 6);
  const GoalVectors j = assemble_goal_vectors(space, goals());
  SlabOperator<2> own(space, basis, options);
  const auto U_own = march_primal(space, mesh, basis, own, MarchOptions{});
  const auto Z_own = march_adjoint(space, mesh, basis, own, j, MarchOptions{});

  SlabOperator<2> op(space, basis, options);
  EXPECT_FALSE(op.prepared_for(mesh)); // (not factorized yet)
  EXPECT_THROW(march_primal_prepared(space, mesh, basis, op, MarchOptions{}), std::logic_error);
  const unsigned int last = mesh.n_slabs() - 1;
  op.prepare(mesh.start(last), mesh.tau(last));
  ASSERT_TRUE(op.prepared_for(mesh));
  auto primal = std::async(std::launch::async, [&]()
                           { return march_primal_prepared(space, mesh, basis, op, MarchOptions{}); });
  const auto Z = march_adjoint(space, mesh, basis, op, j, MarchOptions{});
  const auto U = primal.get();
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    Vector<double> d(U[n]);
    d -= U_own[n];
    EXPECT_LE(d.linfty_norm(), 1e-13 * U_own[n].linfty_norm()) << "slab " << n;
    d = Z[n];
    d -= Z_own[n];
    EXPECT_LE(d.linfty_norm(), 1e-13 * Z_own[n].linfty_norm()) << "slab " << n;
  }
  EXPECT_GT(U_own.back().linfty_norm(), 1e-2);
  EXPECT_EQ(op.modes(), GetParam() == SolverType::modes);

  // not prepared for: slabs of another length, coefficients that depend on time, an
  // operator for transposed solves only
  TimeMesh uneven = mesh;
  uneven.t[1] = 0.5 * uneven.t[1];
  EXPECT_FALSE(op.prepared_for(uneven));
  SlabSolverOptions transposed = options;
  transposed.transposed_only = true;
  SlabOperator<2> adjoint_only(space, basis, transposed);
  adjoint_only.prepare(0., mesh.tau(0));
  EXPECT_FALSE(adjoint_only.prepared_for(mesh));
  const auto rotating = create_scene<2>(Parameters::from_overrides(
      {"scene.name=manufactured", "scene.variant=rotating", "scene.epsilon=0.01"}));
  Triangulation<2> tria_r;
  make_mesh(*rotating, tria_r);
  Space<2> space_r(*rotating, tria_r, 1, Stabilization{1.0, SupgLength::volume, 0.});
  space_r.setup();
  SlabOperator<2> op_r(space_r, basis, options);
  op_r.prepare(0., mesh.tau(0));
  EXPECT_FALSE(op_r.prepared_for(mesh));
}

INSTANTIATE_TEST_SUITE_P(Solver, PreparedMarch,
                         ::testing::Values(SolverType::direct, SolverType::modes));
