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

/// dst = (sum_t T_t (x) S_t) src, or with transposed factors if `transpose`.
void vmult_kron(const std::vector<KronTerm> &terms, const dealii::Vector<double> &src,
                dealii::Vector<double> &dst, bool transpose = false);
} // namespace anisodwr
