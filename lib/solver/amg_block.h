#pragma once
// Algebraic multigrid (ML through deal.II's TrilinosWrappers::PreconditionAMG on
// Epetra) for one spatial block of the Kronecker preconditioners (internal to
// lib/solver/).
#include "solver/iterative_solver.h"
#include "solver/tpetra_bridge.h"

#include <memory>

class Epetra_MpiComm;
class Epetra_Map;
class Epetra_CrsMatrix;
class Epetra_MultiVector;
namespace dealii::TrilinosWrappers
{
class PreconditionAMG;
}

namespace anisodwr::tpetra
{
/// One ML AMG hierarchy (deal.II TrilinosWrappers::PreconditionAMG, Epetra) for a serial
/// spatial block given as a Tpetra matrix; applied to Tpetra vectors through Epetra
/// views of their host data (no copies). block_size 2 (the real 2n x 2n form of a complex
/// shift, interleaved) aggregates the two unknowns of a node together ("PDE equations").
class AmgBlock
{
public:
  AmgBlock(const Matrix &A, unsigned int block_size, const IterativeOptions &o);
  ~AmgBlock();

  /// out = one V-cycle applied to in.
  void apply(const Vec &in, Vec &out) const;

private:
  /// matrix = the Epetra copy of A (on map, over comm).
  void copy_to_epetra(const Matrix &A);
  /// The ML hierarchy of `matrix`: nonsymmetric smoothed aggregation, one V-cycle.
  void build_hierarchy(unsigned int block_size, const IterativeOptions &o);

  std::unique_ptr<Epetra_MpiComm> comm;
  std::unique_ptr<Epetra_Map> map;
  std::unique_ptr<Epetra_CrsMatrix> matrix; // ML keeps a reference to it
  std::unique_ptr<Epetra_MultiVector> modes;
  std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
};
} // namespace anisodwr::tpetra
