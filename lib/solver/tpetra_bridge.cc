#include "solver/tpetra_bridge.h"

#include "time/slab_vector.h"

#include <Kokkos_Core.hpp>
#include <Teuchos_DefaultSerialComm.hpp>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

namespace anisodwr::tpetra
{
void ensure_kokkos()
{
  // Never finalized: Tpetra keeps static Kokkos buffers that are freed at exit.
  static const bool done = []
  {
    if (!Kokkos::is_initialized())
      Kokkos::initialize();
    return true;
  }();
  (void)done;
}

RCP<const Teuchos::Comm<int>> serial_comm()
{
  static const RCP<const Teuchos::Comm<int>> comm = rcp(new Teuchos::SerialComm<int>());
  return comm;
}

RCP<const Map> serial_map(std::size_t n)
{
  return rcp(new Map(static_cast<Tpetra::global_size_t>(n), 0, serial_comm()));
}

RCP<Matrix> to_tpetra(const RCP<const Map> &map, const dealii::SparseMatrix<double> &A,
                      double a, const dealii::SparseMatrix<double> *B, double b,
                      bool transpose)
{
  const std::size_t n = A.m();
  if (B && &B->get_sparsity_pattern() != &A.get_sparsity_pattern() &&
      B->n_nonzero_elements() != A.n_nonzero_elements())
    throw std::logic_error("to_tpetra: the two matrices do not share a pattern");
  Teuchos::ArrayRCP<std::size_t> ptr(n + 1, 0);
  const std::size_t nnz = A.n_nonzero_elements();
  Teuchos::ArrayRCP<LO> col(nnz);
  Teuchos::ArrayRCP<double> val(nnz);
  // Pass 1: row lengths of the result.
  for (std::size_t i = 0; i < n; ++i)
    for (auto it = A.begin(i); it != A.end(i); ++it)
      ++ptr[(transpose ? it->column() : i) + 1];
  std::partial_sum(ptr.begin(), ptr.end(), ptr.begin());
  std::vector<std::size_t> fill(ptr.begin(), ptr.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    auto itb = B ? B->begin(i) : A.begin(i);
    for (auto it = A.begin(i); it != A.end(i); ++it, ++itb)
    {
      const std::size_t j = it->column();
      const double v = a * it->value() + (B ? b * itb->value() : 0.);
      const std::size_t row = transpose ? j : i;
      col[fill[row]] = static_cast<LO>(transpose ? i : j);
      val[fill[row]++] = v;
    }
  }
  // Sort each row by column (deal.II stores the diagonal first).
  std::vector<std::pair<LO, double>> tmp;
  for (std::size_t i = 0; i < n; ++i)
  {
    tmp.clear();
    for (std::size_t q = ptr[i]; q < ptr[i + 1]; ++q)
      tmp.emplace_back(col[q], val[q]);
    std::sort(tmp.begin(), tmp.end(),
              [](const auto &x, const auto &y) { return x.first < y.first; });
    for (std::size_t q = ptr[i]; q < ptr[i + 1]; ++q)
    {
      col[q] = tmp[q - ptr[i]].first;
      val[q] = tmp[q - ptr[i]].second;
    }
  }
  auto M = rcp(new Matrix(map, map, ptr, col, val));
  M->fillComplete();
  return M;
}

RCP<Matrix> kron_block_tpetra(const RCP<const Map> &map,
                              const dealii::FullMatrix<double> &Tb,
                              const dealii::SparseMatrix<double> &S1,
                              const dealii::SparseMatrix<double> &S2, bool transpose)
{
  const unsigned int nb = Tb.m();
  if (nb == 1)
    return to_tpetra(map, S1, Tb(0, 0), &S2, 1., transpose);
  // Spatial CSR of S1 and S2 (transposed if asked), then expand each entry to a block.
  const RCP<const Map> smap = serial_map(S1.m());
  const auto A1 = to_tpetra(smap, S1, 1., nullptr, 0., transpose);
  const auto A2 = to_tpetra(smap, S2, 1., nullptr, 0., transpose);
  const std::size_t n = S1.m(), nnz = A1->getNodeNumEntries();
  const SlabLayout block{nb};
  Teuchos::ArrayRCP<std::size_t> ptr(n * nb + 1, 0);
  Teuchos::ArrayRCP<LO> col(nnz * nb * nb);
  Teuchos::ArrayRCP<double> val(nnz * nb * nb);
  std::size_t q = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    typename Matrix::local_inds_host_view_type c1, c2;
    typename Matrix::values_host_view_type v1, v2;
    A1->getLocalRowView(static_cast<LO>(i), c1, v1);
    A2->getLocalRowView(static_cast<LO>(i), c2, v2);
    for (unsigned int s = 0; s < nb; ++s)
    {
      for (std::size_t e = 0; e < c1.extent(0); ++e)
        for (unsigned int t = 0; t < nb; ++t)
        {
          col[q] = static_cast<LO>(block.index(c1(e), t));
          val[q++] = Tb(s, t) * v1(e) + (s == t ? v2(e) : 0.);
        }
      ptr[block.index(i, s) + 1] = q;
    }
  }
  auto M = rcp(new Matrix(map, map, ptr, col, val));
  M->fillComplete();
  return M;
}
} // namespace anisodwr::tpetra
