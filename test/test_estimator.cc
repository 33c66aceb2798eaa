// Localization of the DWR indicators (doc/method.md §6): the cell-wise forms of the
// estimator (strong cell residual + half flux jumps + boundary terms + temporal jumps
// for rho; cell-wise weak forms for the adjoint residual; SUPG terms) summed over all
// cells equal the global weak forms, computed independently from the assembled
// Kronecker slab operator, to round-off: random continuous functions (hanging nodes,
// anisotropic cells), polynomial-in-space data, time-dependent b and alpha.
#include "adaptivity/estimator.h"
#include "adaptivity/short_vectors.h"
#include "config/parameters.h"
#include "io/loop_report.h"
#include "slab/adjoint_march.h"
#include "slab/primal_march.h"
#include "space/stabilization_terms.h"
#include "study/options.h"
#include "time/slab_vector.h"

#include <deal.II/base/multithread_info.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace anisodwr;
using namespace dealii;

namespace
{
void make_mesh(Triangulation<2> &tria)
{
  GridGenerator::hyper_cube(tria, 0., 1.);
  tria.refine_global(2);
  auto cell = tria.begin_active();
  cell->set_refine_flag(RefinementCase<2>::cut_x);
  (++cell)->set_refine_flag(RefinementCase<2>::isotropic_refinement);
  std::next(cell, 5)->set_refine_flag(RefinementCase<2>::cut_y);
  tria.execute_coarsening_and_refinement();
}

/// Random continuous function per temporal node (hanging-node constraints only, so
/// boundary values are random too).
std::vector<Vector<double>> random_function(const Space<2> &space, unsigned int m,
                                            unsigned int n_slabs, unsigned int seed)
{
  AffineConstraints<double> hanging;
  DoFTools::make_hanging_node_constraints(space.dof_handler(), hanging);
  hanging.close();
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1., 1.);
  std::vector<Vector<double>> U(n_slabs, Vector<double>(space.n_dofs() * m));
  for (auto &Un : U)
    for (unsigned int k = 0; k < m; ++k)
    {
      Vector<double> u(space.n_dofs());
      for (auto &v : u)
        v = dist(gen);
      hanging.distribute(u);
      insert_block(u, k, m, Un);
    }
  return U;
}

/// K_n V_n - C_n(V_{n-1}) with the full (unconstrained) matrices of `space`;
/// C_0 = 0 (no jump before t_0).
Vector<double> operator_apply(const Space<2> &space, const TemporalBasis &basis,
                              const TimeMesh &mesh, unsigned int n,
                              const std::vector<Vector<double>> &V)
{
  SlabOperator<2> op(space, basis, SlabSolverOptions::direct(false));
  op.prepare(mesh.start(n), mesh.tau(n));
  Vector<double> out(V[n].size()), last, c(space.n_dofs());
  vmult_kron(op.full_terms(), V[n], out);
  if (n > 0)
  {
    combine_blocks(V[n - 1], basis.right_trace(), last);
    op.jump_mass().vmult(c, last);
    add_kron_vector(-1., basis.left_trace(), c, out);
  }
  return out;
}

/// F_n (+ the initial term at n = 0).
Vector<double> load(const Space<2> &space, const TemporalBasis &basis,
                    const TimeMesh &mesh, unsigned int n)
{
  Vector<double> F;
  assemble_slab_load(space, basis, mesh.start(n), mesh.tau(n), F);
  if (n == 0)
  {
    Vector<double> u0;
    space.assemble_initial(mesh.tau(0), u0);
    add_kron_vector(1., basis.left_trace(), u0, F);
  }
  return F;
}

bool crosswind(const std::string &variant)
{
  return variant.find("+crosswind") != std::string::npos;
}
std::string base_variant(const std::string &variant)
{
  return variant.substr(0, variant.find('+'));
}

struct Problem
{
  std::unique_ptr<Scene<2>> scene;
  Triangulation<2> tria;
  std::unique_ptr<Space<2>> galerkin, supg;
  TemporalBasis basis;
  TimeMesh mesh;
  /// `variant` poly_space: b, alpha depend on t; constant: they do not (the estimator
  /// then applies A and S' through cell matrices). A suffix "+crosswind" adds the
  /// crosswind diffusion (crosswind0 = 0.8) to the stabilized space, with eps = 1e-3 so
  /// that it acts on every cell; "+crosswind_scaled" scales it per cell by factors
  /// 0.2-1 (Space::set_crosswind_scale, crosswind_form = residual).
  Problem(unsigned int p, unsigned int r, const std::string &variant = "poly_space")
      : scene(create_scene<2>(Parameters::from_overrides(
            {"scene.name=manufactured", "scene.variant=" + base_variant(variant),
             crosswind(variant) ? "scene.epsilon=1e-3" : "scene.epsilon=0.5"}))),
        basis(r), mesh(TimeMesh::uniform(0.6, 2))
  {
    mesh.t[1] = 0.25; // unequal slabs
    make_mesh(tria);
    galerkin = std::make_unique<Space<2>>(*scene, tria, p,
                                          Stabilization{0., SupgLength::volume, 0.});
    Stabilization stab{0.7, SupgLength::volume, 0.};
    stab.crosswind0 = crosswind(variant) ? 0.8 : 0.;
    supg = std::make_unique<Space<2>>(*scene, tria, p, stab);
    if (variant.find("+crosswind_scaled") != std::string::npos)
    {
      // crosswind_form = residual: a different factor on each cell
      std::vector<double> scale(tria.n_active_cells());
      for (std::size_t k = 0; k < scale.size(); ++k)
        scale[k] = 0.2 + 0.8 * double(k % 5) / 4.;
      supg->set_crosswind_scale(scale);
    }
    for (const auto &cell : tria.active_cell_iterators())
      if (crosswind(variant) && !supg->cell_diffusion(cell).active)
        throw std::logic_error("the crosswind term must act on every cell");
    galerkin->setup();
    supg->setup();
  }
};

} // namespace

