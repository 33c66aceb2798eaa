#include "solver/ifpack2_factory.h"

#include <Ifpack2_Factory.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace anisodwr::tpetra
{
RCP<Prec> make_ifpack2(Preconditioner type, const RCP<const RowMatrix> &A,
                       const IterativeOptions &o, LO n_blocks)
{
  Teuchos::ParameterList pl;
  std::string kind;
  if (type == Preconditioner::ilut)
  {
    kind = "ILUT";
    pl.set("fact: ilut level-of-fill", std::max(1., o.ilu_fill));
    pl.set("fact: drop tolerance", o.ilut_drop);
  }
  else if (type == Preconditioner::riluk || type == Preconditioner::block_ilu)
  {
    kind = type == Preconditioner::riluk ? "RILUK" : "RBILUK";
    pl.set("fact: iluk level-of-fill", static_cast<int>(std::lround(o.ilu_fill)));
  }
  else if (type == Preconditioner::block_jacobi || type == Preconditioner::block_gauss_seidel)
  {
    kind = "BLOCK RELAXATION";
    pl.set("relaxation: type",
           type == Preconditioner::block_jacobi ? "Jacobi" : "Gauss-Seidel");
    pl.set("relaxation: container", "Dense");
    pl.set("relaxation: sweeps", 1);
    pl.set("partitioner: type", "linear");
    pl.set("partitioner: local parts", n_blocks);
  }
  else
    throw std::invalid_argument("make_ifpack2: " + name(type) + " is not an Ifpack2 "
                                "preconditioner");
  Ifpack2::Factory factory;
  RCP<Prec> p = factory.create<RowMatrix>(kind, A);
  p->setParameters(pl);
  p->initialize();
  p->compute();
  return p;
}
} // namespace anisodwr::tpetra
