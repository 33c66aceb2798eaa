// dG(r) temporal basis and reference matrices against hand-computed values and
// against their definitions (independent high-order quadrature).
#include "time/temporal_basis.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace anisodwr;

TEST(TemporalBasis, RadauNodesByHand)
{
  EXPECT_NEAR(right_radau_points(0)[0], 1.0, 1e-15);
  const auto s1 = right_radau_points(1);
  EXPECT_NEAR(s1[0], 1. / 3., 1e-14);
  EXPECT_NEAR(s1[1], 1., 1e-15);
  const auto s2 = right_radau_points(2);
  EXPECT_NEAR(s2[0], (4. - std::sqrt(6.)) / 10., 1e-14);
  EXPECT_NEAR(s2[1], (4. + std::sqrt(6.)) / 10., 1e-14);
  EXPECT_NEAR(s2[2], 1., 1e-15);
}

TEST(TemporalBasis, MatricesByHandR0R1)
{
  const TemporalBasis b0(0);
  EXPECT_NEAR(b0.mass()(0, 0), 1., 1e-15);
  EXPECT_NEAR(b0.derivative_with_jump()(0, 0), 1., 1e-15);
  EXPECT_NEAR(b0.left_trace()[0], 1., 1e-15);
  EXPECT_NEAR(b0.right_trace()[0], 1., 1e-15);

  // l_0 = 3(1-s)/2, l_1 = (3s-1)/2
  const TemporalBasis b1(1);
  const double M[2][2] = {{0.75, 0.}, {0., 0.25}};
  const double D[2][2] = {{9. / 8., 3. / 8.}, {-9. / 8., 5. / 8.}};
  for (unsigned int k = 0; k < 2; ++k)
    for (unsigned int l = 0; l < 2; ++l)
    {
      EXPECT_NEAR(b1.mass()(k, l), M[k][l], 1e-14) << k << l;
      EXPECT_NEAR(b1.derivative_with_jump()(k, l), D[k][l], 1e-14) << k << l;
    }
  EXPECT_NEAR(b1.left_trace()[0], 1.5, 1e-14);
  EXPECT_NEAR(b1.left_trace()[1], -0.5, 1e-14);
  EXPECT_NEAR(b1.right_trace()[0], 0., 1e-14);
  EXPECT_NEAR(b1.right_trace()[1], 1., 1e-14);
}

TEST(TemporalBasis, MassIsRadauWeightsR2)
{
  // Radau quadrature with r+1 points is exact for degree 2r: M = diag(weights).
  const TemporalBasis b(2);
  const double w[3] = {(16. - std::sqrt(6.)) / 36., (16. + std::sqrt(6.)) / 36., 1. / 9.};
  for (unsigned int k = 0; k < 3; ++k)
    for (unsigned int l = 0; l < 3; ++l)
      EXPECT_NEAR(b.mass()(k, l), k == l ? w[k] : 0., 1e-14);
}

class TemporalBasisR : public ::testing::TestWithParam<unsigned int>
{
};

TEST_P(TemporalBasisR, MatricesMatchDefinitions)
{
  const unsigned int r = GetParam();
  const TemporalBasis b(r);
  // Independent evaluation: 12-point Gauss, derivative by the exact monomial
  // expansion is replaced by a 4th-order central difference of the Lagrange basis,
  // accurate to ~1e-9 for these low degrees.
  std::vector<double> sq, wq;
  gauss_rule(12, sq, wq);
  const double h = 1e-3;
  for (unsigned int k = 0; k <= r; ++k)
  {
    EXPECT_NEAR(b.value(k, b.nodes()[k]), 1., 1e-13);
    for (unsigned int l = 0; l <= r; ++l)
    {
      if (l != k)
      {
        EXPECT_NEAR(b.value(k, b.nodes()[l]), 0., 1e-13);
      }
      double m = 0, d = 0;
      for (unsigned int q = 0; q < sq.size(); ++q)
      {
        const double s = sq[q];
        const double dl = (-b.value(l, s + 2 * h) + 8 * b.value(l, s + h) -
                           8 * b.value(l, s - h) + b.value(l, s - 2 * h)) /
                          (12 * h);
        m += wq[q] * b.value(l, s) * b.value(k, s);
        d += wq[q] * dl * b.value(k, s);
      }
      d += b.value(l, 0.) * b.value(k, 0.);
      EXPECT_NEAR(b.mass()(k, l), m, 1e-13);
      EXPECT_NEAR(b.derivative_with_jump()(k, l), d, 1e-8);
    }
  }
  // Partition of unity: D 1 = e (the derivative of a constant vanishes).
  for (unsigned int k = 0; k <= r; ++k)
  {
    double row = 0;
    for (unsigned int l = 0; l <= r; ++l)
      row += b.derivative_with_jump()(k, l);
    EXPECT_NEAR(row, b.left_trace()[k], 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Degrees, TemporalBasisR, ::testing::Values(0u, 1u, 2u, 3u, 5u));