class Localization
    : public ::testing::TestWithParam<std::tuple<unsigned int, const char *>>
{
};

// poly_space: the data are polynomials in space, so both sides integrate the loads
// exactly and the whole forms are compared. constant (b, alpha constant in time: the
// estimator applies rho and S through cell matrices): f = sin(pi x) sin(pi y)-type data,
// integrated with different rules on the two sides, so the parts linear in u are
// compared: rho(U)(W) - rho(0)(W) = -W . A U (likewise S).
TEST_P(Localization, PrimalResidualAndSupgSumToGlobalForms)
{
  Problem s(1, std::get<0>(GetParam()), std::get<1>(GetParam()));
  const bool exact_data = std::string(std::get<1>(GetParam())) == "poly_space";
  const unsigned int m = s.basis.n_dofs(), N = s.mesh.n_slabs();
  const auto U = random_function(*s.galerkin, m, N, 1),
             W = random_function(*s.galerkin, m, N, 2);
  std::vector<Vector<double>> zero(U);
  for (auto &z : zero)
    z = 0.;
  auto rho =
      LocalizedForms<2>::primal_residual(*s.supg, *s.galerkin, s.mesh, s.basis, U, W);
  auto S = LocalizedForms<2>::supg(*s.supg, *s.galerkin, s.mesh, s.basis, U, W);
  if (!exact_data)
  {
    const auto rho0 = LocalizedForms<2>::primal_residual(*s.supg, *s.galerkin, s.mesh,
                                                         s.basis, zero, W);
    const auto S0 =
        LocalizedForms<2>::supg(*s.supg, *s.galerkin, s.mesh, s.basis, zero, W);
    for (unsigned int n = 0; n < N; ++n)
    {
      rho[n] -= rho0[n];
      S[n] -= S0[n];
    }
  }
  for (unsigned int n = 0; n < N; ++n)
  {
    Vector<double> r0(U[n].size()), rd(U[n].size());
    if (exact_data)
    {
      r0 = load(*s.galerkin, s.basis, s.mesh, n);
      rd = load(*s.supg, s.basis, s.mesh, n);
    }
    r0 -= operator_apply(*s.galerkin, s.basis, s.mesh, n, U);
    rd -= operator_apply(*s.supg, s.basis, s.mesh, n, U);
    const double global_rho = W[n] * r0;
    Vector<double> diff = r0;
    diff -= rd;
    const double global_S = W[n] * diff;
    EXPECT_NEAR(rho[n], global_rho, 1e-10 * std::max(1., std::abs(global_rho)))
        << "slab " << n;
    EXPECT_NEAR(S[n], global_S, 1e-10 * std::max(1., std::abs(global_S))) << "slab " << n;
    EXPECT_GT(std::abs(global_S), 1e-3) << "SUPG part must not be trivially zero";
  }
}

class AdjointLocalization
    : public ::testing::TestWithParam<std::tuple<unsigned int, const char *>>
{
};

TEST_P(AdjointLocalization, AdjointFormsSumToGlobalForms)
{
  Problem s(1, std::get<0>(GetParam()), std::get<1>(GetParam()));
  const unsigned int m = s.basis.n_dofs(), N = s.mesh.n_slabs();
  const auto V = random_function(*s.galerkin, m, N, 3),
             Z = random_function(*s.galerkin, m, N, 4);
  const auto A =
      LocalizedForms<2>::adjoint_form(*s.supg, *s.galerkin, s.mesh, s.basis, V, Z, false);
  const auto Sd =
      LocalizedForms<2>::adjoint_form(*s.supg, *s.galerkin, s.mesh, s.basis, V, Z, true);
  for (unsigned int n = 0; n < N; ++n)
  {
    const Vector<double> a0 = operator_apply(*s.galerkin, s.basis, s.mesh, n, V);
    Vector<double> ad = operator_apply(*s.supg, s.basis, s.mesh, n, V);
    ad -= a0;
    EXPECT_NEAR(A[n], Z[n] * a0, 1e-10 * std::max(1., std::abs(Z[n] * a0)))
        << "slab " << n;
    EXPECT_NEAR(Sd[n], Z[n] * ad, 1e-10 * std::max(1., std::abs(Z[n] * ad)))
        << "slab " << n;
  }
}

// "+crosswind": the crosswind diffusion of the stabilized space is part of S and S';
// "+crosswind_scaled" with a per-cell factor on it
INSTANTIATE_TEST_SUITE_P(TemporalDegreeAndCoefficients, Localization,
                         ::testing::Combine(::testing::Values(0u, 1u, 2u),
                                            ::testing::Values("poly_space", "constant",
                                                              "poly_space+crosswind",
                                                              "constant+crosswind",
                                                              "constant+crosswind_scaled")));
INSTANTIATE_TEST_SUITE_P(TemporalDegreeAndCoefficients, AdjointLocalization,
                         ::testing::Combine(::testing::Values(0u, 1u, 2u),
                                            ::testing::Values("poly_space", "constant",
                                                              "poly_space+crosswind",
                                                              "constant+crosswind",
                                                              "constant+crosswind_scaled")));

/// a and b cell by cell, slab by slab and part by part within rel times the largest cell
/// indicator (rel = 0: bit for bit).
void expect_indicators_near(const Indicators<2> &a, const Indicators<2> &b, double rel);

