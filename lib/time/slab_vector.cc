#include "time/slab_vector.h"

namespace anisodwr
{
using namespace dealii;

void extract_block(const Vector<double> &U, unsigned int k, unsigned int m,
                   Vector<double> &u)
{
  const SlabLayout slab{m};
  const auto n = U.size() / m;
  u.reinit(n);
  for (types::global_dof_index i = 0; i < n; ++i)
    u(i) = U(slab.index(i, k));
}

void insert_block(const Vector<double> &u, unsigned int k, unsigned int m,
                  Vector<double> &U)
{
  const SlabLayout slab{m};
  for (types::global_dof_index i = 0; i < u.size(); ++i)
    U(slab.index(i, k)) = u(i);
}

void add_kron_vector(double factor, const std::vector<double> &a, const Vector<double> &c,
                     Vector<double> &U)
{
  const SlabLayout slab{static_cast<unsigned int>(a.size())};
  const unsigned int m = slab.m;
  for (types::global_dof_index i = 0; i < c.size(); ++i)
    for (unsigned int k = 0; k < m; ++k)
      U(slab.index(i, k)) += factor * a[k] * c(i);
}

void combine_blocks(const Vector<double> &U, const std::vector<double> &c,
                    Vector<double> &u)
{
  const SlabLayout slab{static_cast<unsigned int>(c.size())};
  const unsigned int m = slab.m;
  const auto n = U.size() / m;
  u.reinit(n);
  for (types::global_dof_index i = 0; i < n; ++i)
  {
    double v = 0.;
    for (unsigned int k = 0; k < m; ++k)
      v += c[k] * U(slab.index(i, k));
    u(i) = v;
  }
}
} // namespace anisodwr
