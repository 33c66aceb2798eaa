#pragma once
// Ifpack2 preconditioners by name (internal to lib/solver/).
#include "solver/iterative_solver.h"
#include "solver/tpetra_bridge.h"

#include <string>

namespace anisodwr::tpetra
{
/// ilut, riluk, block_ilu (A a BlockCrsMatrix), block_jacobi or block_gauss_seidel (over
/// n_blocks linear parts) on A, initialized and computed; fill and drop from `o`.
RCP<Prec> make_ifpack2(Preconditioner type, const RCP<const RowMatrix> &A,
                       const IterativeOptions &o, LO n_blocks);
} // namespace anisodwr::tpetra
