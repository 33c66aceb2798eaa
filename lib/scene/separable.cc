#include "scene/separable.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cmath>
#include <memory>

namespace anisodwr
{
using namespace dealii;

namespace separable_detail // not anonymous: unity builds merge this file with others
{
using Column = std::vector<double>;

double dot(const Column &a, const Column &b)
{
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    s += a[i] * b[i];
  return s;
}

/// Columns of F (F[j] = f(points, t_j)) chosen by Gram-Schmidt with column pivoting
/// until every column's rest is below `tol` times the largest column's norm; empty if
/// that takes more than max_terms columns.
std::vector<std::size_t> pivot_columns(const std::vector<Column> &F, unsigned int max_terms,
                                       double tol)
{
  std::vector<Column> rest = F;
  double largest = 0;
  for (const auto &c : F)
    largest = std::max(largest, std::sqrt(dot(c, c)));
  std::vector<std::size_t> chosen;
  if (largest == 0)
    return {0};
  while (true)
  {
    std::size_t j_max = 0;
    double n_max = -1;
    for (std::size_t j = 0; j < rest.size(); ++j)
      if (const double n = std::sqrt(dot(rest[j], rest[j])); n > n_max)
      {
        n_max = n;
        j_max = j;
      }
    if (n_max <= tol * largest)
      return chosen;
    if (chosen.size() == max_terms)
      return {};
    chosen.push_back(j_max);
    Column q = rest[j_max];
    for (double &v : q)
      v /= n_max;
    for (auto &c : rest)
      for (int pass = 0; pass < 2; ++pass) // twice: orthogonal to round-off
      {
        const double s = dot(q, c);
        for (std::size_t i = 0; i < c.size(); ++i)
          c[i] -= s * q[i];
      }
  }
}

/// Rows of the n x k matrix A (columns `cols` of F) chosen by Gaussian elimination with
/// row pivoting: A restricted to them is as well conditioned as pivoting gives.
std::vector<std::size_t> pivot_rows(const std::vector<Column> &F,
                                    const std::vector<std::size_t> &cols)
{
  std::vector<Column> A;
  for (const auto j : cols)
    A.push_back(F[j]);
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k < A.size(); ++k)
  {
    std::size_t r = 0;
    for (std::size_t i = 1; i < A[k].size(); ++i)
      if (std::abs(A[k][i]) > std::abs(A[k][r]))
        r = i;
    rows.push_back(r);
    for (std::size_t l = k + 1; l < A.size(); ++l)
    {
      const double m = A[l][r] / A[k][r];
      for (std::size_t i = 0; i < A[l].size(); ++i)
        A[l][i] -= m * A[k][i];
    }
  }
  return rows;
}

std::atomic<std::uint64_t> next_decomposition_id{1};

/// a(t) = M^{-1} f(x_k, t), the time factors of all terms at once; the last t's factors
/// are kept per thread (the terms ask for them one after the other at the same t).
struct TimeCoefficients
{
  std::function<double(const Point<2> &, double)> f;
  FullMatrix<double> M;
  std::vector<Point<2>> x_k;
  /// tells the factors of this decomposition from an earlier one at the same address
  std::uint64_t id = next_decomposition_id++;

