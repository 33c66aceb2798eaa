#pragma once
// dG(r) temporal basis and reference matrices on the reference interval (0,1].
//
// Basis: Lagrange polynomials l_0..l_r at the r+1 right Gauss-Radau points of
// (0,1] (the last node is s = 1, so the last coefficient is u(t_n^-)).
#include <deal.II/lac/full_matrix.h>

#include <vector>

namespace anisodwr
{
/// Nodes of the (r+1)-point right Gauss-Radau rule on (0,1] (ascending, last = 1).
std::vector<double> right_radau_points(unsigned int r);

/// Points and weights of the n-point Gauss rule on (0,1).
void gauss_rule(unsigned int n, std::vector<double> &points, std::vector<double> &weights);

class TemporalBasis
{
public:
  explicit TemporalBasis(unsigned int r);

  unsigned int degree() const { return r; }
  unsigned int n_dofs() const { return r + 1; }
  const std::vector<double> &nodes() const { return s_nodes; }

  /// l_k(s) and l_k'(s) on the reference interval.
  double value(unsigned int k, double s) const;
  double derivative(unsigned int k, double s) const;
  /// All values l_0(s)..l_r(s).
  std::vector<double> values(double s) const;

  /// M_kl = int_0^1 l_l l_k ds
  const dealii::FullMatrix<double> &mass() const { return M; }
  /// D_kl = int_0^1 l_l' l_k ds + l_l(0) l_k(0)  (time derivative + upwind jump)
  const dealii::FullMatrix<double> &derivative_with_jump() const { return D; }
  /// e_k = l_k(0): left trace of the test functions.
  const std::vector<double> &left_trace() const { return e; }
  /// y_l = l_l(1): right trace of the trial functions.
  const std::vector<double> &right_trace() const { return y; }

private:
  unsigned int r;
  std::vector<double> s_nodes;
  dealii::FullMatrix<double> M, D;
  std::vector<double> e, y;
};

/// Outer product a b^T as a FullMatrix.
dealii::FullMatrix<double> outer(const std::vector<double> &a, const std::vector<double> &b);
} // namespace anisodwr
