// Localization of the DWR indicators (SPEC §5): the cell-wise forms of the estimator
// (strong cell residual + half flux jumps + boundary terms + temporal jumps for rho;
// cell-wise weak forms for the adjoint residual; SUPG terms) summed over all cells
// equal the global weak forms, computed independently from the assembled Kronecker
// slab operator, to round-off: random continuous functions (hanging nodes,
// anisotropic cells), polynomial-in-space data, time-dependent b and alpha.
#include "adaptivity/estimator.h"
#include "config/parameters.h"
#include "slab/primal_march.h"

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

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

struct Problem
{
  std::unique_ptr<Scene<2>> scene;
  Triangulation<2> tria;
  std::unique_ptr<Space<2>> galerkin, supg;
  TemporalBasis basis;
  TimeMesh mesh;
  /// `variant` poly_space: b, alpha depend on t; constant: they do not (the estimator
  /// then applies A and S' through cell matrices).
  Problem(unsigned int p, unsigned int r, const std::string &variant = "poly_space")
      : scene(create_scene<2>(Parameters::from_overrides({"scene.name=manufactured",
                                                          "scene.variant=" + variant,
                                                          "scene.epsilon=0.5"}))),
        basis(r), mesh(TimeMesh::uniform(0.6, 2))
  {
    mesh.t[1] = 0.25; // unequal slabs
    make_mesh(tria);
    galerkin = std::make_unique<Space<2>>(*scene, tria, p, 0.);
    supg = std::make_unique<Space<2>>(*scene, tria, p, 0.7);
    galerkin->setup();
    supg->setup();
  }
};

} // namespace

class Localization : public ::testing::TestWithParam<unsigned int>
{
};

TEST_P(Localization, PrimalResidualAndSupgSumToGlobalForms)
{
  Problem s(1, GetParam());
  const unsigned int m = s.basis.n_dofs(), N = s.mesh.n_slabs();
  const auto U = random_function(*s.galerkin, m, N, 1),
             W = random_function(*s.galerkin, m, N, 2);
  const auto rho =
      LocalizedForms<2>::primal_residual(*s.supg, *s.galerkin, s.mesh, s.basis, U, W);
  const auto S = LocalizedForms<2>::supg(*s.supg, *s.galerkin, s.mesh, s.basis, U, W);
  for (unsigned int n = 0; n < N; ++n)
  {
    Vector<double> r0 = load(*s.galerkin, s.basis, s.mesh, n),
                   rd = load(*s.supg, s.basis, s.mesh, n);
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

INSTANTIATE_TEST_SUITE_P(TemporalDegree, Localization, ::testing::Values(0u, 1u, 2u));
INSTANTIATE_TEST_SUITE_P(TemporalDegreeAndCoefficients, AdjointLocalization,
                         ::testing::Combine(::testing::Values(0u, 1u, 2u),
                                            ::testing::Values("poly_space", "constant")));
