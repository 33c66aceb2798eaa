// The table of stabilization terms beside SUPG (stabilization_terms.h).
#include "space/stabilization_terms.h"

#include <algorithm>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// Crosswind diffusion (Stabilization::crosswind0): eps_cw,K (P grad u, P grad v) with P
/// = a a^T the projection on the unit vector a across b, eps_cw,K = s_K crosswind0
/// max(0, |b| h_cw,K / 2 - eps), h_cw,K the cell's length along a. Not consistent: the
/// scheme's error gains O(eps_cw) where it acts; the estimator counts it in S(u).
Tensor<2, 2> crosswind(const Stabilization &stab, const StabilizationCell &cell)
{
  const double nb = cell.b.norm();
  if (nb == 0. || cell.switch_factor == 0.)
    return {};
  Tensor<1, 2> across;
  across[0] = -cell.b[1] / nb;
  across[1] = cell.b[0] / nb;
  const double eps_cw = cell.switch_factor * stab.crosswind0 *
                        std::max(0., 0.5 * nb * cell.length_along(across) - cell.epsilon);
  return eps_cw * outer_product(across, across);
}
} // namespace

const std::vector<DiffusionTerm> &diffusion_terms()
{
  static const std::vector<DiffusionTerm> terms{
      {"crosswind", [](const Stabilization &s) { return s.crosswind0 > 0.; }, crosswind},
  };
  return terms;
}
} // namespace anisodwr
