#include "study/errors.h"

#include "slab/kronecker.h"

#include <algorithm>
#include <cmath>

namespace anisodwr
{
using namespace dealii;

template <int dim>
ErrorNorms compute_errors(const Space<dim> &space, const TimeMesh &mesh,
                          const TemporalBasis &basis, const std::vector<Vector<double>> &U)
{
  ErrorNorms e;
  std::vector<double> sq, wq;
  gauss_rule(basis.n_dofs() + 1, sq, wq);
  Vector<double> u;
  double sum = 0;
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    combine_blocks(U[n], basis.right_trace(), u);
    const double en = space.l2_error(u, mesh.t[n + 1]);
    e.nodal = std::max(e.nodal, en);
    if (n + 1 == mesh.n_slabs())
      e.L2_T = en;
    for (unsigned int q = 0; q < sq.size(); ++q)
    {
      combine_blocks(U[n], basis.values(sq[q]), u);
      const double eq = space.l2_error(u, mesh.start(n) + sq[q] * mesh.tau(n));
      sum += mesh.tau(n) * wq[q] * eq * eq;
    }
  }
  e.L2L2 = std::sqrt(sum);
  return e;
}

template ErrorNorms compute_errors<2>(const Space<2> &, const TimeMesh &, const TemporalBasis &,
                                      const std::vector<Vector<double>> &);
} // namespace anisodwr
