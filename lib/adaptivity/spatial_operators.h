#pragma once
// The cell-wise spatial operators of the estimator (doc/method.md §7), acting into the
// "weight element" W = FE_Q(w), w = max(q, 2p), on each active cell K:
//
//   R_i  (i < dim): replaces the dependence in direction i by its degree-p
//        interpolant at the degree-p Gauss-Lobatto points (other directions kept);
//        R_h = R_0 o ... o R_{dim-1}. Reference matrices on W, the same on every cell.
//   I_2h: patch lift of u (degree p) to degree 2p in every direction the patch
//        (K's parent, all children active) is cut in, degree p in the others.
//   I_2h,i: directional lift: degree 2p in direction i, degree p (K's own nodes) in
//        the others. The 1D patch along i is K plus one partner cell P:
//          1. K's sibling across its inner i-face, if K's parent is cut in i and the
//             sibling is active (the patch of doc/method.md §7);
//          2. otherwise K's face neighbour across its lower, then upper i-face, if that
//             face is not refined (the neighbour is as large as K or coarser);
//          3. otherwise there is no lift (I_2h,i u - u := 0 on K).
//        The 2p+1 nodes along i are K's p+1 nodes and P's p nodes beyond the shared
//        face, located through the cells' multilinear (MappingQ(1)) maps; on curved
//        patches a point up to 0.2 cell widths outside its nearest candidate is clamped.
//
// Lifts are returned as LocalMap: W-local coefficients = matrix * u(dofs).
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace anisodwr
{
struct LocalMap
{
  bool exists = false;
  std::vector<dealii::types::global_dof_index> dofs;
  dealii::FullMatrix<double> matrix;
  /// local = matrix * global(dofs * stride + offset) (stride r+1 and offset k pick
  /// temporal node k of an interleaved slab vector, time/slab_vector.h).
  void apply(const dealii::Vector<double> &global, dealii::Vector<double> &local,
             unsigned int stride = 1, unsigned int offset = 0) const;
};

template <int dim> class SpatialOperators
{
public:
  using cell_iterator = typename dealii::DoFHandler<dim>::active_cell_iterator;

  /// `dofs` is the primal DoFHandler (FE_Q(p)); W = FE_Q(weight_degree), weight_degree >=
  /// 2p.
  SpatialOperators(const dealii::DoFHandler<dim> &dofs, unsigned int weight_degree);

  const dealii::FE_Q<dim> &weight_element() const { return fe_w; }
  /// R_i (i < dim) or R_h (i == dim) on W-local coefficients.
  const dealii::FullMatrix<double> &restriction(unsigned int i) const { return R[i]; }
  /// Interpolation of cell-local coefficients of `fe` (degree <= W's) into W.
  dealii::FullMatrix<double>
  interpolation_from(const dealii::FiniteElement<dim> &fe) const;

  LocalMap directional_lift(const cell_iterator &cell, unsigned int direction) const;
  /// exists == false when K's parent is not a patch (K is level 0 or a sibling is
  /// refined).
  LocalMap patch_lift(const cell_iterator &cell) const;

  /// The partner cell of rule 1/2 above, or an invalid iterator (rule 3).
  cell_iterator partner(const cell_iterator &cell, unsigned int direction) const;

private:
  const dealii::DoFHandler<dim> &dofs;
  const unsigned int p;
  dealii::FE_Q<dim> fe_w;
  std::vector<double> gl; // degree-p Gauss-Lobatto nodes on [0,1]
  std::vector<dealii::FullMatrix<double>> R;

  /// K's nodes along one direction, extended by the other cell covering [lo, hi]
  /// (in K's unit coordinates) beyond the face at 0 or 1.
  std::vector<double> extended_nodes(double lo, double hi) const;
  LocalMap build(const cell_iterator &K, const std::vector<std::vector<double>> &nodes,
                 const std::vector<cell_iterator> &candidates) const;
};
} // namespace anisodwr