  const Vector<double> &at(double t) const
  {
    thread_local struct
    {
      std::uint64_t owner = 0;
      double t = 0;
      Vector<double> a;
    } last;
    if (last.owner != id || last.t != t)
    {
      Vector<double> v(x_k.size());
      for (std::size_t i = 0; i < x_k.size(); ++i)
        v[i] = f(x_k[i], t);
      last.a.reinit(x_k.size());
      M.vmult(last.a, v);
      last.owner = id;
      last.t = t;
    }
    return last.a;
  }
};
/// Whether the separation f(x, t) = sum_l a_l(t) f(x, t_l) (a from `coefficients`, t_l
/// the sampled times of the pivot columns `cols` of the samples F at `points`) holds to
/// 1e-11 of f's largest sample: at `points` at the m + 1 times jT/m (between the sampled
/// ones, and 0 and T), and at `check_points` at three times that were not sampled.
bool reproduces_f(const std::function<double(const Point<2> &, double)> &f,
                  const TimeCoefficients &coefficients, const std::vector<Column> &F,
                  const std::vector<std::size_t> &cols, const std::vector<double> &times,
                  const std::vector<Point<2>> &points,
                  const std::vector<Point<2>> &check_points, double end_time)
{
  const std::size_t k = cols.size(), m = times.size();
  double scale = 0;
  for (const auto &c : F)
    for (const double v : c)
      scale = std::max(scale, std::abs(v));
  for (std::size_t j = 0; j <= m; ++j)
  {
    const double t = end_time * j / m;
    const Vector<double> &a = coefficients.at(t);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      double g = 0;
      for (std::size_t l = 0; l < k; ++l)
        g += a[l] * F[cols[l]][i];
      if (!(std::abs(g - f(points[i], t)) <= 1e-11 * scale))
        return false;
    }
  }
  std::vector<double> check_times;
  std::vector<Vector<double>> check_a;
  for (const double s : {0.1234, 0.5678, 0.9012})
  {
    check_times.push_back(s * end_time);
    check_a.push_back(coefficients.at(check_times.back()));
  }
  std::vector<double> g_x(k);
  for (const auto &x : check_points)
  {
    for (std::size_t l = 0; l < k; ++l)
      g_x[l] = f(x, times[cols[l]]);
    for (std::size_t j = 0; j < check_times.size(); ++j)
    {
      double g = 0;
      for (std::size_t l = 0; l < k; ++l)
        g += check_a[j][l] * g_x[l];
      if (!(std::abs(g - f(x, check_times[j])) <= 1e-11 * scale))
        return false;
    }
  }
  return true;
}
} // namespace separable_detail

bool separate_in_time(const std::function<double(const Point<2> &, double)> &f,
                      bool uses_t, const std::vector<Point<2>> &points,
                      const std::vector<Point<2>> &check_points, double end_time,
                      std::vector<LoadTerm<2>> &terms, unsigned int max_terms)
{
  using namespace separable_detail;
  terms.clear();
  if (!uses_t)
  {
    terms.push_back({[](double) { return 1.; },
                     [f](const Point<2> &x) { return f(x, 0.); }});
    return true;
  }
  if (points.empty())
    return false;
  const unsigned int m = 4 * max_terms;
  const auto sample = [&](double t)
  {
    Column c(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      c[i] = f(points[i], t);
    return c;
  };
  std::vector<double> times;
  std::vector<Column> F;
  for (unsigned int j = 0; j < m; ++j)
  {
    times.push_back(end_time * (j + 0.5) / m);
    F.push_back(sample(times.back()));
  }
  const auto cols = pivot_columns(F, max_terms, 1e-12);
  if (cols.empty())
    return false;
  const auto rows = pivot_rows(F, cols);
  const std::size_t k = cols.size();
  FullMatrix<double> M(k, k);
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t l = 0; l < k; ++l)
      M(i, l) = F[cols[l]][rows[i]];
  try
  {
    M.gauss_jordan();
  }
  catch (...)
  {
    return false;
  }
  std::vector<Point<2>> x_k;
  for (const auto r : rows)
    x_k.push_back(points[r]);
  const auto coefficients =
      std::make_shared<const TimeCoefficients>(TimeCoefficients{f, M, x_k});
  if (!reproduces_f(f, *coefficients, F, cols, times, points, check_points, end_time))
    return false;
  for (std::size_t l = 0; l < k; ++l)
  {
    const double t_l = times[cols[l]];
    terms.push_back({[coefficients, l](double t) { return coefficients->at(t)[l]; },
                     [f, t_l](const Point<2> &x) { return f(x, t_l); }});
  }
  return true;
}
} // namespace anisodwr
