#pragma once
// The Radau reconstruction E_tau in time (doc/method.md §7), as coefficient arrays on
// the reference slab (0,1]:
//
//   primal:  E u is the polynomial of degree r+1 with E u(s_k) = u(s_k) at the right
//            Radau nodes and E u(0) = u(t_{n-1}^-);
//   adjoint: E z is the polynomial of degree r+1 with E z(1 - s_k) = z(1 - s_k) at the
//            left Radau nodes and E z(1) = z(t_n^+).
//
// Both are continuous at the slab ends by construction. All values are linear
// combinations of the slab coefficients U_0..U_r and one outside value.
#include "time/temporal_basis.h"

#include <vector>

namespace anisodwr
{
/// Coefficients of a value: outside * (outside vector) + sum_k slab[k] * U_k.
struct TimeCombination
{
  double outside = 0;
  std::vector<double> slab;
};

class TemporalReconstruction
{
public:
  explicit TemporalReconstruction(const TemporalBasis &basis);

  /// (E u)(s) (derivative = false) or d/ds (E u)(s); outside = u(t_{n-1}^-).
  TimeCombination primal(double s, bool derivative = false) const;
  /// (E z)(s) or d/ds (E z)(s); outside = z(t_n^+).
  TimeCombination adjoint(double s, bool derivative = false) const;

private:
  const TemporalBasis &basis;
  std::vector<double> primal_nodes, adjoint_nodes; // r+2 nodes each
};

/// Value (or derivative) at s of the Lagrange polynomial j on `nodes`.
double lagrange(const std::vector<double> &nodes, unsigned int j, double s,
                bool derivative = false);
} // namespace anisodwr
