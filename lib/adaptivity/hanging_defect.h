#pragma once
// The hanging-node defect of the estimator's spatial interpolant (doc/method.md §7).
//
// R_h z interpolates z cell by cell at the primal's nodes. On a cell with a hanging
// node this is not the conforming interpolant I_h z of the primal space V_h: at a
// hanging node x_c, R_h z takes z(x_c) while I_h z takes sum_m c_cm z(x_m), the
// hanging-node constraint's combination of its masters. R_h z is then discontinuous
// across the coarse face, and the identity J(e) = rho(u)(z - z_h) + S(u)(z_h) + D(z_h),
// which holds for z_h in V_h only, fails with z_h = R_h z by rho(u)(R_h z) - S(u)(R_h z)
// - D(R_h z): a residual weighed against an O(h^2 z'') function on the cells along
// every hanging face, the same order as those cells' own indicators.
//
// The defect delta_c = z(x_c) - sum_m c_cm z(x_m) per constrained DoF c and temporal
// node gives I_h z = R_h z - sum_c delta_c phi_c on every cell. Its part of eta_h,
// rho(u)(delta_c phi_c) on a fine cell along the hanging face, stays on that cell in the
// direction along the face (the direction in which the masters lie). Charging it to the
// coarse cell across the face instead (which marking would then cut, removing the
// hanging node) was measured worse: the moving hump's J error 1.5-2x larger at the same
// N_space on loops 9-12 (config/moving_hump.json).
#include "space/space.h"

#include <deal.II/lac/vector.h>

#include <utility>
#include <vector>

namespace anisodwr
{
template <int dim> class HangingDefect
{
public:
  /// Z: the adjoint's slab vectors (interleaved, n_nodes temporal nodes per DoF) on
  /// `adjoint`, a space on the primal's mesh.
  HangingDefect(const Space<dim> &primal, const Space<dim> &adjoint,
                const std::vector<dealii::Vector<double>> &Z, unsigned int n_nodes);
  /// No defects: the cell-wise interpolant R_h z everywhere
  /// (adaptivity.conforming_weights = false).
  explicit HangingDefect(unsigned int n_nodes) : n_nodes(n_nodes) {}

  /// The cell's constrained DoFs: pairs (local index, slot); empty without hanging nodes.
  void cell_slots(const std::vector<dealii::types::global_dof_index> &primal_dofs,
                  std::vector<std::pair<unsigned int, unsigned int>> &slots) const;
  /// delta_c of a slot at temporal node k of slab n.
  double value(unsigned int n, unsigned int slot, unsigned int k) const
  {
    return defect[n][slot * n_nodes + k];
  }
  /// The direction a slot's defect is charged to.
  unsigned int direction(unsigned int slot) const { return directions[slot]; }
  /// The number of constrained DoFs.
  unsigned int n_slots() const { return directions.size(); }

private:
  const unsigned int n_nodes;
  /// per primal DoF: its slot, or none
  std::vector<unsigned int> slot_of;
  std::vector<unsigned char> directions;
  /// per slab: delta at slot * n_nodes + k
  std::vector<std::vector<double>> defect;
};
} // namespace anisodwr
