#pragma once
// The time mesh 0 = t_0 < ... < t_N = T (slab n is (t_{n-1}, t_n], n = 1..N).
#include <vector>

namespace anisodwr
{
struct TimeMesh
{
  std::vector<double> t;

  static TimeMesh uniform(double T, unsigned int n_slabs)
  {
    TimeMesh m;
    for (unsigned int n = 0; n <= n_slabs; ++n)
      m.t.push_back(T * n / n_slabs);
    return m;
  }
  unsigned int n_slabs() const { return t.size() - 1; }
  /// Start and length of slab n (0-based).
  double start(unsigned int n) const { return t[n]; }
  double tau(unsigned int n) const { return t[n + 1] - t[n]; }
  double max_tau() const
  {
    double h = 0;
    for (unsigned int n = 0; n < n_slabs(); ++n)
      h = tau(n) > h ? tau(n) : h;
    return h;
  }
};
} // namespace anisodwr
