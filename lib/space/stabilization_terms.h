#pragma once
// The stabilization terms beside SUPG, as one table. Each adds an artificial diffusion
// (D_K grad u, grad v)_K on a cell K, D_K constant on K (doc/method.md §3). The assembly
// (Space::assemble_matrices) and the estimator's cell forms (the S(u) and S'(., z) parts
// of CellKernel) take the sum of the terms' D_K from Space::cell_diffusion, so that a new
// term is one entry in diffusion_terms(), its parameters in Stabilization
// (stabilization.h) and their entries in the key table.
#include "space/stabilization.h"

#include <deal.II/base/tensor.h>

#include <functional>
#include <string>
#include <vector>

namespace anisodwr
{
/// What a term sees of one cell.
struct StabilizationCell
{
  /// b at the cell's centre at t = 0 (the terms are one matrix per mesh)
  dealii::Tensor<1, 2> b;
  /// the diffusion coefficient eps
  double epsilon = 0.;
  /// the cell's length along a unit vector through its centre
  std::function<double(const dealii::Tensor<1, 2> &)> length_along;
  /// the cell's factor s_K in [0, 1] set from a previous solution
  /// (Space::set_crosswind_scale, crosswind_form = residual); 1 where none is set
  double switch_factor = 1.;
};

/// One stabilization term of the form (D_K grad u, grad v)_K.
struct DiffusionTerm
{
  std::string name;
  /// Whether the term is on with these parameters (off: no work on any cell).
  std::function<bool(const Stabilization &)> active;
  /// D_K on one cell (symmetric, positive semi-definite).
  std::function<dealii::Tensor<2, 2>(const Stabilization &, const StabilizationCell &)>
      diffusion;
};

/// Every term, in the order their D_K are summed.
const std::vector<DiffusionTerm> &diffusion_terms();
} // namespace anisodwr
