#include "slab/adjoint_march.h"

namespace anisodwr
{
using namespace dealii;

template <int dim>
std::vector<Vector<double>>
march_adjoint(const Space<dim> &space, const TimeMesh &mesh, const TemporalBasis &basis,
              SlabOperator<dim> &op, const GoalVectors &goal, const MarchOptions &options)
{
  const unsigned int N = mesh.n_slabs();
  std::vector<Vector<double>> Z(N);
  Vector<double> coupling(space.n_dofs()), first, rhs;
  for (unsigned int n = N; n-- > 0;)
  {
    guarded_slab_solve(
        options, "adjoint", n, mesh,
        [&]()
        {
          op.prepare(mesh.start(n), mesh.tau(n));
          slab_goal_rhs(goal, mesh, basis, n, rhs);
          if (n + 1 < N)
            add_kron_vector(1., basis.right_trace(), coupling, rhs);
          op.solve(rhs, Z[n], true);
          // M(t_{n-1})^T z(t_{n-1}^+): the coupling into slab n-1, computed while the
          // operator still holds slab n's jump mass.
          combine_blocks(Z[n], basis.left_trace(), first);
          op.jump_mass().Tvmult(coupling, first);
        },
        Z[n]);
  }
  return Z;
}

template std::vector<Vector<double>>
march_adjoint<2>(const Space<2> &, const TimeMesh &, const TemporalBasis &,
                 SlabOperator<2> &, const GoalVectors &, const MarchOptions &);
} // namespace anisodwr