// TimeIndicator::higher_order: eta_tau = rho*(u, z)(u_r+1 - u) + J_T(u_r+1(T) - u(T)).
// Heat with u = (x^2 - x)(y^2 - y)(-t/4): Q2 in space, linear in t, so dG(1) (u_r+1)
// is exact and dG(0) (u) is not; with q = p and b = 0 (no SUPG), the discrete adjoint
// lies in the primal test space, Galerkin orthogonality removes A(u_r+1 - u, z), and
// eta_tau equals the temporal error J(u_r+1) - J(u) to round-off, for a goal at T and a
// goal over I (means over unions of cells, which the estimator's goal representation in
// the weight space and the goal vectors integrate exactly; other goals differ by
// quadrature). The Radau reconstruction E u - u vanishes at the nodes, so the
// adjoint_residual form misses J_T's end part: the contrast shows the test can fail.
TEST(TimeIndicator, HigherOrderIsExactForPolynomialTemporalError)
{
  const auto scene = create_scene<2>(Parameters::from_overrides(
      {"scene.name=heat", "scene.variant=poly", "scene.epsilon=0.1"}));
  Triangulation<2> tria;
  make_mesh(tria);
  Space<2> space(*scene, tria, 2, Stabilization{0., SupgLength::volume, 0.});
  space.setup();
  const TemporalBasis basis(0), basis_hi(1);
  const TimeMesh mesh = TimeMesh::uniform(0.5, 4);
  SlabOperator<2> op(space, basis, SlabSolverOptions::direct(true));
  SlabOperator<2> op_hi(space, basis_hi, SlabSolverOptions::direct(true));
  const auto U = march_primal(space, mesh, basis, op, MarchOptions{});
  const auto U_hi = march_primal(space, mesh, basis_hi, op_hi, MarchOptions{});
  GoalSpec at_T, over_I;
  at_T.name = "mean_T";
  at_T.kind = "mean";
  // rectangles x0, y0, x1, y1 on cell faces: both goal representations integrate them
  // exactly
  at_T.location = {0.25, 0.25, 0.75, 0.75};
  over_I.name = "mean_I";
  over_I.kind = "mean";
  over_I.location = {0.5, 0., 1., 0.5};
  over_I.over_time = true;
  over_I.weight = 0.5;
  const HigherOrderPrimal hi{basis_hi, U_hi};
  std::vector<std::vector<Vector<double>>> Z_alone;
  std::vector<Indicators<2>> alone;
  for (const auto &goals :
       std::vector<std::vector<GoalSpec>>{{at_T}, {over_I}, {at_T, over_I}})
  {
    const GoalVectors j = assemble_goal_vectors(space, goals);
    const auto Z = march_adjoint(space, mesh, basis, op, j, MarchOptions{});
    const double err_tau =
        evaluate_goal(j, mesh, basis_hi, U_hi) - evaluate_goal(j, mesh, basis, U);
    MultithreadInfo::set_thread_limit(1); // (bit-identical comparison below)
    const auto ind = estimate(space, space, mesh, basis, U, Z, goals,
                              TimeIndicator::higher_order, &hi);
    MultithreadInfo::set_thread_limit();
    if (goals.size() == 1)
    {
      Z_alone.push_back(Z);
      alone.push_back(ind);
    }
    EXPECT_GT(std::abs(err_tau), 1e-5);
    EXPECT_NEAR(ind.eta_tau, err_tau, 1e-9 * std::abs(err_tau))
        << goals.size() << " goal(s)";
    double slab_sum = 0;
    for (const double e : ind.eta_tau_slab)
      slab_sum += e;
    EXPECT_NEAR(slab_sum, ind.eta_tau, 1e-12 * std::abs(err_tau));
    if (goals.size() == 1 && !goals[0].over_time)
    {
      const auto radau = estimate(space, space, mesh, basis, U, Z, goals,
                                  TimeIndicator::adjoint_residual);
      EXPECT_GT(std::abs(radau.eta_tau - err_tau), 1e-3 * std::abs(err_tau));
    }
  }
  // both adjoints in one pass: each gets its estimate alone, bit for bit
  MultithreadInfo::set_thread_limit(1);
  const auto each = estimate_each(space, space, mesh, basis, U,
                                  {{&Z_alone[0], {at_T}}, {&Z_alone[1], {over_I}}},
                                  TimeIndicator::higher_order, &hi);
  MultithreadInfo::set_thread_limit();
  ASSERT_EQ(each.size(), 2u);
  for (unsigned int i = 0; i < 2; ++i)
    expect_indicators_near(alone[i], each[i], 0.);
  EXPECT_THROW(
      estimate(space, space, mesh, basis, U, U, {at_T}, TimeIndicator::higher_order),
      std::invalid_argument);
}

/// The moving hump (SUPG on) on make_mesh() refined `refinements` more times: Q1 primal
/// and Q2 adjoint in dG(1) on 3 slabs, the scene's two point goals at T.
struct HumpProblem
{
  explicit HumpProblem(unsigned int refinements,
                       const std::vector<std::string> &scene_keys = {"scene.name=moving_hump"})
      : scene(create_scene<2>(Parameters::from_overrides(scene_keys)))
  {
    make_mesh(tria);
    tria.refine_global(refinements);
    primal.setup();
    adjoint.setup();
    SlabOperator<2> op(primal, basis, SlabSolverOptions::direct(true));
    SlabOperator<2> opq(adjoint, basis, SlabSolverOptions::direct(true));
    U = march_primal(primal, mesh, basis, op, MarchOptions{});
    goals = scene->default_goals(0.1);
    Z = march_adjoint(adjoint, mesh, basis, opq, assemble_goal_vectors(adjoint, goals),
                      MarchOptions{});
  }
  Indicators<2> estimate(SpaceIndicator form, const DataQuadrature &data = {}) const
  {
    return anisodwr::estimate(primal, adjoint, mesh, basis, U, Z, goals,
                              TimeIndicator::average, nullptr, form, data);
  }

  std::unique_ptr<Scene<2>> scene;
  Triangulation<2> tria;
  const Stabilization supg{1., SupgLength::volume, 0.};
  Space<2> primal{*scene, tria, 1, supg}, adjoint{*scene, tria, 2, supg};
  const TemporalBasis basis{1};
  const TimeMesh mesh = TimeMesh::uniform(0.5, 3);
  std::vector<GoalSpec> goals;
  std::vector<Vector<double>> U, Z;
};

