#include "solver/kronecker_operator.h"

#include <stdexcept>

namespace anisodwr::tpetra
{
KroneckerOperator::KroneckerOperator(const RCP<const Map> &slab_map,
                                     const std::vector<KronTerm> &terms, bool transpose)
    : slab_map(slab_map), transpose(transpose)
{
  K.reinit(terms);
  if (K.size() != slab_map->getNodeNumElements())
    throw std::logic_error("Kronecker operator: the terms do not match the slab map");
}

void KroneckerOperator::apply(const MV &X, MV &Y, Teuchos::ETransp mode, double alpha,
                              double beta) const
{
  if (mode != Teuchos::NO_TRANS)
    throw std::logic_error("Kronecker operator: transposed apply not implemented");
  const std::size_t N = K.size();
  y.resize(N);
  for (std::size_t c = 0; c < X.getNumVectors(); ++c)
  {
    auto x = X.getData(c);
    if (transpose)
      K.Tvmult(y.data(), x.getRawPtr());
    else
      K.vmult(y.data(), x.getRawPtr());
    auto out = Y.getDataNonConst(c);
    for (std::size_t i = 0; i < N; ++i)
      out[i] = (beta == 0. ? 0. : beta * out[i]) + alpha * y[i];
  }
}
} // namespace anisodwr::tpetra
