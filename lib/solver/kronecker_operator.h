#pragma once
// The slab matrix K = sum_t T_t (x) S_t applied matrix-free (internal to lib/solver/).
#include "solver/tpetra_bridge.h"
#include "time/kronecker.h"

#include <vector>

namespace anisodwr::tpetra
{
/// K = sum_t T_t (x) S_t (or K^T) applied from its m x m blocks per spatial entry
/// (KronBlocks), on the Tpetra vectors' own storage.
class KroneckerOperator : public OP
{
public:
  KroneckerOperator(const RCP<const Map> &slab_map, const std::vector<KronTerm> &terms,
                    bool transpose);

  RCP<const Map> getDomainMap() const override { return slab_map; }
  RCP<const Map> getRangeMap() const override { return slab_map; }

  void apply(const MV &X, MV &Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1., double beta = 0.) const override;

private:
  RCP<const Map> slab_map;
  KronBlocks K;
  bool transpose;
  mutable std::vector<double> y;
};
} // namespace anisodwr::tpetra
