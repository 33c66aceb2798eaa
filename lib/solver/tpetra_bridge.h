#pragma once
// The Tpetra side of the slab solvers (internal to lib/solver/): the Tpetra types, the
// one-time Kokkos set-up and the serial communicator, and copies of deal.II sparse
// matrices (and of the 2x2 Kronecker blocks of the Schur-form preconditioner) into
// Tpetra CSR matrices with sorted rows.
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>

#include <Ifpack2_Preconditioner.hpp>
#include <Teuchos_RCP.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>
#include <Tpetra_Vector.hpp>

#include <cstddef>

namespace anisodwr::tpetra
{
using Map = Tpetra::Map<>;
using LO = Map::local_ordinal_type;
using GO = Map::global_ordinal_type;
using Node = Map::node_type;
using Matrix = Tpetra::CrsMatrix<double, LO, GO, Node>;
using RowMatrix = Tpetra::RowMatrix<double, LO, GO, Node>;
using MV = Tpetra::MultiVector<double, LO, GO, Node>;
using Vec = Tpetra::Vector<double, LO, GO, Node>;
using OP = Tpetra::Operator<double, LO, GO, Node>;
using Prec = Ifpack2::Preconditioner<double, LO, GO, Node>;
using Teuchos::RCP;
using Teuchos::rcp;

/// Initializes Kokkos on first use (never finalized).
void ensure_kokkos();

RCP<const Teuchos::Comm<int>> serial_comm();

/// The serial map of n indices.
RCP<const Map> serial_map(std::size_t n);

/// CSR of a*A + b*B (B on A's pattern, may be null), optionally transposed; sorted rows.
RCP<Matrix> to_tpetra(const RCP<const Map> &map, const dealii::SparseMatrix<double> &A,
                      double a, const dealii::SparseMatrix<double> *B, double b,
                      bool transpose);

/// Tb (x) S1 + I (x) S2 in the interleaved ordering (block size Tb.m()), or its transpose
/// built from S1^T, S2^T if `transpose` (Tb is used as given).
RCP<Matrix> kron_block_tpetra(const RCP<const Map> &map,
                              const dealii::FullMatrix<double> &Tb,
                              const dealii::SparseMatrix<double> &S1,
                              const dealii::SparseMatrix<double> &S2, bool transpose);
} // namespace anisodwr::tpetra
