#pragma once
// The interleaved space-time vector layout of one slab: the m = r+1 temporal
// coefficients of spatial DoF i are neighbours, global index i*m + k. A slab matrix in
// this layout is a point-block matrix with m x m blocks.
#include <deal.II/lac/vector.h>

#include <cstddef>
#include <vector>

namespace anisodwr
{
/// Index arithmetic of the interleaved layout with m temporal coefficients per DoF.
struct SlabLayout
{
  unsigned int m = 1; ///< temporal coefficients per spatial DoF (r+1)

  /// Global index of temporal coefficient k of spatial DoF i.
  constexpr std::size_t index(std::size_t i, unsigned int k) const { return i * m + k; }
  /// Global index of spatial DoF i's last temporal coefficient (k = m-1).
  constexpr std::size_t last(std::size_t i) const { return index(i, m - 1); }
};

/// Temporal coefficient k of an interleaved slab vector with m coefficients per DoF.
void extract_block(const dealii::Vector<double> &U, unsigned int k, unsigned int m,
                   dealii::Vector<double> &u);
void insert_block(const dealii::Vector<double> &u, unsigned int k, unsigned int m,
                  dealii::Vector<double> &U);
/// U += factor * (a (x) c): adds factor * a_k * c to temporal block k of U.
void add_kron_vector(double factor, const std::vector<double> &a,
                     const dealii::Vector<double> &c, dealii::Vector<double> &U);
/// sum_k c_k U_k: e.g. the value u(t) = sum_k l_k(s) U_k.
void combine_blocks(const dealii::Vector<double> &U, const std::vector<double> &c,
                    dealii::Vector<double> &u);
} // namespace anisodwr
