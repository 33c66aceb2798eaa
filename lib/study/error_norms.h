#pragma once
// Error norms of a space-time solution against the scene's exact solution.
#include "space/space.h"
#include "time/temporal_basis.h"
#include "time/time_mesh.h"

#include <vector>

namespace anisodwr
{
struct ErrorNorms
{
  double L2_T = 0;  ///< ||u(T) - u_h(T^-)||_L2
  double nodal = 0; ///< max_n ||u(t_n) - u_h(t_n^-)||_L2
  double L2L2 = 0;  ///< (int_I ||u - u_h||^2 dt)^(1/2), (r+2)-point Gauss in time
};

template <int dim>
ErrorNorms compute_errors(const Space<dim> &space, const TimeMesh &mesh,
                          const TemporalBasis &basis, const std::vector<dealii::Vector<double>> &U);
} // namespace anisodwr