// eta_h_split_rest = sum_i rho(u)(z - R_i z) - rho(u)(z - R_h z) = rho(u)((I - R_1)(I -
// R_2) z): zero for a weight without mixed x-y content, z = f(x) + g(y) (its Q2
// interpolant on the moving hump's rectangles is again a sum of a function of x and one
// of y, which R_2 resp. R_1 leave alone), nonzero for z = f(x) g(y), and linear in z.
TEST(SpaceIndicator, SplitRestSeesOnlyMixedContent)
{
  HumpProblem hump(1);
  const auto weight_of = [&](const std::function<double(const Point<2> &)> &f)
  {
    Vector<double> z(hump.adjoint.n_dofs());
    VectorTools::interpolate(hump.adjoint.mapping(), hump.adjoint.dof_handler(),
                             ScalarFunctionFromFunctionObject<2>(f), z);
    const SlabLayout slab{hump.basis.n_dofs()};
    std::vector<Vector<double>> Z(hump.mesh.n_slabs(),
                                  Vector<double>(z.size() * hump.basis.n_dofs()));
    for (auto &Zn : Z)
      for (std::size_t i = 0; i < z.size(); ++i)
        for (unsigned int k = 0; k < slab.m; ++k)
          Zn(slab.index(i, k)) = z(i);
    return Z;
  };
  const auto separate = weight_of([](const Point<2> &x)
                                  { return std::sin(3 * x[0]) + std::cos(2 * x[1]); });
  const auto mixed = weight_of([](const Point<2> &x)
                               { return std::sin(3 * x[0]) * std::cos(2 * x[1]); });
  const auto estimate_with = [&](const std::vector<Vector<double>> &Z)
  {
    hump.Z = Z;
    return hump.estimate(SpaceIndicator::primal_residual);
  };
  const auto a = estimate_with(separate), b = estimate_with(mixed);
  auto both = separate;
  for (std::size_t n = 0; n < both.size(); ++n)
    both[n] += mixed[n];
  const auto c = estimate_with(both);
  const double scale_a = std::abs(a.eta_h_rho), scale_b = std::abs(b.eta_h_rho);
  ASSERT_GT(scale_a, 0.);
  ASSERT_GT(scale_b, 0.);
  EXPECT_LE(std::abs(a.eta_h_split_rest), 1e-12 * scale_a);
  EXPECT_GT(std::abs(b.eta_h_split_rest),
            1e-5 * scale_b); // measured 7e-4: O(h^4) against O(h^2)
  EXPECT_NEAR(c.eta_h_split_rest, b.eta_h_split_rest, 1e-12 * (scale_a + scale_b));
}

// The parts of eta_h reported in loops.csv add up to eta_h in both forms: average =
// 1/2 rho + adjoint half + S, primal_residual = rho + S (no adjoint half); the primal
// half and the SUPG term do not depend on the form. Moving hump (SUPG on), Q1/Q2 on the
// anisotropic mesh, dG(1), a point goal at T.
TEST(SpaceIndicator, PartsSumToEtaHInBothForms)
{
  const HumpProblem hump(1);
  const auto avg = hump.estimate(SpaceIndicator::average);
  const auto pr = hump.estimate(SpaceIndicator::primal_residual);
  const double scale =
      std::abs(avg.eta_h_rho) + std::abs(avg.eta_h_rhostar) + std::abs(avg.eta_h_supg);
  ASSERT_GT(scale, 0.);
  EXPECT_GT(std::abs(avg.eta_h_rhostar), 1e-6 * scale); // the forms differ
  EXPECT_NEAR(avg.eta_h_total(),
              avg.eta_h_rho + avg.eta_h_rhostar + avg.eta_h_supg + avg.eta_h_quad,
              1e-12 * scale);
  EXPECT_NEAR(pr.eta_h_total(), 2 * pr.eta_h_rho + pr.eta_h_supg + pr.eta_h_quad,
              1e-12 * scale);
  EXPECT_EQ(pr.eta_h_rhostar, 0.);
  EXPECT_NEAR(pr.eta_h_rho, avg.eta_h_rho, 1e-12 * scale);
  EXPECT_NEAR(pr.eta_h_supg, avg.eta_h_supg, 1e-12 * scale);
  EXPECT_NEAR(pr.eta_tau, avg.eta_tau, 1e-12 * scale);
  // per cell: the directional indicators of primal_residual sum to its eta_h
  double cells = 0;
  for (const auto &c : pr.eta_h_cell)
    cells += c[0] + c[1];
  EXPECT_NEAR(cells, pr.eta_h_total(), 1e-12 * scale);
}

/// sum over cells of |eta_h,x^K| + |eta_h,y^K|
double cell_scale(const Indicators<2> &a)
{
  double scale = 0;
  for (const auto &c : a.eta_h_cell)
    scale += std::abs(c[0]) + std::abs(c[1]);
  return scale;
}

