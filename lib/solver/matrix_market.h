#pragma once
// A slab matrix in Matrix Market format (output.dump_slab_loop).
#include <deal.II/lac/sparse_matrix.h>

#include <string>

namespace anisodwr
{
/// Writes A to `path` in Matrix Market coordinate format (1-based, all stored entries;
/// rank 0 writes, all ranks throw an InputError if it cannot). Collective.
void write_matrix_market(const dealii::SparseMatrix<double> &A, const std::string &path);
} // namespace anisodwr
