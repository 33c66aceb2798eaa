// The Kronecker slab operator against a direct space-time assembly, and exactness
// of cG(p)-dG(r) on solutions that are polynomials of degree r in t and lie in
// the FE space in x (hanging nodes, inhomogeneous time-dependent Dirichlet data,
// Neumann data, time-dependent b and alpha, SUPG on).
#include "slab/primal_march.h"
#include "study/error_norms.h"
#include "study/options.h"
#include "time/kronecker.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace anisodwr;
using namespace dealii;

namespace
{
/// u = X(x,y) T(t), X = 1 + x + 2 y^2 + x y (in Q2), T(t) = sum_{j<=r} (j+1) t^j / 2^j.
class PolySolution : public ExactSolution<2>
{
public:
  /// split: declare the product form (separable()), which loads and errors then use.
  explicit PolySolution(unsigned int r, bool split = false) : r(r), split(split) {}
  double value(const Point<2> &p, double t) const override { return X(p) * T(t); }
  Tensor<1, 2> gradient(const Point<2> &p, double t) const override
  {
    return space_gradient(p) * T(t);
  }
  double laplacian(const Point<2> &, double t) const override { return 4. * T(t); }
  double time_derivative(const Point<2> &p, double t) const override { return X(p) * dT(t); }
  bool separable() const override { return split; }
  double time_factor(double t, unsigned int derivative) const override
  {
    return derivative == 0 ? T(t) : dT(t);
  }
  double space_value(const Point<2> &p) const override { return X(p); }
  Tensor<1, 2> space_gradient(const Point<2> &p) const override
  {
    return Tensor<1, 2>({1. + p[1], 4. * p[1] + p[0]});
  }
  double space_laplacian(const Point<2> &) const override { return 4.; }

private:
  unsigned int r;
  bool split;
  static double X(const Point<2> &p) { return 1. + p[0] + 2. * p[1] * p[1] + p[0] * p[1]; }
  double T(double t) const
  {
    double v = 0;
    for (unsigned int j = 0; j <= r; ++j)
      v += (j + 1.) * std::pow(t / 2., j);
    return v;
  }
  double dT(double t) const
  {
    double v = 0;
    for (unsigned int j = 1; j <= r; ++j)
      v += (j + 1.) * j * std::pow(t / 2., j - 1) / 2.;
    return v;
  }
};

/// Unit square, boundary ids 0..3 (left, right, bottom, top); Neumann on the right.
class PolyScene : public Scene<2>
{
public:
  PolyScene(unsigned int r, double eps)
  {
    epsilon = eps;
    end_time = 1.;
    dirichlet_ids = {0, 2, 3};
    neumann_ids = {1};
    exact_solution = std::make_unique<PolySolution>(r);
  }
  std::string name() const override { return "poly"; }
  void make_coarse_grid(Triangulation<2> &tria) const override
  {
    GridGenerator::hyper_cube(tria, 0., 1., true);
  }
  Tensor<1, 2> convection(const Point<2> &p, double t) const override
  {
    return Tensor<1, 2>({-(p[1] - 0.5) * (1. + t), (p[0] - 0.5) * (1. + t)});
  }
  double reaction(const Point<2> &, double t) const override { return 1. + t; }
  bool coefficients_depend_on_time() const override { return true; }
};

/// Like PolyScene with b = (1, -0.5), alpha = 2 constant in time; `split` declares u
/// separable, so that f is assembled from its space-time products.
class ConstantCoefficientPolyScene : public Scene<2>
{
public:
  ConstantCoefficientPolyScene(unsigned int r, double eps, bool split)
  {
    epsilon = eps;
    end_time = 1.;
    dirichlet_ids = {0, 2, 3};
    neumann_ids = {1};
    exact_solution = std::make_unique<PolySolution>(r, split);
  }
  std::string name() const override { return "poly_constant"; }
  void make_coarse_grid(Triangulation<2> &tria) const override
  {
    GridGenerator::hyper_cube(tria, 0., 1., true);
  }
  Tensor<1, 2> convection(const Point<2> &, double) const override
  {
    return Tensor<1, 2>({1., -0.5});
  }
  double reaction(const Point<2> &, double) const override { return 2.; }
  bool coefficients_depend_on_time() const override { return false; }
};

/// 2x2 mesh with one cell cut in x and one of its children cut in y: hanging nodes
/// and anisotropic cells.
void make_mesh(const Scene<2> &scene, Triangulation<2> &tria)
{
  scene.make_coarse_grid(tria);
  tria.refine_global(1);
  tria.begin_active()->set_refine_flag(RefinementCase<2>::cut_x);
  tria.execute_coarsening_and_refinement();
  tria.begin_active(1)->set_refine_flag(RefinementCase<2>::cut_y);
  tria.execute_coarsening_and_refinement();
}

/// Direct space-time assembly of the unconstrained slab matrix (reference).
FullMatrix<double> direct_slab_matrix(const Space<2> &space, const TemporalBasis &basis,
                                      double delta0, double t0, double tau)
{
  const Scene<2> &scene = space.scene;
  const unsigned int m = basis.n_dofs(), nd = space.n_dofs();
  FullMatrix<double> K(nd * m, nd * m);
  const QGauss<2> qx(space.degree() + 2);
  std::vector<double> st, wt;
  gauss_rule(m + 2, st, wt);
  FEValues<2> fv(space.mapping(), space.finite_element(), qx,
                 update_values | update_gradients | update_hessians | update_quadrature_points |
                   update_JxW_values);
  const unsigned int n = space.finite_element().n_dofs_per_cell();
  std::vector<types::global_dof_index> idx(n);
  for (const auto &cell : space.dof_handler().active_cell_iterators())
  {
    fv.reinit(cell);
    cell->get_dof_indices(idx);
    const double dK = delta0 * std::sqrt(cell->measure());
    for (unsigned int q = 0; q < qx.size(); ++q)
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
        {
          const Point<2> &x = fv.quadrature_point(q);
          const double pi = fv.shape_value(i, q), pj = fv.shape_value(j, q);
          const auto gi = fv.shape_grad(i, q), gj = fv.shape_grad(j, q);
          const double lap_j = trace(fv.shape_hessian(j, q));
          for (unsigned int k = 0; k < m; ++k)
            for (unsigned int l = 0; l < m; ++l)
            {
              double v = 0;
              for (unsigned int a = 0; a < st.size(); ++a)
              {
                const double t = t0 + st[a] * tau;
                const auto b = scene.convection(x, t);
                const double al = scene.reaction(x, t), test = pi + dK * (b * gi);
                const double lk = basis.value(k, st[a]), ll = basis.value(l, st[a]);
                const double dll = basis.derivative(l, st[a]) / tau;
                const double strong = -scene.epsilon * lap_j + b * gj + al * pj;
                v += tau * wt[a] *
                     (dll * lk * pj * test +
                      lk * ll *
                        (scene.epsilon * (gj * gi) + (b * gj + al * pj) * pi +
                         dK * strong * (b * gi)));
              }
              const auto b0 = scene.convection(x, t0);
              v += basis.value(k, 0.) * basis.value(l, 0.) * pj * (pi + dK * (b0 * gi));
              K(idx[i] * m + k, idx[j] * m + l) += v * fv.JxW(q);
            }
        }
  }
  return K;
}
} // namespace