// Galerkin orthogonality at hanging nodes (adaptivity/hanging_defect.h): for the
// discrete primal u and any continuous z vanishing on Gamma_D, the primal-residual
// indicators minus the directional split's rest and the Dirichlet data's share equal
// rho(u)(z) summed cell by cell (LocalizedForms), because the interpolant they subtract
// is the conforming I_h z, for which rho(u)(I_h z) = S(u)(I_h z) + D(I_h z) holds
// exactly. Moving hump, SUPG, Q1/Q2, dG(1), the test mesh's hanging nodes on faces in
// both directions. The cell-wise interpolant R_h z (conforming_weights = false) misses
// this identity by rho(u)(R_h z - I_h z): by 0.15 of the indicators' scale here (0.122
// against 0.046); the cells' indicators sum to eta_h in both.
TEST(Estimator, GalerkinOrthogonalityAtHangingNodes)
{
  HumpProblem hump(1);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> dist(-1., 1.);
  for (auto &Zn : hump.Z)
    for (unsigned int k = 0; k < hump.basis.n_dofs(); ++k)
    {
      Vector<double> z(hump.adjoint.n_dofs());
      for (auto &v : z)
        v = dist(gen);
      hump.adjoint.constraints().distribute(z); // hanging nodes, z = 0 on Gamma_D
      insert_block(z, k, hump.basis.n_dofs(), Zn);
    }
  const auto est = hump.estimate(SpaceIndicator::primal_residual);
  const auto rho = LocalizedForms<2>::primal_residual(hump.primal, hump.adjoint,
                                                      hump.mesh, hump.basis, hump.U,
                                                      hump.Z);
  double rho_z = 0;
  for (const double r : rho)
    rho_z += r;
  const double scale = cell_scale(est);
  ASSERT_GT(scale, 0.);
  EXPECT_NEAR(est.eta_h_total() - est.eta_h_split_rest - est.eta_h_data, rho_z,
              1e-9 * scale);
  const auto cellwise = anisodwr::estimate(
      hump.primal, hump.adjoint, hump.mesh, hump.basis, hump.U, hump.Z, hump.goals,
      TimeIndicator::average, nullptr, SpaceIndicator::primal_residual, {}, false);
  EXPECT_GT(std::abs(cellwise.eta_h_total() - cellwise.eta_h_split_rest -
                     cellwise.eta_h_data - rho_z),
            1e-3 * scale);
  for (const auto *e : {&est, &cellwise})
  {
    double cells = 0;
    for (const auto &c : e->eta_h_cell)
      cells += c[0] + c[1];
    EXPECT_NEAR(cells, e->eta_h_total(), 1e-12 * scale);
  }
}

// The Dirichlet data's share of eta_h (eta_h_data, doc/method.md §8) weighs the spatial
// mismatch g_tau - u_h only, g_tau interpolating g at the slab's temporal nodes where u_h
// takes it: the temporal part g - g_tau is the primal's temporal error, which eta_tau
// carries. Heat problem with boundary data g = (1 + x + 2y) t^3 (Q1 interpolates it
// exactly in space, dG(1) does not in time): eta_h_data vanishes to round-off; weighing
// g - u_h instead gave 0.56 of the indicators' scale here. Data quadratic in space and
// linear in time (exact in time, not in space) do give a share.
TEST(Estimator, DirichletDataTermSeesOnlyTheSpatialMismatch)
{
  const auto data_share = [](const std::string &g)
  {
    const HumpProblem heat(1, {"scene.name=custom", "scene.epsilon=1",
                               "scene.initial_value=0", "scene.rhs=0",
                               "scene.dirichlet=0, 1, 2, 3: " + g,
                               "scene.goals=m = mean 0.2, 0.2, 0.8, 0.8"});
    const auto est = heat.estimate(SpaceIndicator::primal_residual);
    return std::make_pair(est.eta_h_data, cell_scale(est));
  };
  const auto [temporal, scale_t] = data_share("(1 + x + 2*y)*t^3");
  ASSERT_GT(scale_t, 0.);
  EXPECT_LE(std::abs(temporal), 1e-12 * scale_t);
  const auto [spatial, scale_s] = data_share("(1 + x*x + y*y)*(1 + t)");
  ASSERT_GT(scale_s, 0.);
  EXPECT_GT(std::abs(spatial), 1e-4 * scale_s);
}

// The data quadrature term D(R_h z) = (f, w + delta b.grad w) and (u_0, ...) on the
// estimator's data rule minus the same on the primal's QGauss(p+2) (doc/method.md §6):
// - zero (to round-off) where QGauss(p+2) integrates the data exactly: u = x^2 y (1 + t)
//   with b = (1, 1), eps = 0.01, so f and u_0 are polynomials of degree <= 2 per
//   direction (SUPG on, Q1 primal, which does not contain u);
// - for the moving hump's front non-zero, and with it off exactly zero while every other
//   part stays the same: eta_h differs by the term itself, cell sums included;
// - the finer data rule moves it towards a limit: copies 4 and 8 agree better than 1
//   and 8.
TEST(Estimator, DataQuadratureTermIsTheRuleDifference)
{
  HumpProblem poly(1, {"scene.name=custom", "scene.epsilon=0.01", "scene.end_time=0.5",
                       "scene.convection=1; 1", "scene.exact_solution=x^2*y*(1+t)",
                       "scene.rhs=x^2*y - 0.02*y*(1+t) + (1+t)*(2*x*y + x^2)",
                       "scene.initial_value=x^2*y",
                       "scene.dirichlet=0, 1, 2, 3: x^2*y*(1+t)",
                       "scene.goals=mid = point 0.5, 0.5"});
  const auto p = poly.estimate(SpaceIndicator::primal_residual);
  ASSERT_GT(std::abs(p.eta_h_rho), 1e-8);
  EXPECT_LE(std::abs(p.eta_h_quad), 1e-12 * cell_scale(p));

  const HumpProblem hump(1);
  const auto on = hump.estimate(SpaceIndicator::primal_residual);
  const auto off = hump.estimate(SpaceIndicator::primal_residual, {2, false});
  const double scale = cell_scale(off);
  ASSERT_GT(scale, 0.);
  EXPECT_GT(std::abs(on.eta_h_quad), 1e-6 * scale);
  EXPECT_EQ(off.eta_h_quad, 0.);
  EXPECT_NEAR(on.eta_h_total() - off.eta_h_total(), on.eta_h_quad, 1e-12 * scale);
  EXPECT_NEAR(on.eta_h_rho, off.eta_h_rho, 1e-12 * scale);
  EXPECT_NEAR(on.eta_h_supg, off.eta_h_supg, 1e-12 * scale);
  EXPECT_NEAR(on.eta_tau, off.eta_tau, 1e-12 * scale);
  double cells = 0;
  for (std::size_t c = 0; c < on.eta_h_cell.size(); ++c)
    cells += on.eta_h_cell[c][0] + on.eta_h_cell[c][1] - off.eta_h_cell[c][0] -
             off.eta_h_cell[c][1];
  EXPECT_NEAR(cells, on.eta_h_quad, 1e-12 * scale);

  const double d1 = hump.estimate(SpaceIndicator::primal_residual, {1, true}).eta_h_quad,
               d4 = hump.estimate(SpaceIndicator::primal_residual, {4, true}).eta_h_quad,
               d8 = hump.estimate(SpaceIndicator::primal_residual, {8, true}).eta_h_quad;
  EXPECT_LT(std::abs(d4 - d8), std::abs(d1 - d8));
}

