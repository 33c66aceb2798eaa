#include "slab/slab_operator.h"

#include <deal.II/base/timer.h>

#include <cmath>

namespace anisodwr
{
using namespace dealii;

template <int dim>
SlabOperator<dim>::SlabOperator(const Space<dim> &space, const TemporalBasis &basis,
                                bool reuse_factorization)
    : space(space), basis(basis), reuse(reuse_factorization)
{
  make_kron_sparsity(space.sparsity(), basis.n_dofs(), pattern);
}

template <int dim>
void SlabOperator<dim>::prepare(double t_start, double tau_n)
{
  const bool constant = !space.scene.coefficients_depend_on_time();
  // Equal slab lengths computed as differences of t_n differ in the last bits.
  const bool same_tau = std::abs(tau_n - tau) <= 1e-12 * tau_n;
  if (constant && reuse && factorized && same_tau)
  {
    t0 = t_start;
    return;
  }
  Timer timer;
  const unsigned int m = basis.n_dofs();
  terms_full.clear();
  terms_cond.clear();
  if (constant)
  {
    if (mats.empty())
    {
      mats.resize(1);
      space.assemble_matrices(0., mats[0]);
    }
    FullMatrix<double> tM(basis.mass());
    tM *= tau_n;
    terms_full = {{basis.derivative_with_jump(), &mats[0].M}, {tM, &mats[0].A}};
    terms_cond = {{basis.derivative_with_jump(), &mats[0].Mc}, {tM, &mats[0].Ac}};
    jump_M = &mats[0].M;
  }
  else
  {
    // r+2 Gauss points integrate polynomial-in-t coefficients of degree <= 2 exactly.
    std::vector<double> sq, wq;
    gauss_rule(m + 1, sq, wq);
    mats.resize(sq.size() + 1);
    for (unsigned int q = 0; q < sq.size(); ++q)
    {
      space.assemble_matrices(t_start + sq[q] * tau_n, mats[q]);
      std::vector<double> l = basis.values(sq[q]), dl(m);
      for (unsigned int k = 0; k < m; ++k)
        dl[k] = basis.derivative(k, sq[q]);
      FullMatrix<double> Tm = outer(l, dl), Ta = outer(l, l);
      Tm *= wq[q];
      Ta *= wq[q] * tau_n;
      terms_full.push_back({Tm, &mats[q].M});
      terms_full.push_back({Ta, &mats[q].A});
      terms_cond.push_back({Tm, &mats[q].Mc});
      terms_cond.push_back({Ta, &mats[q].Ac});
    }
    auto &mj = mats.back();
    space.assemble_matrices(t_start, mj);
    const FullMatrix<double> Tj = outer(basis.left_trace(), basis.left_trace());
    terms_full.push_back({Tj, &mj.M});
    terms_cond.push_back({Tj, &mj.Mc});
    jump_M = &mj.M;
  }
  time.assemble_spatial += timer.wall_time();
  timer.restart();
  assemble_kron(terms_cond, pattern, K);
  time.assemble_slab += timer.wall_time();
  timer.restart();
  lu.factorize(K);
  time.factorize += timer.wall_time();
  ++time.n_factorizations;
  factorized = true;
  t0 = t_start;
  tau = tau_n;
}

template <int dim>
void SlabOperator<dim>::solve(const Vector<double> &load, Vector<double> &U, bool transpose)
{
  Timer timer;
  const unsigned int m = basis.n_dofs();
  const auto n = space.n_dofs();
  Vector<double> rhs(load), block(n);
  std::vector<AffineConstraints<double>> node_constraints(m);
  if (!transpose)
  {
    // Dirichlet lift g (values at constrained DoFs only): rhs -= K_full g.
    Vector<double> g(n * m), Kg;
    for (unsigned int k = 0; k < m; ++k)
    {
      space.make_dirichlet_constraints(t0 + basis.nodes()[k] * tau, node_constraints[k]);
      block = 0.;
      node_constraints[k].distribute(block);
      insert_block(block, k, m, g);
    }
    vmult_kron(terms_full, g, Kg);
    rhs -= Kg;
  }
  // C^T applied to each temporal block.
  for (unsigned int k = 0; k < m; ++k)
  {
    extract_block(rhs, k, m, block);
    space.constraints().condense(block);
    insert_block(block, k, m, rhs);
  }
  lu.solve(rhs, transpose);
  U = rhs;
  for (unsigned int k = 0; k < m; ++k)
  {
    extract_block(U, k, m, block);
    if (transpose)
      space.constraints().distribute(block);
    else
      node_constraints[k].distribute(block);
    insert_block(block, k, m, U);
  }
  time.solve += timer.wall_time();
  ++time.n_solves;
}

template class SlabOperator<2>;
} // namespace anisodwr