class SlabByDegree : public ::testing::TestWithParam<std::tuple<unsigned int, double>>
{
};

TEST_P(SlabByDegree, KroneckerEqualsDirectSpaceTimeAssembly)
{
  const auto [r, delta0] = GetParam();
  const PolyScene scene(r, 0.1);
  Triangulation<2> tria;
  make_mesh(scene, tria);
  Space<2> space(scene, tria, 2, Stabilization{delta0, SupgLength::volume, 0.});
  space.setup();
  const TemporalBasis basis(r);
  SlabOperator<2> op(space, basis, SlabSolverOptions::direct(true));
  const double t0 = 0.3, tau = 0.25;
  op.prepare(t0, tau);
  SparsityPattern sp;
  make_kron_sparsity(space.sparsity(), basis.n_dofs(), sp);
  SparseMatrix<double> K;
  assemble_kron(op.full_terms(), sp, K);
  const FullMatrix<double> Kd = direct_slab_matrix(space, basis, delta0, t0, tau);
  double max_diff = 0, max_entry = 0;
  for (unsigned int i = 0; i < Kd.m(); ++i)
    for (unsigned int j = 0; j < Kd.n(); ++j)
    {
      max_diff = std::max(max_diff, std::abs(K.el(i, j) - Kd(i, j)));
      max_entry = std::max(max_entry, std::abs(Kd(i, j)));
    }
  EXPECT_LT(max_diff, 1e-12 * max_entry) << "r = " << r << ", delta0 = " << delta0;

  // The matrix-free Kronecker product agrees with the assembled matrix (and its transpose).
  std::mt19937 gen(42);
  std::uniform_real_distribution<double> dist(-1., 1.);
  Vector<double> x(K.m()), y1, y2(K.m());
  for (auto &v : x)
    v = dist(gen);
  vmult_kron(op.full_terms(), x, y1);
  K.vmult(y2, x);
  y2 -= y1;
  EXPECT_LT(y2.linfty_norm(), 1e-12 * max_entry * x.l1_norm());
  vmult_kron(op.full_terms(), x, y1, true);
  K.Tvmult(y2, x);
  y2 -= y1;
  EXPECT_LT(y2.linfty_norm(), 1e-12 * max_entry * x.l1_norm());

  // So do the products from the summed m x m blocks (the Krylov path's operator).
  KronBlocks blocks;
  blocks.reinit(op.full_terms());
  ASSERT_EQ(blocks.size(), K.m());
  for (const bool transpose : {false, true})
  {
    transpose ? blocks.Tvmult(y1.data(), x.data()) : blocks.vmult(y1.data(), x.data());
    transpose ? K.Tvmult(y2, x) : K.vmult(y2, x);
    y2 -= y1;
    EXPECT_LT(y2.linfty_norm(), 1e-12 * max_entry * x.l1_norm()) << "transpose " << transpose;
  }
}

