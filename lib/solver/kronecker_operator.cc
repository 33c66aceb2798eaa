#include "solver/kronecker_operator.h"

#include "time/slab_vector.h"

#include <map>
#include <stdexcept>

namespace anisodwr::tpetra
{
KroneckerOperator::KroneckerOperator(const RCP<const Map> &slab_map,
                                     const std::vector<KronTerm> &terms, bool transpose)
    : slab_map(slab_map)
{
  m = terms.at(0).T.m();
  space_map = serial_map(terms[0].S->m());
  std::map<const dealii::SparseMatrix<double> *, RCP<Matrix>> converted;
  for (const auto &t : terms)
  {
    Term term;
    term.T.reinit(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        term.T(i, j) = transpose ? t.T(j, i) : t.T(i, j);
    auto &S = converted[t.S];
    if (S.is_null())
      S = to_tpetra(space_map, *t.S, 1., nullptr, 0., transpose);
    term.S = S;
    this->terms.push_back(term);
  }
  for (unsigned int k = 0; k < m; ++k)
  {
    xs.push_back(rcp(new Vec(space_map)));
    ys.push_back(rcp(new Vec(space_map)));
    sx.push_back(rcp(new Vec(space_map)));
  }
}

void KroneckerOperator::apply(const MV &X, MV &Y, Teuchos::ETransp mode, double alpha,
                              double beta) const
{
  if (mode != Teuchos::NO_TRANS)
    throw std::logic_error("Kronecker operator: transposed apply not implemented");
  const std::size_t n = space_map->getNodeNumElements();
  const SlabLayout slab{m};
  for (std::size_t c = 0; c < X.getNumVectors(); ++c)
  {
    {
      auto x = X.getData(c);
      for (unsigned int k = 0; k < m; ++k)
      {
        auto xk = xs[k]->getDataNonConst();
        for (std::size_t i = 0; i < n; ++i)
          xk[i] = x[slab.index(i, k)];
      }
    }
    for (unsigned int k = 0; k < m; ++k)
      ys[k]->putScalar(0.);
    for (const auto &t : terms)
      for (unsigned int l = 0; l < m; ++l)
      {
        bool used = false;
        for (unsigned int k = 0; k < m; ++k)
          used = used || t.T(k, l) != 0.;
        if (!used)
          continue;
        t.S->apply(*xs[l], *sx[l]);
        for (unsigned int k = 0; k < m; ++k)
          if (t.T(k, l) != 0.)
            ys[k]->update(t.T(k, l), *sx[l], 1.);
      }
    auto y = Y.getDataNonConst(c);
    for (unsigned int k = 0; k < m; ++k)
    {
      auto yk = ys[k]->getData();
      for (std::size_t i = 0; i < n; ++i)
        y[slab.index(i, k)] =
            (beta == 0. ? 0. : beta * y[slab.index(i, k)]) + alpha * yk[i];
    }
  }
}
} // namespace anisodwr::tpetra
