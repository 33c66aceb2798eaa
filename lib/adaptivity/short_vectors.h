#pragma once
// Arithmetic on the estimator's cell vectors (W-local coefficients: 9 entries for Q2,
// 16 for Q3). At these sizes deal.II's Vector operations cost more in their dispatch
// (thread partitioner, parallel_for / parallel_reduce) than in the arithmetic. These
// helpers do the same arithmetic in the same order, so their results are bit-identical
// to deal.II's:
// - element-wise operations are one multiply and/or add per entry, as in deal.II;
// - matrix-vector products sum each row in its natural order;
// - sums of fewer than 32 terms follow deal.II's accumulate_recursive (up to three
//   chunks of 8 summed in turn, then the remainder, combined as there); longer vectors
//   go to deal.II itself.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cstddef>

namespace anisodwr::short_vectors
{
/// sum_i term(i), i < n < 32, in deal.II's order for short vectors.
template <class Term> inline double accumulate(const Term &term, std::size_t n)
{
  std::size_t i = 0;
  double r0 = 0., r1 = 0., r2 = 0.;
  switch (n / 8)
  {
  case 3:
    r2 = term(i++);
    for (unsigned int j = 1; j < 8; ++j)
      r2 += term(i++);
    [[fallthrough]];
  case 2:
    r1 = term(i++);
    for (unsigned int j = 1; j < 8; ++j)
      r1 += term(i++);
    r1 += r2;
    [[fallthrough]];
  case 1:
    r2 = term(i++);
    for (unsigned int j = 1; j < 8; ++j)
      r2 += term(i++);
    [[fallthrough]];
  default:
    for (std::size_t j = 0; j < n % 8; ++j)
      r0 += term(i++);
    r0 += r2;
    r0 += r1;
  }
  return r0;
}

/// a · b (= a * b of deal.II)
inline double dot(const dealii::Vector<double> &a, const dealii::Vector<double> &b)
{
  if (a.size() >= 32)
    return a * b;
  const double *x = a.begin(), *y = b.begin();
  return accumulate([&](std::size_t i) { return x[i] * y[i]; }, a.size());
}

/// |a|² (= a.norm_sqr())
inline double norm_sqr(const dealii::Vector<double> &a)
{
  if (a.size() >= 32)
    return a.norm_sqr();
  const double *x = a.begin();
  return accumulate([&](std::size_t i) { return x[i] * x[i]; }, a.size());
}

/// y += s x (= y.add(s, x))
inline void add(dealii::Vector<double> &y, double s, const dealii::Vector<double> &x)
{
  double *py = y.begin();
  const double *px = x.begin();
  for (std::size_t i = 0; i < y.size(); ++i)
    py[i] += s * px[i];
}

/// y -= x
inline void subtract(dealii::Vector<double> &y, const dealii::Vector<double> &x)
{
  double *py = y.begin();
  const double *px = x.begin();
  for (std::size_t i = 0; i < y.size(); ++i)
    py[i] -= px[i];
}

/// y *= s
inline void scale(dealii::Vector<double> &y, double s)
{
  for (double &e : y)
    e *= s;
}

/// y = 0
inline void zero(dealii::Vector<double> &y)
{
  std::fill(y.begin(), y.end(), 0.);
}

/// y = x (y reallocated only when the sizes differ)
inline void copy(dealii::Vector<double> &y, const dealii::Vector<double> &x)
{
  if (y.size() != x.size())
    y.reinit(x.size(), true);
  std::copy(x.begin(), x.end(), y.begin());
}

/// y = 0 with size n (reallocated only when the size changes)
inline void zero(dealii::Vector<double> &y, std::size_t n)
{
  if (y.size() != n)
    y.reinit(n);
  else
    zero(y);
}
/// y = s A x + (adding ? y : 0), A row-major as deal.II's FullMatrix. Four rows at a
/// time, so that the row sums run side by side (each row sums in its natural order).
inline void matrix_vector(dealii::Vector<double> &y, double s,
                          const dealii::FullMatrix<double> &A,
                          const dealii::Vector<double> &x, bool adding)
{
  const std::size_t m = A.m(), n = A.n();
  const double *a = n ? &A(0, 0) : nullptr, *px = x.begin();
  double *py = y.begin();
  std::size_t i = 0;
  for (; i + 4 <= m; i += 4, a += 4 * n)
  {
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    for (std::size_t j = 0; j < n; ++j)
    {
      s0 += a[j] * px[j];
      s1 += a[n + j] * px[j];
      s2 += a[2 * n + j] * px[j];
      s3 += a[3 * n + j] * px[j];
    }
    py[i] = s * s0 + (adding ? py[i] : 0.);
    py[i + 1] = s * s1 + (adding ? py[i + 1] : 0.);
    py[i + 2] = s * s2 + (adding ? py[i + 2] : 0.);
    py[i + 3] = s * s3 + (adding ? py[i + 3] : 0.);
  }
  for (; i < m; ++i, a += n)
  {
    double r = 0;
    for (std::size_t j = 0; j < n; ++j)
      r += a[j] * px[j];
    py[i] = s * r + (adding ? py[i] : 0.);
  }
}

/// y = A x (y reallocated only when its size differs)
inline void vmult(dealii::Vector<double> &y, const dealii::FullMatrix<double> &A,
                  const dealii::Vector<double> &x)
{
  if (y.size() != A.m())
    y.reinit(A.m(), true);
  matrix_vector(y, 1., A, x, false);
}

/// y += s A x
inline void add_vmult(dealii::Vector<double> &y, double s,
                      const dealii::FullMatrix<double> &A,
                      const dealii::Vector<double> &x)
{
  matrix_vector(y, s, A, x, true);
}
} // namespace anisodwr::short_vectors