TEST(KronBlocks, ProductsEqualTheAssembledSumForEveryBlockSize)
{
  // three terms with random temporal factors on a Q1 pattern with hanging nodes;
  // m = 1..4 take the fixed-size kernels, m = 5 the general one
  Triangulation<2> tria;
  GridGenerator::hyper_cube(tria);
  tria.refine_global(2);
  tria.begin_active()->set_refine_flag();
  tria.execute_coarsening_and_refinement();
  const FE_Q<2> fe(1);
  DoFHandler<2> dofs(tria);
  dofs.distribute_dofs(fe);
  DynamicSparsityPattern dsp(dofs.n_dofs());
  DoFTools::make_sparsity_pattern(dofs, dsp);
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> dist(-1., 1.);
  std::vector<SparseMatrix<double>> S(3);
  for (auto &s : S)
  {
    s.reinit(pattern);
    for (auto &e : s)
      e.value() = dist(gen);
  }
  for (unsigned int m = 1; m <= 5; ++m)
  {
    std::vector<KronTerm> terms;
    for (const auto &s : S)
    {
      FullMatrix<double> T(m, m);
      for (unsigned int k = 0; k < m; ++k)
        for (unsigned int l = 0; l < m; ++l)
          T(k, l) = dist(gen);
      terms.push_back({T, &s});
    }
    SparsityPattern kp;
    make_kron_sparsity(pattern, m, kp);
    SparseMatrix<double> K;
    assemble_kron(terms, kp, K);
    KronBlocks blocks;
    blocks.reinit(terms);
    Vector<double> x(K.m()), y1(K.m()), y2(K.m());
    for (auto &v : x)
      v = dist(gen);
    for (const bool transpose : {false, true})
    {
      transpose ? blocks.Tvmult(y1.data(), x.data()) : blocks.vmult(y1.data(), x.data());
      transpose ? K.Tvmult(y2, x) : K.vmult(y2, x);
      y2 -= y1;
      EXPECT_LT(y2.linfty_norm(), 1e-13 * K.linfty_norm() * x.linfty_norm())
          << "m = " << m << ", transpose " << transpose;
    }
  }
  // terms on two different patterns are refused
  SparsityPattern other;
  other.copy_from(dsp);
  SparseMatrix<double> s_other(other);
  KronBlocks blocks;
  EXPECT_THROW(blocks.reinit({{FullMatrix<double>(1, 1), &S[0]}, {FullMatrix<double>(1, 1), &s_other}}),
               std::logic_error);
}

