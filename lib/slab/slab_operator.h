#pragma once
// The slab operator K_n of SPEC §2 as a Kronecker sum, for one space and one dG(r)
// basis, with its condensed (constrained) form factorized by UMFPACK.
//
//   K_n = sum_q w_q [ l(s_q) l'(s_q)^T (x) M(t_q) + tau l(s_q) l(s_q)^T (x) A(t_q) ]
//         + e e^T (x) M(t_{n-1})
// reduces to D (x) M + tau Mhat (x) A when b and alpha do not depend on t; the
// spatial matrices are then assembled once per mesh and the factorization is
// reused while tau does not change.
#include <deal.II/lac/sparse_direct.h>

#include "slab/kronecker.h"
#include "space/space.h"
#include "time/temporal_basis.h"

#include <memory>

namespace anisodwr
{
struct SlabTimings
{
  double assemble_spatial = 0, assemble_slab = 0, factorize = 0, solve = 0;
  unsigned int n_factorizations = 0, n_solves = 0;
};

template <int dim>
class SlabOperator
{
public:
  SlabOperator(const Space<dim> &space, const TemporalBasis &basis, bool reuse_factorization);

  /// Prepares K_n for the slab (t0, t0 + tau]: assembles spatial matrices if needed,
  /// builds the condensed slab matrix and factorizes, unless the previous
  /// factorization can be reused.
  void prepare(double t0, double tau);

  /// Unconstrained Kronecker terms of K_n (for tests and for the Dirichlet lift).
  const std::vector<KronTerm> &full_terms() const { return terms_full; }
  /// M(t_{n-1}) (unconstrained): the mass matrix of the jump term.
  const dealii::SparseMatrix<double> &jump_mass() const { return *jump_M; }

  /// Solves K_n U = load with the Dirichlet values u_D(t0 + s_k tau) at the temporal
  /// nodes and the hanging-node constraints. `load` and U are interleaved full vectors.
  /// If `transpose`, solves K_n^T U = load with homogeneous constraints (adjoint).
  void solve(const dealii::Vector<double> &load, dealii::Vector<double> &U,
             bool transpose = false);

  const SlabTimings &timings() const { return time; }
  dealii::types::global_dof_index n_slab_dofs() const { return space.n_dofs() * basis.n_dofs(); }

private:
  const Space<dim> &space;
  const TemporalBasis &basis;
  bool reuse;

  std::vector<SpatialMatrices> mats; // one per temporal quadrature point (+ jump), or one
  std::vector<KronTerm> terms_full, terms_cond;
  const dealii::SparseMatrix<double> *jump_M = nullptr;
  dealii::SparsityPattern pattern;
  dealii::SparseMatrix<double> K;
  dealii::SparseDirectUMFPACK lu;
  bool factorized = false;
  double t0 = 0, tau = -1;
  SlabTimings time;
};
} // namespace anisodwr
