#pragma once
// The slab matrix K = sum_t T_t (x) S_t applied matrix-free (internal to lib/solver/).
#include "solver/tpetra_bridge.h"
#include "time/kronecker.h"

#include <vector>

namespace anisodwr::tpetra
{
/// Matrix-free K = sum_t T_t (x) S_t (or K^T): m spatial products per term.
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
  struct Term
  {
    dealii::FullMatrix<double> T;
    RCP<Matrix> S;
  };
  unsigned int m = 1;
  RCP<const Map> slab_map, space_map;
  std::vector<Term> terms;
  std::vector<RCP<Vec>> xs, ys, sx;
};
} // namespace anisodwr::tpetra