INSTANTIATE_TEST_SUITE_P(RAndSupg, SlabByDegree,
                         ::testing::Combine(::testing::Values(0u, 1u, 2u),
                                            ::testing::Values(0.0, 1.0)));

class ExactnessByDegree : public ::testing::TestWithParam<unsigned int>
{
};

TEST_P(ExactnessByDegree, PolynomialInTimeAndInFESpaceIsReproduced)
{
  const unsigned int r = GetParam();
  const PolyScene scene(r, 0.05);
  Triangulation<2> tria;
  make_mesh(scene, tria);
  Space<2> space(scene, tria, 2, Stabilization{1.0, SupgLength::volume, 0.});
  space.setup();
  const TemporalBasis basis(r);
  const TimeMesh mesh = TimeMesh::uniform(1.0, 3);
  SlabOperator<2> op(space, basis, SlabSolverOptions::direct(true));
  const auto U = march_primal(space, mesh, basis, op, MarchOptions{});
  const ErrorNorms e = compute_errors(space, mesh, basis, U);
  EXPECT_LT(e.nodal, 1e-10);
  EXPECT_LT(e.L2L2, 1e-10);
  // dG(r-1) cannot reproduce a degree-r polynomial in time: the test can fail.
  if (r > 0)
  {
    const TemporalBasis lower(r - 1);
    SlabOperator<2> op2(space, lower, SlabSolverOptions::direct(true));
    const auto U2 = march_primal(space, mesh, lower, op2, MarchOptions{});
    EXPECT_GT(compute_errors(space, mesh, lower, U2).L2L2, 1e-6);
  }
}

INSTANTIATE_TEST_SUITE_P(R, ExactnessByDegree, ::testing::Values(0u, 1u, 2u, 3u));

// Loads of a separable f, assembled once per mesh and slab length from the products
// a_j(t) g_j(x), equal the pointwise assembly of f(x, t_k) (SUPG with delta_K bounded
// by tau, so the cached parts depend on the slab length; Neumann data on one side);
// the errors of a separable exact solution equal those of the pointwise evaluation.
TEST(Slab, SeparableLoadsAndErrorsEqualPointwiseEvaluation)
{
  const ConstantCoefficientPolyScene split(2, 0.05, true), pointwise(2, 0.05, false);
  std::vector<LoadTerm<2>> terms;
  ASSERT_TRUE(split.separable_rhs(terms));
  EXPECT_EQ(terms.size(), 2u);
  ASSERT_FALSE(pointwise.separable_rhs(terms));
  Triangulation<2> tria;
  make_mesh(split, tria);
  tria.refine_global(1);
  const Stabilization stab{1.0, SupgLength::streamline, 0.5};
  Space<2> a(split, tria, 2, stab), b(pointwise, tria, 2, stab);
  a.setup();
  b.setup();
  ASSERT_TRUE(a.delta_depends_on_tau());
  // two slab lengths (two cached entries), the first one again (a cache hit)
  for (const auto &[times, tau] : std::vector<std::pair<std::vector<double>, double>>{
           {{0.1, 0.3}, 0.4}, {{0.45, 0.55, 0.6}, 0.01}, {{0.7, 0.9}, 0.4}})
  {
    std::vector<Vector<double>> Fa, Fb;
    a.assemble_loads(times, tau, Fa);
    b.assemble_loads(times, tau, Fb);
    ASSERT_EQ(Fa.size(), times.size());
    for (std::size_t k = 0; k < times.size(); ++k)
    {
      Vector<double> d = Fa[k];
      d -= Fb[k];
      EXPECT_GT(Fb[k].l2_norm(), 1e-2);
      EXPECT_LT(d.l2_norm(), 1e-13 * Fb[k].l2_norm()) << "t = " << times[k] << ", tau " << tau;
    }
  }
  // errors of the dG(1) solution of a quadratic-in-time u (not exact: nonzero errors)
  const TemporalBasis basis(1);
  const TimeMesh mesh = TimeMesh::uniform(1.0, 3);
  SlabOperator<2> op(a, basis, SlabSolverOptions::direct(true));
  const auto U = march_primal(a, mesh, basis, op, MarchOptions{});
  const ErrorNorms ea = compute_errors(a, mesh, basis, U), eb = compute_errors(b, mesh, basis, U);
  EXPECT_GT(ea.L2L2, 1e-6);
  EXPECT_NEAR(ea.L2L2, eb.L2L2, 1e-14 * eb.L2L2);
  EXPECT_NEAR(ea.nodal, eb.nodal, 1e-14 * eb.nodal);
  EXPECT_NEAR(ea.L2_T, eb.L2_T, 1e-14 * eb.L2_T);
}

