#include "time/temporal_basis.h"

#include <deal.II/base/quadrature_lib.h>

#include <cmath>
#include <stdexcept>

namespace anisodwr
{
namespace
{
// Legendre polynomial P_n(x) by the three-term recurrence.
double legendre(unsigned int n, double x)
{
  double p0 = 1., p1 = x;
  if (n == 0)
    return p0;
  for (unsigned int k = 1; k < n; ++k)
  {
    const double p2 = ((2. * k + 1.) * x * p1 - k * p0) / (k + 1.);
    p0 = p1;
    p1 = p2;
  }
  return p1;
}
} // namespace

std::vector<double> right_radau_points(unsigned int r)
{
  // The right Radau points on [-1,1] are the roots of P_{r+1} - P_r; x = 1 is one
  // of them. The others are simple roots in (-1,1): bracket by sign changes on a
  // fine grid, then bisect to round-off.
  auto f = [r](double x) { return legendre(r + 1, x) - legendre(r, x); };
  std::vector<double> x_roots;
  const unsigned int n_grid = 400 * (r + 1);
  const double h = 2.0 / n_grid;
  for (unsigned int i = 0; i + 1 < n_grid; ++i) // stop before the root x = 1
  {
    double a = -1. + i * h, b = a + h;
    double fa = f(a), fb = f(b);
    if (fa == 0.)
    {
      x_roots.push_back(a);
      continue;
    }
    if (fa * fb > 0.)
      continue;
    for (int it = 0; it < 200 && b - a > 1e-16; ++it)
    {
      const double m = 0.5 * (a + b), fm = f(m);
      if (fa * fm <= 0.)
        b = m;
      else
      {
        a = m;
        fa = fm;
      }
    }
    x_roots.push_back(0.5 * (a + b));
  }
  x_roots.push_back(1.0);
  if (x_roots.size() != r + 1)
    throw std::logic_error("right_radau_points: found " + std::to_string(x_roots.size()) +
                           " roots, expected " + std::to_string(r + 1));
  std::vector<double> s(r + 1);
  for (unsigned int k = 0; k <= r; ++k)
    s[k] = 0.5 * (x_roots[k] + 1.);
  return s;
}

void gauss_rule(unsigned int n, std::vector<double> &points, std::vector<double> &weights)
{
  const dealii::QGauss<1> q(n);
  points.resize(n);
  weights.resize(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    points[i] = q.point(i)[0];
    weights[i] = q.weight(i);
  }
}

TemporalBasis::TemporalBasis(unsigned int r_)
    : r(r_), s_nodes(right_radau_points(r_)), M(r_ + 1, r_ + 1), D(r_ + 1, r_ + 1),
      e(r_ + 1), y(r_ + 1)
{
  // Products l_k l_l and l_k l_l' have degree <= 2r: r+1 Gauss points are exact.
  std::vector<double> sq, wq;
  gauss_rule(r + 1, sq, wq);
  for (unsigned int q = 0; q < sq.size(); ++q)
    for (unsigned int k = 0; k <= r; ++k)
      for (unsigned int l = 0; l <= r; ++l)
      {
        M(k, l) += wq[q] * value(l, sq[q]) * value(k, sq[q]);
        D(k, l) += wq[q] * derivative(l, sq[q]) * value(k, sq[q]);
      }
  for (unsigned int k = 0; k <= r; ++k)
  {
    e[k] = value(k, 0.);
    y[k] = value(k, 1.);
  }
  for (unsigned int k = 0; k <= r; ++k)
    for (unsigned int l = 0; l <= r; ++l)
      D(k, l) += e[l] * e[k];
}

double TemporalBasis::value(unsigned int k, double s) const
{
  double v = 1.;
  for (unsigned int m = 0; m <= r; ++m)
    if (m != k)
      v *= (s - s_nodes[m]) / (s_nodes[k] - s_nodes[m]);
  return v;
}

double TemporalBasis::derivative(unsigned int k, double s) const
{
  double d = 0.;
  for (unsigned int j = 0; j <= r; ++j)
  {
    if (j == k)
      continue;
    double term = 1. / (s_nodes[k] - s_nodes[j]);
    for (unsigned int m = 0; m <= r; ++m)
      if (m != k && m != j)
        term *= (s - s_nodes[m]) / (s_nodes[k] - s_nodes[m]);
    d += term;
  }
  return d;
}

std::vector<double> TemporalBasis::values(double s) const
{
  std::vector<double> v(r + 1);
  for (unsigned int k = 0; k <= r; ++k)
    v[k] = value(k, s);
  return v;
}

dealii::FullMatrix<double> outer(const std::vector<double> &a, const std::vector<double> &b)
{
  dealii::FullMatrix<double> m(a.size(), b.size());
  for (unsigned int i = 0; i < a.size(); ++i)
    for (unsigned int j = 0; j < b.size(); ++j)
      m(i, j) = a[i] * b[j];
  return m;
}
} // namespace anisodwr
