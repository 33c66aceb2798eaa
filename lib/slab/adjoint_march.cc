#include "slab/adjoint_march.h"

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/numerics/matrix_tools.h>

namespace anisodwr
{
using namespace dealii;

template <int dim>
std::vector<std::vector<Vector<double>>>
march_adjoints(const Space<dim> &space, const TimeMesh &mesh, const TemporalBasis &basis,
               SlabOperator<dim> &op, const std::vector<GoalVectors> &goals,
               const MarchOptions &options)
{
  const unsigned int N = mesh.n_slabs();
  const std::size_t G = goals.size();
  std::vector<std::vector<Vector<double>>> Z(G, std::vector<Vector<double>>(N));
  std::vector<Vector<double>> coupling(G, Vector<double>(space.n_dofs())), rhs(G);
  std::vector<const Vector<double> *> loads(G);
  std::vector<Vector<double> *> results(G);
  Vector<double> first;
  for (unsigned int n = N; n-- > 0;)
  {
    for (std::size_t g = 0; g < G; ++g)
    {
      loads[g] = &rhs[g];
      results[g] = &Z[g][n];
    }
    guarded_slab_solve(
        options, "adjoint", n, mesh,
        [&]()
        {
          op.prepare(mesh.start(n), mesh.tau(n));
          for (std::size_t g = 0; g < G; ++g)
          {
            slab_goal_rhs(goals[g], mesh, basis, n, rhs[g]);
            if (n + 1 < N)
              add_kron_vector(1., basis.right_trace(), coupling[g], rhs[g]);
          }
          op.solve_transposed(loads, results);
          // M(t_{n-1})^T z(t_{n-1}^+): the coupling into slab n-1, computed while the
          // operator still holds slab n's jump mass.
          for (std::size_t g = 0; g < G; ++g)
          {
            combine_blocks(Z[g][n], basis.left_trace(), first);
            op.jump_mass().Tvmult(coupling[g], first);
          }
        },
        Z[0][n]);
    for (std::size_t g = 1; g < G; ++g) // (their non-finite check)
      guarded_slab_solve(options, "adjoint", n, mesh, []() {}, Z[g][n]);
  }
  return Z;
}

template <int dim>
std::vector<Vector<double>>
march_adjoint(const Space<dim> &space, const TimeMesh &mesh, const TemporalBasis &basis,
              SlabOperator<dim> &op, const GoalVectors &goal, const MarchOptions &options)
{
  return std::move(march_adjoints(space, mesh, basis, op, {goal}, options).front());
}

template <int dim>
Vector<double> end_time_representer(const Space<dim> &adjoint,
                                    const std::vector<GoalSpec> &goals)
{
  GoalVectors gv = assemble_goal_vectors(adjoint, goals);
  SparseMatrix<double> M(adjoint.sparsity());
  MatrixCreator::create_mass_matrix(
      adjoint.mapping(), adjoint.dof_handler(), QGauss<dim>(adjoint.degree() + 1), M,
      (const Function<dim> *)nullptr, adjoint.constraints());
  adjoint.constraints().condense(gv.at_end);
  for (unsigned int i = 0; i < M.m(); ++i)
    if (adjoint.constraints().is_constrained(i))
      M.set(i, i, 1.);
  SparseDirectUMFPACK lu;
  lu.initialize(M);
  Vector<double> zT = gv.at_end;
  lu.solve(zT);
  adjoint.constraints().distribute(zT);
  return zT;
}

template Vector<double> end_time_representer<2>(const Space<2> &,
                                                const std::vector<GoalSpec> &);
template std::vector<std::vector<Vector<double>>>
march_adjoints<2>(const Space<2> &, const TimeMesh &, const TemporalBasis &, SlabOperator<2> &,
                  const std::vector<GoalVectors> &, const MarchOptions &);
template std::vector<Vector<double>>
march_adjoint<2>(const Space<2> &, const TimeMesh &, const TemporalBasis &,
                 SlabOperator<2> &, const GoalVectors &, const MarchOptions &);
} // namespace anisodwr
