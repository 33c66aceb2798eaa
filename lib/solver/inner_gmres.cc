#include "solver/inner_gmres.h"

#include <BelosBlockGmresSolMgr.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_oblackholestream.hpp>

#include <stdexcept>
#include <utility>

namespace anisodwr::tpetra
{
FunctionOperator::FunctionOperator(const RCP<const Map> &map, Function f)
    : map(map), f(std::move(f)), work(rcp(new Vec(map)))
{
}

void FunctionOperator::apply(const MV &X, MV &Y, Teuchos::ETransp mode, double alpha,
                             double beta) const
{
  if (mode != Teuchos::NO_TRANS)
    throw std::logic_error("FunctionOperator: transposed apply not implemented");
  for (std::size_t c = 0; c < X.getNumVectors(); ++c)
  {
    const auto x = X.getVector(c);
    auto y = Y.getVectorNonConst(c);
    if (alpha == 1. && beta == 0.)
      f(*x, *y);
    else
    {
      f(*x, *work);
      y->update(alpha, *work, beta);
    }
  }
}

unsigned int inner_gmres(const RCP<const OP> &A, const RCP<const OP> &P, const Vec &b,
                         Vec &x, unsigned int max_iterations, double tolerance)
{
  x.putScalar(0.);
  auto X = Teuchos::rcpFromRef(static_cast<MV &>(x));
  auto B = Teuchos::rcpFromRef(static_cast<const MV &>(b));
  auto problem = rcp(new Belos::LinearProblem<double, MV, OP>(A, X, B));
  problem->setRightPrec(P);
  problem->setProblem();
  static const RCP<std::ostream> quiet = rcp(new Teuchos::oblackholestream);
  auto pl = rcp(new Teuchos::ParameterList);
  pl->set("Convergence Tolerance", tolerance);
  pl->set("Maximum Iterations", static_cast<int>(max_iterations));
  pl->set("Num Blocks", static_cast<int>(max_iterations));
  pl->set("Maximum Restarts", 0);
  pl->set("Verbosity", static_cast<int>(Belos::Errors));
  pl->set("Output Stream", quiet);
  pl->set("Implicit Residual Scaling", "Norm of RHS");
  pl->set("Explicit Residual Test", false);
  Belos::BlockGmresSolMgr<double, MV, OP> solver(problem, pl);
  solver.solve(); // Belos errors reach the outer solve, which reports a breakdown
  return static_cast<unsigned int>(solver.getNumIters());
}
} // namespace anisodwr::tpetra
