#pragma once
// The cell vectors of goals with a density (internal to lib/goal/): j(phi_l) =
// int density phi_l dx by iterated Gauss rules on sub-cells of each cell: summed by
// factors on MappingQ(1) cells with FE_Q, otherwise through FEValues (one per sub-cell
// count, built once).
#include "goal/goal_type.h"

#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>

#include <array>
#include <map>
#include <memory>

namespace anisodwr
{
/// The largest quadrature rule of a goal on one cell whose FEValues are built at once
/// (and cached per sub-cell count); larger ones are evaluated in slices.
constexpr unsigned int max_rule_points = 4096;

/// A goal int density(x) u(x) dx. A kind says which cells it meets, its density, the
/// sub-cells of a cell and, where an iterated rule is not the best one, a rule of its
/// own (clipped to the support, or exact on a box).
template <int dim> class DensityGoalPart : public GoalPart<dim>
{
public:
  using CellIterator = typename dealii::Triangulation<dim>::active_cell_iterator;
  using SubCells = std::array<unsigned int, dim>;
  using Rule = std::array<dealii::Quadrature<1>, dim>;

  DensityGoalPart(const dealii::Mapping<dim> &mapping, const dealii::FiniteElement<dim> &fe);
  bool add_cell_vector(const CellIterator &cell, double weight,
                       dealii::Vector<double> &j) const override;

  /// The longest edge of `cell` along unit direction d (vertices v and v + 2^d).
  static double edge_length(const CellIterator &cell, unsigned int d);
  /// The tensor product of q0 (index running fastest) and q1, built point by point:
  /// deal.II's tensor-product constructor asserts (Debug) that the weights sum to 1,
  /// which a clipped rule or a slice of a rule does not.
  static dealii::Quadrature<dim> tensor_rule(const dealii::Quadrature<1> &q0,
                                             const dealii::Quadrature<1> &q1);
  /// The Gauss rule of base_points() points mapped to [lo, hi].
  dealii::Quadrature<1> gauss_on(double lo, double hi) const;
  /// Points of the 1D Gauss rule on a sub-cell: fe.degree + 2 (exact for a density that
  /// is a polynomial of degree <= fe.degree + 3 on the sub-cell), or more for a kind
  /// whose density is smooth but not polynomial.
  virtual unsigned int base_points() const { return fe.degree + 2; }

protected:
  virtual bool meets(const CellIterator &cell) const = 0;
  virtual double density(const dealii::Point<dim> &x) const = 0;
  /// Sub-cells along each unit direction of `cell`; `capped` tells whether a cap kept
  /// them coarser than the density wants.
  virtual SubCells sub_cells(const CellIterator &cell, bool &capped) const = 0;
  /// A rule of the kind's own for `cell` with sub-cells n: true with the 1D rules per
  /// direction in `rule`, or with `empty` set where the support misses the cell; false
  /// where the iterated Gauss rule on the sub-cells is to be used.
  virtual bool own_rule(const CellIterator &cell, const SubCells &n, bool capped,
                        Rule &rule, bool &empty) const = 0;

  const dealii::Mapping<dim> &mapping;
  const dealii::FiniteElement<dim> &fe;

private:
  dealii::FEValues<dim> &fe_values(const SubCells &n) const;
  /// j += weight int density phi_l over the tensor rule q0 x q1 (unit coordinates) by
  /// sum factorization: the bilinear map of the cell's vertices and the FE's 1D
  /// Lagrange factors, without an FEValues. Only where `tensor` (MappingQ(1), FE_Q).
  bool add_tensor(const CellIterator &cell, const dealii::Quadrature<1> &q0,
                  const dealii::Quadrature<1> &q1, double weight,
                  dealii::Vector<double> &j) const;
  /// FE_Q's shape functions as products of 1D Lagrange polynomials (lexicographic
  /// index a + (k+1) b -> the FE's index lex_to_fe), usable where the mapping is bilinear
  bool tensor = false;
  std::vector<dealii::Polynomials::Polynomial<double>> basis_1d;
  std::vector<unsigned int> lex_to_fe;
  /// FEValues on iterated Gauss rules, one per number of sub-cells (built on demand)
  mutable std::map<SubCells, std::unique_ptr<dealii::FEValues<dim>>> values;
};
} // namespace anisodwr
