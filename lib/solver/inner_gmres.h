#pragma once
// Inner Krylov solves of the Kronecker preconditioners (internal to lib/solver/): a
// right-preconditioned Belos GMRES on one temporal mode block, and the Tpetra operator
// made of a function that both the block operators and their preconditioners use.
#include "solver/tpetra_bridge.h"

#include <functional>

namespace anisodwr::tpetra
{
/// A Tpetra operator given by y = f(x) on one map (single vectors; Y = beta Y + alpha
/// f(X) column by column).
class FunctionOperator : public OP
{
public:
  using Function = std::function<void(const Vec &, Vec &)>;
  FunctionOperator(const RCP<const Map> &map, Function f);

  RCP<const Map> getDomainMap() const override { return map; }
  RCP<const Map> getRangeMap() const override { return map; }
  void apply(const MV &X, MV &Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1., double beta = 0.) const override;

private:
  RCP<const Map> map;
  Function f;
  RCP<Vec> work;
};

/// At most max_iterations of GMRES (no restart) on A x = b, right preconditioned by P,
/// from x = 0, stopping at ||b - A x|| <= tolerance ||b||. Returns the iterations used;
/// an unconverged inner solve is not an error (the outer flexible GMRES absorbs it).
unsigned int inner_gmres(const RCP<const OP> &A, const RCP<const OP> &P, const Vec &b,
                         Vec &x, unsigned int max_iterations, double tolerance);
} // namespace anisodwr::tpetra
