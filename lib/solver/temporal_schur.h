#pragma once
// The temporal modes of a two-term Kronecker sum K = T1 (x) S1 + T2 (x) S2 (m x m
// temporal factors T1, T2 with T2 invertible, spatial S1, S2): the real Schur form of
// G = T2^{-1} T1 and the gather/scatter between the interleaved slab layout (index
// i*m + k, time/slab_vector.h) and the modes. Shared by the Kronecker preconditioners
// (an inexact solve per mode) and the direct mode solver (an LU per mode).
//
// With G = Q T Q^T (Q orthogonal, T quasi upper triangular with standardized 2x2
// blocks [[a, b], [c, a]], b c < 0),
//
//   K = (T2 Q (x) I) (T (x) S1 + I (x) S2) (Q^T (x) I),
//
// so K x = f is y' = (Q^T T2^{-1} (x) I) f, a block back substitution with
// T (x) S1 + I (x) S2, and x = (Q (x) I) y. A 1x1 block t is the spatial matrix
// t S1 + S2; a 2x2 block is, after scaling its second component by sigma, the complex
// matrix (a + i beta) S1 + S2, beta = sqrt(-b c) (see ModeBlock).
#include <deal.II/lac/full_matrix.h>

#include <cstddef>
#include <vector>

namespace anisodwr
{
/// One diagonal block of the Schur factor T: 1x1 (real eigenvalue `shift`) or 2x2
/// (eigenvalues alpha +- i beta). For a 2x2 block [[a, b], [c, a]] with components
/// (y1, y2) and right-hand side (r1, r2): y2 = sigma zz and
///   [[B, -beta S1], [beta S1, B]] [y1; zz] = [r1; rho r2],  B = alpha S1 + S2,
/// i.e. ((alpha + i beta) S1 + S2)(y1 + i zz) = r1 + i rho r2, with sigma = -beta/b and
/// rho = beta/c. For the transposed block, sigma and rho swap roles: y2 = -rho zz,
/// right-hand side r1 - i r2 / rho, and the complex matrix is transposed (not
/// conjugated).
struct ModeBlock
{
  unsigned int first = 0, size = 1;
  double shift = 0, alpha = 0, beta = 0, sigma = 0, rho = 0;
};

/// The real Schur form of G = T2^{-1} T1 (of T2^{-T} T1^T if `transpose`).
struct TemporalSchur
{
  unsigned int m = 0;
  dealii::FullMatrix<double> T, Q;
  /// T2^{-1} (of the transposed factor if `transpose`)
  dealii::FullMatrix<double> T2inv;
  /// P = Q^T T2^{-1}: the right-hand side in the Schur basis is (P (x) I) f.
  dealii::FullMatrix<double> P;
  /// The diagonal blocks of T in order.
  std::vector<ModeBlock> blocks;

  TemporalSchur() = default;
  TemporalSchur(const dealii::FullMatrix<double> &T1,
                const dealii::FullMatrix<double> &T2, bool transpose = false);

  unsigned int n_real() const;
  unsigned int n_complex_pairs() const;
};

/// y_k[i] = sum_l A(k, l) x[i*m + l] for k < m = A.m() (interleaved -> modes); the y_k
/// hold n entries each.
void gather_modes(const dealii::FullMatrix<double> &A, const double *x, std::size_t n,
                  const std::vector<double *> &y);
/// out[i*m + k] = beta out[i*m + k] + alpha sum_l A(k, l) y_l[i] (modes -> interleaved;
/// beta = 0 overwrites out).
void scatter_modes(const dealii::FullMatrix<double> &A,
                   const std::vector<const double *> &y, std::size_t n, double *out,
                   double alpha = 1., double beta = 0.);
} // namespace anisodwr
