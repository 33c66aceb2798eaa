// The direct slab solver by temporal modes (solver.type = modes) against the coupled
// UMFPACK solve: the Schur form of the dG(r) temporal matrices, random Kronecker sums
// with real and complex modes, and the slab operator's primal and transposed (adjoint)
// solves for r = 0..3 with hanging nodes and Dirichlet constraints.
#include "config/parameters.h"
#include "scene/scene.h"
#include "slab/slab_operator.h"
#include "solver/mode_solver.h"
#include "study/options.h"
#include "time/kronecker.h"
#include "time/temporal_basis.h"

#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>

#include "slab_problem.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

using namespace anisodwr;
using namespace dealii;

namespace
{
double relative_difference(Vector<double> a, const Vector<double> &b)
{
  a -= b;
  return a.l2_norm() / b.l2_norm();
}

/// T1 = D (derivative with jump), T2 = tau Mhat of dG(r).
void dg_factors(unsigned int r, double tau, FullMatrix<double> &T1,
                FullMatrix<double> &T2)
{
  const TemporalBasis basis(r);
  T1 = basis.derivative_with_jump();
  T2 = basis.mass();
  T2 *= tau;
}
} // namespace

// Q orthogonal, Q T Q^T = T2^{-1} T1, T quasi upper triangular with the blocks the
// solver reads; dG(r) has r+1 modes, complex pairs from r = 1 on (so the complex path
// is tested below).
TEST(TemporalSchur, FactorsTheDgMatrices)
{
  for (unsigned int r = 0; r <= 4; ++r)
    for (const bool transpose : {false, true})
    {
      FullMatrix<double> T1, T2;
      dg_factors(r, 0.3, T1, T2);
      const TemporalSchur s(T1, T2, transpose);
      const unsigned int m = r + 1;
      ASSERT_EQ(s.m, m);
      FullMatrix<double> A1(m, m), A2(m, m), G(m, m), QT(m, m), QTQ(m, m), QQ(m, m);
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < m; ++j)
        {
          A1(i, j) = transpose ? T1(j, i) : T1(i, j);
          A2(i, j) = transpose ? T2(j, i) : T2(i, j);
        }
      FullMatrix<double> inv(m, m);
      inv.invert(A2);
      inv.mmult(G, A1);
      s.Q.mmult(QT, s.T);
      QT.mTmult(QTQ, s.Q);
      s.Q.Tmmult(QQ, s.Q);
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < m; ++j)
        {
          EXPECT_NEAR(QTQ(i, j), G(i, j), 1e-12 * G.frobenius_norm()) << "r = " << r;
          EXPECT_NEAR(QQ(i, j), i == j ? 1. : 0., 1e-13) << "r = " << r;
          if (i > j + 1)
          {
            EXPECT_EQ(s.T(i, j), 0.);
          }
        }
      unsigned int covered = 0;
      for (const auto &b : s.blocks)
      {
        EXPECT_EQ(b.first, covered);
        covered += b.size;
        if (b.size == 2)
        {
          EXPECT_GT(b.beta, 0.);
          EXPECT_DOUBLE_EQ(s.T(b.first, b.first), s.T(b.first + 1, b.first + 1));
        }
        // dG(r) is stable: every mode has a positive real part
        EXPECT_GT(b.size == 1 ? b.shift : b.alpha, 0.) << "r = " << r;
      }
      EXPECT_EQ(covered, m);
      EXPECT_EQ(s.n_real() + 2 * s.n_complex_pairs(), m);
      // m / 2 pairs and, for odd m, one real mode, in the order the memory model reads
      EXPECT_EQ(s.n_real(), m % 2) << "r = " << r;
      EXPECT_EQ(s.n_complex_pairs(), m / 2) << "r = " << r;
      const std::vector<unsigned int> order = mode_blocks(m);
      ASSERT_EQ(order.size(), s.blocks.size()) << "r = " << r;
      for (std::size_t b = 0; b < order.size(); ++b)
        EXPECT_EQ(order[b], s.blocks[b].size) << "r = " << r << ", block " << b;
      if (r >= 1)
      {
        EXPECT_GE(s.n_complex_pairs(), 1u) << "r = " << r;
      }
      if (r == 2)
      {
        EXPECT_EQ(s.n_real(), 1u);
      }
    }
}

