#pragma once
// Kronecker products of (r+1)x(r+1) temporal matrices with spatial sparse matrices.
//
// Unknown ordering (interleaved): the r+1 temporal coefficients of spatial DoF i
// are neighbours, global index = i*(r+1) + k. The slab matrix is then a
// point-block matrix with (r+1)x(r+1) blocks.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

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

/// Temporal coefficient k of an interleaved slab vector with m coefficients per DoF.
void extract_block(const dealii::Vector<double> &U, unsigned int k, unsigned int m,
                   dealii::Vector<double> &u);
void insert_block(const dealii::Vector<double> &u, unsigned int k, unsigned int m,
                  dealii::Vector<double> &U);
/// U += factor * (a (x) c): adds factor * a_k * c to temporal block k of U.
void add_kron_vector(double factor, const std::vector<double> &a, const dealii::Vector<double> &c,
                     dealii::Vector<double> &U);
/// sum_k c_k U_k: e.g. the value u(t) = sum_k l_k(s) U_k.
void combine_blocks(const dealii::Vector<double> &U, const std::vector<double> &c,
                    dealii::Vector<double> &u);
} // namespace anisodwr