// SUPG whose test function v + delta_K b.grad v also multiplies du/dt is stable only
// for delta_K <~ tau_n (the term delta_K (u_t, b.grad u) is controlled by the SUPG
// part of A only then). On a strongly anisotropic mesh, where delta_K jumps between
// neighbours, 40 small slabs blow up without the bound; with delta_K <= tau_n they
// stay bounded by the data (|u| <= 1 for the moving hump).
TEST(Slab, SupgBoundedByTauKeepsSmallSlabsStable)
{
  const auto scene = create_scene<2>(Parameters::from_overrides(
      {"scene.name=moving_hump", "scene.epsilon=1e-6", "scene.end_time=0.5"}));
  Triangulation<2> tria;
  scene->make_coarse_grid(tria);
  tria.refine_global(2);
  // thin cells along the hump's ring (|x - (0.5, 0.5)| = 0.25), cut across it
  for (unsigned int k = 0; k < 7; ++k)
  {
    for (const auto &cell : tria.active_cell_iterators())
    {
      const Tensor<1, 2> c = cell->center() - Point<2>(0.5, 0.5);
      if (std::abs(c.norm() - 0.25) < 0.6 * cell->extent_in_direction(0) +
                                             0.6 * cell->extent_in_direction(1))
        cell->set_refine_flag(std::abs(c[0]) > std::abs(c[1]) ? RefinementCase<2>::cut_x
                                                              : RefinementCase<2>::cut_y);
    }
    tria.execute_coarsening_and_refinement();
  }
  const TemporalBasis basis(1);
  const TimeMesh mesh = TimeMesh::uniform(0.5, 40);
  double max_u[2] = {0, 0};
  for (const double factor : {0., 1.})
  {
    Space<2> space(*scene, tria, 1, Stabilization{1.0, SupgLength::streamline, factor});
    space.setup();
    if (factor > 0)
      for (const auto &cell : tria.active_cell_iterators())
      {
        EXPECT_LE(space.delta(cell, mesh.tau(0)), factor * mesh.tau(0) * (1 + 1e-14));
        EXPECT_DOUBLE_EQ(space.delta(cell, 1e6), space.unbounded_delta(cell));
      }
    SlabOperator<2> op(space, basis, SlabSolverOptions::direct(true));
    const auto U = march_primal(space, mesh, basis, op, MarchOptions{});
    max_u[factor > 0] = U.back().linfty_norm();
  }
  std::cout << "max |U(T)| without / with the bound: " << max_u[0] << ", " << max_u[1]
            << std::endl;
  EXPECT_LT(max_u[1], 1.5);
  EXPECT_GT(max_u[0], 10.); // the test can fail: without the bound the march blows up
}
