#pragma once
// Kronecker products of (r+1)x(r+1) temporal matrices with spatial sparse matrices,
// in the interleaved slab layout of time/slab_vector.h.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include "time/slab_vector.h"

#include <vector>

namespace anisodwr
{
/// One term T (x) S of a Kronecker sum.
struct KronTerm
{
  dealii::FullMatrix<double> T;
  const dealii::SparseMatrix<double> *S;
};

/// Pattern of T (x) S for a full m x m T and the spatial pattern of S.
void make_kron_sparsity(const dealii::SparsityPattern &spatial, unsigned int m,
                        dealii::SparsityPattern &out);

/// K = sum_t T_t (x) S_t; all S_t share one spatial pattern; K is reinit'ed on `pattern`.
void assemble_kron(const std::vector<KronTerm> &terms, const dealii::SparsityPattern &pattern,
                   dealii::SparseMatrix<double> &K);

/// K = sum_t T_t (x) S_t stored as one m x m block per entry of the spatial pattern the
/// S_t share: block q holds sum_t S_t[q] T_t. Its products read m^2 values per spatial
/// entry once, where a term-by-term product reads every S_t m times.
class KronBlocks
{
public:
  /// Sums the terms into blocks; throws if their S do not share one pattern.
  void reinit(const std::vector<KronTerm> &terms);
  /// dst = K src (interleaved layout, n*m entries each; dst is overwritten).
  void vmult(double *dst, const double *src) const;
  /// dst = K^T src.
  void Tvmult(double *dst, const double *src) const;
  std::size_t size() const { return n * m; }

private:
  std::size_t n = 0;
  unsigned int m = 1;
  std::vector<std::size_t> rowstart; // the spatial pattern in CSR form
  std::vector<dealii::types::global_dof_index> cols;
  std::vector<double> blocks; // entry q's block at q*m*m, row-major (k, l)
};

/// dst = (sum_t T_t (x) S_t) src, or with transposed factors if `transpose`.
void vmult_kron(const std::vector<KronTerm> &terms, const dealii::Vector<double> &src,
                dealii::Vector<double> &dst, bool transpose = false);
} // namespace anisodwr
