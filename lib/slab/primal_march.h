#pragma once
// Forward march of the primal problem over all slabs (doc/method.md §2):
//   K_n U_n = F_n + (e y^T (x) M(t_{n-1})) U_{n-1},   at n = 1 the SUPG initial term.
#include "slab/slab_operator.h"
#include "time/time_mesh.h"

#include <functional>
#include <string>
#include <vector>

namespace anisodwr
{
struct MarchOptions
{
  std::string label = "run"; ///< names the loop/level in progress lines and errors
  bool progress = false;
  /// discretization.growth_limit: the primal march fails when a slab solution's largest
  /// coefficient exceeds growth_limit * data_bound (0 = no check)
  double growth_limit = 0;
};

/// Runs `solve` for slab n (0-based) of `mesh`; any exception becomes a NumericalError
/// naming options.label, `kind` (primal/adjoint), the slab and its time interval, and
/// so does a non-finite `result` afterwards, or one whose largest entry exceeds `bound`
/// (if bound > 0). Prints a progress line if asked.
void guarded_slab_solve(const MarchOptions &options, const std::string &kind,
                        unsigned int n, const TimeMesh &mesh,
                        const std::function<void()> &solve,
                        const dealii::Vector<double> &result, double bound = 0);

/// max(1, max|u_0| + max|g| + sum_n tau_n max|f(t_n + tau_n/2)|): the bound of the
/// maximum principle on |u|, with u_0 and f sampled on a 33 x 33 grid over the scene's
/// bounding box (points inside the domain) and g on the Dirichlet boundary's vertices
/// at the slab ends. A stable discretization stays within a modest factor of it
/// (SUPG's over- and undershoots); a blow-up exceeds it by orders of magnitude.
template <int dim> double data_bound(const Space<dim> &space, const TimeMesh &mesh);

/// Returns one interleaved coefficient vector per slab. Throws NumericalError naming
/// the label and slab on solver failure, non-finite values or (options.growth_limit >
/// 0) a slab solution larger than growth_limit * data_bound.
template <int dim>
std::vector<dealii::Vector<double>>
march_primal(const Space<dim> &space, const TimeMesh &mesh, const TemporalBasis &basis,
             SlabOperator<dim> &op, const MarchOptions &options);

/// march_primal by an operator that another thread prepared and keeps
/// (op.prepared_for(mesh)): its solves only (SlabOperator::solve_prepared), the operator
/// unchanged; the same results. Throws std::logic_error if op is not prepared for mesh.
template <int dim>
std::vector<dealii::Vector<double>>
march_primal_prepared(const Space<dim> &space, const TimeMesh &mesh,
                      const TemporalBasis &basis, const SlabOperator<dim> &op,
                      const MarchOptions &options);

/// Slab load F_n: int_{I_n} l_k (F(t)) dt by (r+2)-point Gauss quadrature, F(t) the
/// spatial load vector of Space::assemble_load.
template <int dim>
void assemble_slab_load(const Space<dim> &space, const TemporalBasis &basis, double t0,
                        double tau, dealii::Vector<double> &F);
} // namespace anisodwr