// A random nonsymmetric Kronecker sum with real and complex modes against UMFPACK on
// the assembled K, both directions.
TEST(ModeDirectSolver, SolvesRandomKroneckerSums)
{
  const unsigned int n = 60;
  DynamicSparsityPattern dsp(n, n);
  std::mt19937 gen(3);
  std::uniform_int_distribution<unsigned int> col(0, n - 1);
  for (unsigned int i = 0; i < n; ++i)
  {
    dsp.add(i, i);
    for (unsigned int k = 0; k < 4; ++k)
    {
      const unsigned int j = col(gen);
      dsp.add(i, j);
      dsp.add(j, i);
    }
  }
  SparsityPattern sp;
  sp.copy_from(dsp);
  SparseMatrix<double> S1(sp), S2(sp);
  std::uniform_real_distribution<double> val(-1., 1.);
  for (unsigned int i = 0; i < n; ++i)
    for (auto e = S1.begin(i); e != S1.end(i); ++e)
    {
      e->value() = (e->column() == i ? 8. : 0.) + val(gen);
      S2.set(i, e->column(), (e->column() == i ? 6. : 0.) + val(gen));
    }
  for (const unsigned int m : {1u, 2u, 3u, 4u, 5u, 6u})
  {
    FullMatrix<double> T1(m, m), T2(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
      {
        // T2^{-1} T1 with eigenvalues of positive real part, real and complex
        // (a skew-symmetric tridiagonal part gives complex pairs, odd m one real mode)
        T1(i, j) = (i == j       ? 3.
                    : j == i + 1 ? 2.
                    : i == j + 1 ? -2.
                                 : 0.) +
                   0.2 * val(gen);
        T2(i, j) = (i == j ? 2. : 0.) + 0.3 * val(gen);
      }
    KronSplit k{T1, T2, &S1, &S2};
    ModeDirectSolver modes;
    modes.factorize(k);
    EXPECT_EQ(modes.schur().n_complex_pairs(), m / 2) << "m = " << m;
    SparsityPattern kp;
    make_kron_sparsity(sp, m, kp);
    SparseMatrix<double> K;
    assemble_kron({{T1, &S1}, {T2, &S2}}, kp, K);
    SparseDirectUMFPACK lu;
    lu.initialize(K);
    for (const bool transpose : {false, true})
    {
      const Vector<double> b = random_vector(n * m, 11 * m + transpose);
      Vector<double> x(b), x_ref(b);
      modes.solve(x, transpose);
      lu.solve(x_ref, transpose);
      EXPECT_LE(relative_difference(x, x_ref), 1e-11)
          << "m = " << m << (transpose ? ", transposed" : "")
          << ", complex pairs: " << modes.schur().n_complex_pairs();
      // the residual itself
      Vector<double> Kx(n * m);
      if (transpose)
        K.Tvmult(Kx, x);
      else
        K.vmult(Kx, x);
      EXPECT_LE(relative_difference(Kx, b), 1e-12) << "m = " << m;
    }
  }
}

namespace
{
SlabSolverOptions modes_options()
{
  SlabSolverOptions o = SlabSolverOptions::direct(true);
  o.type = SolverType::modes;
  return o;
}
} // namespace

class ModesVsCoupled
    : public ::testing::TestWithParam<std::tuple<unsigned int, unsigned int, bool>>
{
};

// The slab operator's mode solve equals the coupled UMFPACK solve (same condensed K,
// Dirichlet lift and constraints) for the primal and the transposed (adjoint) system,
// and reuses its factors while tau is unchanged.
TEST_P(ModesVsCoupled, AgreesWithCoupledUmfpack)
{
  const auto [r, p, adjoint] = GetParam();
  SlabProblem s("moving_hump", "", p, 1e-4);
  const TemporalBasis basis(r);
  SlabOperator<2> direct(*s.space, basis, SlabSolverOptions::direct(true));
  SlabOperator<2> modes(*s.space, basis, modes_options());
  double t0 = 0.1;
  for (const double tau : {0.05, 0.05, 0.02})
  {
    direct.prepare(t0, tau);
    modes.prepare(t0, tau);
    ASSERT_TRUE(modes.modes());
    ASSERT_FALSE(direct.modes());
    const Vector<double> load = random_vector(direct.n_slab_dofs(), 5 + r + 10 * p);
    Vector<double> U_direct, U_modes;
    direct.solve(load, U_direct, adjoint);
    modes.solve(load, U_modes, adjoint);
    EXPECT_LE(relative_difference(U_modes, U_direct), 1e-10)
        << "r = " << r << ", Q" << p << (adjoint ? ", transposed" : ", primal")
        << ", tau = " << tau;
    if (adjoint)
      // several goals' loads side by side (solve_transposed, parallel threads): each
      // result is exactly that load's own transposed solve
      for (SlabOperator<2> *op : {&direct, &modes})
      {
        const Vector<double> load2 = random_vector(load.size(), 21 + r),
                             load3 = random_vector(load.size(), 31 + p);
        std::vector<Vector<double>> U(3);
        op->solve_transposed({&load, &load2, &load3}, {&U[0], &U[1], &U[2]});
        const Vector<double> *loads[] = {&load, &load2, &load3};
        for (unsigned int i = 0; i < 3; ++i)
        {
          Vector<double> own;
          op->solve(*loads[i], own, true);
          EXPECT_EQ(relative_difference(U[i], own), 0.)
              << "r = " << r << ", Q" << p << (op == &modes ? ", modes" : ", coupled")
              << ", load " << i;
        }
      }
    t0 += tau;
  }
  // one factorization per mode for each of the two slab lengths
  EXPECT_EQ(modes.timings().n_factorizations,
            2 * modes.mode_solver().schur().blocks.size());
  EXPECT_EQ(direct.timings().n_factorizations, 2u);
  EXPECT_GT(modes.timings().factor_mb, 0.);
  if (r >= 1)
  {
    EXPECT_GE(modes.mode_solver().schur().n_complex_pairs(), 1u);
  }
}

INSTANTIATE_TEST_SUITE_P(DgZeroToThree, ModesVsCoupled,
                         ::testing::Combine(::testing::Values(0u, 1u, 2u, 3u),
                                            ::testing::Values(1u, 2u), ::testing::Bool()),
                         [](const auto &info)
                         {
                           return "r" + std::to_string(std::get<0>(info.param)) + "_Q" +
                                  std::to_string(std::get<1>(info.param)) +
                                  (std::get<2>(info.param) ? "_adjoint" : "_primal");
                         });

// solver.type = auto: modes for r >= 1 with coefficients constant in time, the coupled
// UMFPACK for r = 0 and for coefficients that depend on time (solver.type = modes then
// falls back to the coupled solve, with the same answer).
TEST(ModesChoice, AutoPicksModesWhereTheyApply)
{
  SlabProblem constant("moving_hump", "", 1, 1e-4);
  SlabSolverOptions o;
  o.type = SolverType::automatic;
  for (unsigned int r = 0; r <= 2; ++r)
  {
    const TemporalBasis basis(r);
    SlabOperator<2> op(*constant.space, basis, o);
    op.prepare(0., 0.1);
    EXPECT_EQ(op.modes(), r >= 1) << op.auto_choice();
    EXPECT_FALSE(op.iterative());
    EXPECT_EQ(op.auto_choice().rfind(r >= 1 ? "modes (" : "UMFPACK (", 0), 0u)
        << op.auto_choice();
    EXPECT_EQ(solves_by_modes(o, constant.space->n_dofs(), r + 1, 1, true, true), r >= 1);
  }
  // the modes' predicted peak decides against the memory budget
  const double n = constant.space->n_dofs();
  SlabSolverOptions tight = o;
  // (with a 10% margin)
  tight.auto_memory_mb = 1.09 * predicted_modes_mb(n, 1, 3);
  EXPECT_FALSE(auto_picks_modes(tight, n, 3, 1, true));
  tight.auto_memory_mb = 1.11 * predicted_modes_mb(n, 1, 3);
  EXPECT_TRUE(auto_picks_modes(tight, n, 3, 1, true));
  EXPECT_FALSE(auto_picks_modes(tight, n, 3, 1, false)); // a factorization per slab
  // MUMPS keeps the coupled solve
  SlabSolverOptions mumps = o;
  mumps.direct_solver = DirectEngine::mumps;
  EXPECT_FALSE(solves_by_modes(mumps, 1e3, 3, 1, true, true));

  SlabProblem rotating("manufactured", "rotating", 1, 1e-2);
  ASSERT_TRUE(rotating.scene->coefficients_depend_on_time());
  const TemporalBasis basis(2);
  SlabOperator<2> auto_op(*rotating.space, basis, o);
  auto_op.prepare(0., 0.1);
  EXPECT_FALSE(auto_op.modes()) << auto_op.auto_choice();
  SlabOperator<2> modes(*rotating.space, basis, modes_options());
  SlabOperator<2> direct(*rotating.space, basis, SlabSolverOptions::direct(true));
  modes.prepare(0., 0.1);
  direct.prepare(0., 0.1);
  EXPECT_FALSE(modes.modes());
  const Vector<double> load = random_vector(direct.n_slab_dofs(), 1);
  Vector<double> U_direct, U_modes;
  direct.solve(load, U_direct);
  modes.solve(load, U_modes);
  EXPECT_EQ(relative_difference(U_modes, U_direct), 0.);
}

// The mode solver's memory prediction from recorded figures: at the recorded size the
// factors of r+1 modes (one real LU for odd r+1, a complex one per pair) and the peak,
// each mode's peak beside the factors of the modes before it (pairs first); larger
// meshes scale per unknown times log n / log n0.
TEST(ModesChoice, PredictsFromRecordedModeFigures)
{
  reset_lu_records();
  const double n = 1e5;
  ModeLuFigures f;
  f.real_factor_mb = 60;
  f.real_peak_mb = 90; // work space 30
  f.complex_factor_mb = 110;
  f.complex_peak_mb = 130; // work space 20
  record_modes(n, 2, f);
  // (dG(2)'s blocks: the complex pair first, its peak, then the real mode's beside its
// factors)
  const ModesMemory three = predicted_modes_memory(n, 2, 3), four = predicted_modes_memory(n, 2, 4);
  EXPECT_DOUBLE_EQ(three.factors_mb, 170.);
  EXPECT_DOUBLE_EQ(three.peak_mb, 110. + 90.);
  EXPECT_DOUBLE_EQ(four.factors_mb, 220.);
  EXPECT_DOUBLE_EQ(four.peak_mb, 110. + 130.);
  EXPECT_DOUBLE_EQ(predicted_modes_mb(n, 2, 2), 130.);
  EXPECT_DOUBLE_EQ(predicted_modes_mb(n, 2, 1), 90.);
  const double scale = 4. * std::log2(4e5) / std::log2(1e5);
  EXPECT_NEAR(predicted_modes_memory(4e5, 2, 3).peak_mb, 200. * scale, 1e-9);
  // a dG(3) factorization records only complex figures: the real record stays
  ModeLuFigures pairs;
  pairs.complex_factor_mb = 240;
  pairs.complex_peak_mb = 260;
  record_modes(2 * n, 2, pairs);
  // (a smaller mesh scales linearly: the log factor only grows)
  EXPECT_DOUBLE_EQ(predicted_modes_memory(n, 2, 3).factors_mb, 60. + 120.);
  EXPECT_DOUBLE_EQ(predicted_modes_memory(n, 2, 3).peak_mb, 120. + 90.);
  EXPECT_DOUBLE_EQ(predicted_modes_memory(2 * n, 2, 1).factors_mb,
                   60. * 2 * std::log2(2e5) / std::log2(1e5));
  // another degree has no record: the fit
  EXPECT_GT(predicted_modes_mb(n, 3, 3), 0.);
  EXPECT_NE(predicted_modes_mb(n, 3, 3), 200.);
  reset_lu_records();
}

// The measured heap of a UMFPACK factorization (solver/umfpack_memory.h) against
// UMFPACK's own figures, real and complex: the factors held afterwards are at least
// UMFPACK's numeric object and at most the peak; the peak covers UMFPACK's own peak and
// the solver's copy of the matrix (8-byte indices and values: 16 bytes per entry, 24
// complex).
TEST(UmfpackHeapMeter, BoundsTheFactorization)
{
  const unsigned int g = 120, n = g * g;
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int i = 0; i < g; ++i)
    for (unsigned int j = 0; j < g; ++j)
    {
      const unsigned int k = i * g + j;
      dsp.add(k, k);
      if (i > 0) dsp.add(k, k - g);
      if (i + 1 < g) dsp.add(k, k + g);
      if (j > 0) dsp.add(k, k - 1);
      if (j + 1 < g) dsp.add(k, k + 1);
    }
  SparsityPattern sp;
  sp.copy_from(dsp);
  SparseMatrix<double> S1(sp), S2(sp);
  for (unsigned int k = 0; k < n; ++k)
    for (auto e = S2.begin(k); e != S2.end(k); ++e)
    {
      const bool diagonal = e->column() == k;
      e->value() = diagonal ? 4.2 : (e->column() == k + 1 ? -1.3 : -0.7);
      S1.set(k, e->column(), diagonal ? 1. : 0.);
    }
  const double MB = 1024. * 1024., nnz = double(sp.n_nonzero_elements());

  DirectSolver real(0);
  real.analyze(S2);
  real.factorize();
  const DirectSolverInfo &r = real.info();
  EXPECT_GT(r.factor_mb, 0.);
  EXPECT_GE(r.heap_held_mb, r.factor_mb);
  EXPECT_LE(r.heap_held_mb, r.heap_peak_mb);
  EXPECT_GE(r.heap_peak_mb, r.peak_mb);
  EXPECT_GE(r.heap_peak_mb, r.factor_mb + 16. * nnz / MB);
  EXPECT_LE(r.heap_peak_mb, 3. * (r.peak_mb + 16. * nnz / MB));

  ComplexDirectSolver complex(0);
  complex.factorize({0.5, 0.8}, S1, S2);
  const DirectSolverInfo &c = complex.info();
  // (UMFPACK's figure for the complex factors can exceed what stays allocated a little)
  EXPECT_GE(c.heap_held_mb, 0.95 * c.factor_mb);
  EXPECT_LE(c.heap_held_mb, c.heap_peak_mb);
  EXPECT_GE(c.heap_peak_mb, c.factor_mb + 24. * nnz / MB);
  EXPECT_LE(c.heap_peak_mb, 3. * (c.peak_mb + 24. * nnz / MB));
  // a complex LU holds more than a real one of the same pattern
  EXPECT_GT(c.heap_held_mb, r.heap_held_mb);
}