/// b equals a cell by cell, direction by direction, slab by slab and in every total
/// and part, to rel times a's cell_scale (> 0).
void expect_indicators_near(const Indicators<2> &a, const Indicators<2> &b, double rel)
{
  const double scale = cell_scale(a);
  ASSERT_GT(scale, 0.);
  const double tol = rel * scale;
  ASSERT_EQ(b.eta_h_cell.size(), a.eta_h_cell.size());
  ASSERT_EQ(b.eta_tau_slab.size(), a.eta_tau_slab.size());
  for (unsigned int c = 0; c < a.eta_h_cell.size(); ++c)
  {
    EXPECT_NEAR(a.eta_h_cell[c][0], b.eta_h_cell[c][0], tol);
    EXPECT_NEAR(a.eta_h_cell[c][1], b.eta_h_cell[c][1], tol);
    EXPECT_NEAR(a.eta_tau_cell[c], b.eta_tau_cell[c], tol);
  }
  for (unsigned int n = 0; n < a.eta_tau_slab.size(); ++n)
    EXPECT_NEAR(a.eta_tau_slab[n], b.eta_tau_slab[n], tol);
  for (const auto &[x, y] :
       std::vector<std::pair<double, double>>{{a.eta_h[0], b.eta_h[0]},
                                              {a.eta_h[1], b.eta_h[1]},
                                              {a.eta_tau, b.eta_tau},
                                              {a.eta_h_rho, b.eta_h_rho},
                                              {a.eta_h_rhostar, b.eta_h_rhostar},
                                              {a.eta_h_supg, b.eta_h_supg},
                                              {a.eta_tau_rho, b.eta_tau_rho},
                                              {a.eta_tau_rhostar, b.eta_tau_rhostar}})
    EXPECT_NEAR(x, y, tol);
}

// The indicators are linear in the goals: with weights w_i, the estimate of
// sum_i w_i J_i (one adjoint for the weighted goals) equals sum_i w_i times the estimate
// of J_i alone (its own adjoint), cell by cell, direction by direction and slab by slab
// (goal.weights = estimate relies on it). Moving hump, Q1/Q2, dG(1), both point goals,
// weights 0.7 and -1.3, both forms of eta_h.
TEST(Estimator, IndicatorsAreLinearInTheGoals)
{
  HumpProblem hump(1);
  ASSERT_EQ(hump.goals.size(), 2u);
  const double w[2] = {0.7, -1.3};
  SlabOperator<2> opq(hump.adjoint, hump.basis, SlabSolverOptions::direct(true));
  const auto adjoint_of = [&](const std::vector<GoalSpec> &goals)
  {
    return march_adjoint(hump.adjoint, hump.mesh, hump.basis, opq,
                         assemble_goal_vectors(hump.adjoint, goals), MarchOptions{});
  };
  for (const auto form : {SpaceIndicator::average, SpaceIndicator::primal_residual})
  {
    std::vector<GoalSpec> weighted;
    Indicators<2> sum;
    for (unsigned int g = 0; g < 2; ++g)
    {
      const GoalSpec one = unweighted(hump.goals[g]);
      const auto Zg = adjoint_of({one});
      add_scaled(sum, w[g],
                 estimate(hump.primal, hump.adjoint, hump.mesh, hump.basis, hump.U, Zg,
                          {one}, TimeIndicator::average, nullptr, form));
      weighted.push_back(one);
      weighted.back().weight = w[g];
    }
    const auto Zw = adjoint_of(weighted);
    const auto direct = estimate(hump.primal, hump.adjoint, hump.mesh, hump.basis, hump.U,
                                 Zw, weighted, TimeIndicator::average, nullptr, form);
    SCOPED_TRACE(form == SpaceIndicator::average ? "average" : "primal_residual");
    expect_indicators_near(direct, sum, 1e-10);
  }
}

// The estimator's cells are shared among threads in chunks whose partial sums are added
// in a fixed order: one thread and several give the same indicators up to round-off
// (deal.II's FEValues reuses data between similar consecutive cells, so the last bits
// of a cell's terms depend on the cell visited before it).
TEST(Estimator, ThreadCountDoesNotChangeTheIndicators)
{
  const HumpProblem hump(2);
  ASSERT_GT(hump.tria.n_active_cells(), 4 * 64u); // several chunks
  std::vector<Indicators<2>> runs;
  for (const unsigned int threads : {1u, 3u})
  {
    MultithreadInfo::set_thread_limit(threads);
    runs.push_back(hump.estimate(SpaceIndicator::average));
  }
  MultithreadInfo::set_thread_limit();
  const auto &a = runs[0], &b = runs[1];
  expect_indicators_near(a, b, 1e-13);
  const double tol = 1e-13 * cell_scale(a);
  EXPECT_EQ(a.no_lift, b.no_lift);
  // the sums are the sums of the cell terms (every cell visited once)
  double cells = 0;
  for (const auto &c : b.eta_h_cell)
    cells += c[0] + c[1];
  EXPECT_NEAR(cells, b.eta_h_total(), tol);
}

// estimate_each runs several adjoints (one per goal) in one pass over the cells and
// shares the work on u_h; each adjoint's indicators must be estimate()'s for it alone,
// bit for bit (on one thread, so that FEValues' reuse between consecutive cells sees
// the same cells). Moving hump (hanging nodes, SUPG): its two point goals at T and a
// mean over I, both space forms, with and without the conforming weights.
TEST(Estimator, EachAdjointInOnePassIsItsEstimateAlone)
{
  const HumpProblem hump(1);
  GoalSpec over_I;
  over_I.name = "mean_I";
  over_I.kind = "mean";
  over_I.location = {0.5, 0., 1., 0.5};
  over_I.over_time = true;
  const std::vector<GoalSpec> goals = {unweighted(hump.goals[0]), unweighted(hump.goals[1]),
                                       over_I};
  SlabOperator<2> opq(hump.adjoint, hump.basis, SlabSolverOptions::direct(true));
  std::vector<std::vector<Vector<double>>> Z;
  std::vector<AdjointOf> each;
  for (const auto &g : goals)
    Z.push_back(march_adjoint(hump.adjoint, hump.mesh, hump.basis, opq,
                              assemble_goal_vectors(hump.adjoint, {g}), MarchOptions{}));
  for (std::size_t i = 0; i < goals.size(); ++i)
    each.push_back({&Z[i], {goals[i]}});
  MultithreadInfo::set_thread_limit(1);
  for (const auto form : {SpaceIndicator::average, SpaceIndicator::primal_residual})
    for (const bool conforming : {true, false})
    {
      const auto parts =
          estimate_each(hump.primal, hump.adjoint, hump.mesh, hump.basis, hump.U, each,
                        TimeIndicator::average, nullptr, form, {}, conforming);
      ASSERT_EQ(parts.size(), goals.size());
      for (std::size_t i = 0; i < goals.size(); ++i)
      {
        const auto alone =
            estimate(hump.primal, hump.adjoint, hump.mesh, hump.basis, hump.U, Z[i],
                     {goals[i]}, TimeIndicator::average, nullptr, form, {}, conforming);
        SCOPED_TRACE(goals[i].name + (form == SpaceIndicator::average ? " average" : " primal") +
                     (conforming ? " conforming" : ""));
        expect_indicators_near(alone, parts[i], 0.);
        EXPECT_EQ(alone.eta_h_split_rest, parts[i].eta_h_split_rest);
        EXPECT_EQ(alone.eta_h_data, parts[i].eta_h_data);
        EXPECT_EQ(alone.eta_h_quad, parts[i].eta_h_quad);
        EXPECT_EQ(alone.no_lift, parts[i].no_lift);
        EXPECT_NE(alone.eta_h_total(), 0.);
      }
    }
  MultithreadInfo::set_thread_limit();
}

// The estimator's short-vector helpers must give exactly deal.II's results (the
// indicators, marking and every table stay bit-identical). Values spread over 16 orders
// of magnitude make the summation order visible in the last bits.
TEST(ShortVectors, BitIdenticalToDealII)
{
  namespace sv = anisodwr::short_vectors;
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> mantissa(-1., 1.);
  std::uniform_int_distribution<int> exponent(-8, 8);
  const auto random = [&](unsigned int n)
  {
    Vector<double> v(n);
    for (auto &e : v)
      e = std::ldexp(mantissa(gen), 3 * exponent(gen));
    return v;
  };
  unsigned int order_matters = 0;
  for (unsigned int n = 1; n <= 40; ++n)
    for (int trial = 0; trial < 20; ++trial)
    {
      const Vector<double> a = random(n), b = random(n);
      EXPECT_EQ(sv::dot(a, b), a * b) << "n = " << n;
      EXPECT_EQ(sv::norm_sqr(a), a.norm_sqr()) << "n = " << n;
      double sequential = 0;
      for (unsigned int i = 0; i < n; ++i)
        sequential += a(i) * b(i);
      order_matters += sequential != a * b;

      const double s = mantissa(gen);
      Vector<double> y = a, ref = a;
      sv::add(y, s, b);
      ref.add(s, b);
      sv::subtract(y, a);
      ref -= a;
      sv::scale(y, 1. / s);
      ref /= s;
      for (unsigned int i = 0; i < n; ++i)
        EXPECT_EQ(y(i), ref(i)) << "n = " << n << ", i = " << i;
      Vector<double> c;
      sv::copy(c, y);
      EXPECT_EQ(c, y);
      sv::zero(c, n + 1);
      EXPECT_EQ(c.size(), n + 1);
      EXPECT_EQ(c.linfty_norm(), 0.);
    }
  // a plain left-to-right sum differs from deal.II's order on these data, so the
  // checks above see the order
  EXPECT_GT(order_matters, 50u);
}

// adaptivity.tolerance_measure = parts: |eta_h,x| + |eta_h,y| + |eta_tau| of the weighted
// goal, or, when every goal has its own parts, sum_i |w_i| (|parts of goal i|); never
// below |eta_tau h| = |sum_i w_i eta_i|.
TEST(LoopRow, EtaPartsAbsSumsUnsignedPartsPerGoal)
{
  LoopRow row;
  row.eta_h = {{0.3, -0.5}};
  row.eta_tau = 0.1;
  row.eta_h_total = -0.2;
  EXPECT_DOUBLE_EQ(row.eta_parts_abs(), 0.9);
  row.weights = {1., -2.};
  row.eta_goal_parts = {{{1., -2., 0.5}}, {{-0.25, 0.25, 1.}}};
  // the weighted goal's eta: 1 (1 - 2 + 0.5) - 2 (-0.25 + 0.25 + 1) = -2.5
  row.eta_h = {{1. + 0.5, -2. - 0.5}};
  row.eta_tau = 0.5 - 2.;
  row.eta_h_total = row.eta_h[0] + row.eta_h[1];
  EXPECT_DOUBLE_EQ(row.eta_h_total + row.eta_tau, -2.5);
  EXPECT_DOUBLE_EQ(row.eta_parts_abs(), 3.5 + 2. * 1.5);
  // parts of some goals only: the weighted goal's parts
  row.eta_goal_parts.pop_back();
  EXPECT_DOUBLE_EQ(row.eta_parts_abs(), 1.5 + 2.5 + 1.5);
}

// adaptivity.tolerance_measure = goals: max_i |w_i eta_i| over the goals' own
// estimates; |eta_tau h| of the weighted goal where the goals have none. Two goals
// whose weighted estimates cancel in the sum (0.3 - 0.3) keep the larger one.
TEST(LoopRow, EtaGoalsMaxTakesTheLargestWeightedGoalEstimate)
{
  LoopRow row;
  row.eta_h_total = -0.2;
  row.eta_tau = 0.05;
  EXPECT_DOUBLE_EQ(row.eta_goals_max(), 0.15);
  row.weights = {1., -2.};
  row.eta_goal = {0.3, 0.15};
  EXPECT_DOUBLE_EQ(row.eta_goals_max(), 0.3);
  row.eta_goal = {0.3, -0.4};
  EXPECT_DOUBLE_EQ(row.eta_goals_max(), 0.8);
  row.eta_goal.pop_back(); // not every goal has its own estimate
  EXPECT_DOUBLE_EQ(row.eta_goals_max(), 0.15);
}

// adaptivity.goal_estimate = both: per goal the u_q whose value is farthest from J_i(u_h),
// whichever side; a u_q without a value per goal (its march failed) is passed over, and
// none leaves J_goal_hi empty (the DWR's estimates).
TEST(LoopRow, PickGoalHiTakesTheLargerEstimatePerGoal)
{
  LoopRow row;
  row.J_goal = {1.0, -2.0, 0.5};
  row.J_uq = {{1.2, -2.5, 0.4}, {}, {0.7, -2.1, 0.6}};
  row.pick_goal_hi();
  ASSERT_EQ(row.J_goal_hi.size(), 3u);
  EXPECT_DOUBLE_EQ(row.J_goal_hi[0], 0.7);  // |-0.3| > |0.2|
  EXPECT_DOUBLE_EQ(row.J_goal_hi[1], -2.5); // |-0.5| > |-0.1|
  EXPECT_DOUBLE_EQ(row.J_goal_hi[2], 0.4);  // a tie keeps the first
  row.J_uq = {{1.1, -2.2, 0.3}};
  row.pick_goal_hi();
  EXPECT_EQ(row.J_goal_hi, (std::vector<double>{1.1, -2.2, 0.3}));
  row.J_uq = {{}, {1.0}};
  row.pick_goal_hi();
  EXPECT_TRUE(row.J_goal_hi.empty());
}

// adaptivity.tolerance_drift: the corrected goal values J_i + eta_i of two loops. Exact
// estimates (J_i + eta_i = J_i(u) on both loops) give 0; otherwise the sum over the goals
// of |w_i| times the change, with the later loop's weights; the weighted goal's own
// J + eta_tau h where the goals have no estimates of their own, if the weights are the
// same; NaN if they changed.
TEST(LoopRow, CorrectedDriftComparesTheGoalsCorrectedValues)
{
  LoopRow a, b;
  a.J_goal = {1.0, -2.0};
  a.eta_goal = {0.5, 0.25}; // J_i(u) = 1.5, -1.75
  a.weights = {1., 1.};
  b.J_goal = {1.25, -1.5};
  b.eta_goal = {0.25, -0.25};
  b.weights = {2., -4.};
  EXPECT_DOUBLE_EQ(corrected_drift(a, b), 0.);
  b.eta_goal = {0.5, -0.5}; // misses by +0.25 and -0.25 more than loop a
  EXPECT_DOUBLE_EQ(corrected_drift(a, b), 2. * 0.25 + 4. * 0.25);
  // no estimates per goal: the weighted goal's J + eta_tau h, same weights
  a.eta_goal.clear();
  b.weights = a.weights;
  a.J = 3.;
  a.eta_h_total = 0.5;
  a.eta_tau = -0.25;
  b.J = 2.;
  b.eta_h_total = 1.;
  b.eta_tau = 0.5;
  EXPECT_DOUBLE_EQ(corrected_drift(a, b), 0.25);
  b.weights = {1., -1.};
  EXPECT_TRUE(std::isnan(corrected_drift(a, b)));
}

// The crosswind entry of the stabilization terms' table: D_K = eps_cw a a^T with a the
// unit vector across b, eps_cw = s_K crosswind0 max(0, |b| h_cw / 2 - eps); nothing along b.
TEST(StabilizationTerms, CrosswindDiffusesAcrossBOnly)
{
  const auto &terms = diffusion_terms();
  const auto it = std::find_if(terms.begin(), terms.end(),
                               [](const DiffusionTerm &t) { return t.name == "crosswind"; });
  ASSERT_NE(it, terms.end());
  Stabilization stab;
  EXPECT_FALSE(it->active(stab)); // crosswind0 = 0 by default
  stab.crosswind0 = 0.8;
  EXPECT_TRUE(it->active(stab));
  StabilizationCell cell;
  cell.b[0] = 3.;
  cell.b[1] = 4.;
  cell.epsilon = 1e-3;
  double asked = 0.;
  cell.length_along = [&asked](const dealii::Tensor<1, 2> &a) {
    asked = a[0] * 0.8 + a[1] * -0.6; // a must be +-(-4, 3) / 5
    return 0.1;
  };
  cell.switch_factor = 0.5;
  const dealii::Tensor<2, 2> D = it->diffusion(stab, cell);
  EXPECT_NEAR(std::abs(asked), 1., 1e-15);
  const double eps_cw = 0.5 * 0.8 * (0.5 * 5. * 0.1 - 1e-3);
  dealii::Tensor<1, 2> across;
  across[0] = -0.8;
  across[1] = 0.6;
  EXPECT_NEAR(across * (D * across), eps_cw, 1e-15);
  EXPECT_NEAR((D * cell.b).norm(), 0., 1e-15);
  EXPECT_EQ(D[0][1], D[1][0]);
  // resolved across b (|b| h_cw / 2 <= eps) or switched off: no diffusion
  cell.epsilon = 1.;
  EXPECT_EQ(it->diffusion(stab, cell).norm(), 0.);
  cell.epsilon = 1e-3;
  cell.switch_factor = 0.;
  EXPECT_EQ(it->diffusion(stab, cell).norm(), 0.);
}
