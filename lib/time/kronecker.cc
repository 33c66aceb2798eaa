#include "time/kronecker.h"

#include <deal.II/lac/lapack_templates.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace anisodwr
{
using namespace dealii;

void make_kron_sparsity(const SparsityPattern &spatial, unsigned int m, SparsityPattern &out)
{
  const auto n = spatial.n_rows();
  const SlabLayout slab{m};
  std::vector<unsigned int> lengths(n * m);
  for (types::global_dof_index i = 0; i < n; ++i)
    for (unsigned int k = 0; k < m; ++k)
      lengths[slab.index(i, k)] = spatial.row_length(i) * m;
  out.reinit(n * m, n * m, lengths);
  std::vector<types::global_dof_index> cols;
  for (types::global_dof_index i = 0; i < n; ++i)
  {
    cols.clear();
    for (auto it = spatial.begin(i); it != spatial.end(i); ++it)
      for (unsigned int l = 0; l < m; ++l)
        cols.push_back(slab.index(it->column(), l));
    std::sort(cols.begin(), cols.end());
    for (unsigned int k = 0; k < m; ++k)
      out.add_entries(slab.index(i, k), cols.begin(), cols.end(), true);
  }
  out.compress();
}

namespace
{
/// The spatial pattern all terms' S share; throws (naming `who`) if there are no terms
/// or they do not share one.
const SparsityPattern &shared_pattern(const std::vector<KronTerm> &terms, const char *who)
{
  if (terms.empty())
    throw std::logic_error(std::string(who) + ": no terms");
  const SparsityPattern &pattern = terms[0].S->get_sparsity_pattern();
  for (const auto &t : terms)
    if (&t.S->get_sparsity_pattern() != &pattern)
      throw std::logic_error(std::string(who) + ": spatial matrices must share one pattern");
  return pattern;
}
} // namespace

void assemble_kron(const std::vector<KronTerm> &terms, const SparsityPattern &pattern,
                   SparseMatrix<double> &K)
{
  const SparsityPattern &spatial = shared_pattern(terms, "assemble_kron");
  const unsigned int m = terms[0].T.m();
  const SlabLayout slab{m};
  K.reinit(pattern);
  const auto n = spatial.n_rows();
  std::vector<types::global_dof_index> scols, kcols, order;
  std::vector<double> svals, kvals;
  for (types::global_dof_index i = 0; i < n; ++i)
  {
    const unsigned int len = spatial.row_length(i);
    scols.resize(len);
    svals.assign(len * terms.size(), 0.);
    for (unsigned int p = 0; p < len; ++p)
      scols[p] = spatial.column_number(i, p);
    for (unsigned int t = 0; t < terms.size(); ++t)
    {
      unsigned int p = 0;
      for (auto it = terms[t].S->begin(i); it != terms[t].S->end(i); ++it, ++p)
        svals[t * len + p] = it->value();
    }
    order.resize(len);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](auto a, auto b) { return scols[a] < scols[b]; });
    kcols.resize(len * m);
    kvals.resize(len * m);
    for (unsigned int k = 0; k < m; ++k)
    {
      unsigned int c = 0;
      for (const auto p : order)
        for (unsigned int l = 0; l < m; ++l, ++c)
        {
          kcols[c] = slab.index(scols[p], l);
          double v = 0.;
          for (unsigned int t = 0; t < terms.size(); ++t)
            v += terms[t].T(k, l) * svals[t * len + p];
          kvals[c] = v;
        }
      K.add(slab.index(i, k), c, kcols.data(), kvals.data(), false, true);
    }
  }
}

void KronBlocks::reinit(const std::vector<KronTerm> &terms)
{
  const SparsityPattern &pattern = shared_pattern(terms, "KronBlocks");
  n = pattern.n_rows();
  m = terms[0].T.m();
  rowstart.assign(n + 1, 0);
  cols.resize(pattern.n_nonzero_elements());
  for (std::size_t i = 0; i < n; ++i)
  {
    rowstart[i + 1] = rowstart[i] + pattern.row_length(i);
    for (unsigned int p = 0; p < pattern.row_length(i); ++p)
      cols[rowstart[i] + p] = pattern.column_number(i, p);
  }
  // blocks = S T: S holds each spatial entry's values in the terms (one row per entry,
  // gathered with the terms' rows walked side by side), T each term's temporal matrix
  // as a row; formed chunk by chunk by BLAS (gemm) straight into the blocks
  const std::size_t mm = std::size_t(m) * m, nt = terms.size();
  std::vector<double> T(nt * mm);
  for (std::size_t t = 0; t < nt; ++t)
    for (unsigned int k = 0; k < m; ++k)
      for (unsigned int l = 0; l < m; ++l)
        T[t * mm + k * m + l] = terms[t].T(k, l);
  blocks.resize(cols.size() * mm);
  constexpr std::size_t chunk = 512;
  std::vector<double> S(chunk * nt);
  std::size_t first = 0, filled = 0; // the chunk's first entry, its entries gathered
  const auto flush = [&]()
  {
    // column-major view: blocks^T (mm x filled) = T^T (mm x nt) S^T (nt x filled)
    const types::blas_int rows = static_cast<types::blas_int>(mm),
                          columns = static_cast<types::blas_int>(filled),
                          inner = static_cast<types::blas_int>(nt);
    const double one = 1., zero = 0.;
    if (filled > 0)
      gemm("N", "N", &rows, &columns, &inner, &one, T.data(), &rows, S.data(), &inner,
           &zero, blocks.data() + first * mm, &rows);
    first += filled;
    filled = 0;
  };
  std::vector<SparseMatrix<double>::const_iterator> row;
  for (std::size_t i = 0; i < n; ++i)
  {
    row.clear();
    for (const auto &t : terms)
      row.push_back(t.S->begin(i));
    for (std::size_t q = rowstart[i]; q < rowstart[i + 1]; ++q)
    {
      double *s_q = S.data() + filled * nt;
      for (std::size_t t = 0; t < nt; ++t)
      {
        s_q[t] = row[t]->value();
        ++row[t];
      }
      if (++filled == chunk)
        flush();
    }
  }
  flush();
}

namespace
{
/// dst = K src (or K^T src) from the blocks, for a block size known at compile time
/// (M > 0) or not (M = 0).
template <bool transpose, unsigned int M>
void block_product(std::size_t n, unsigned int m_run, const std::size_t *rowstart,
                   const types::global_dof_index *cols, const double *blocks,
                   double *__restrict dst, const double *__restrict src)
{
  const unsigned int m = M ? M : m_run;
  const std::size_t mm = std::size_t(m) * m;
  std::fill(dst, dst + n * m, 0.);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t q = rowstart[i]; q < rowstart[i + 1]; ++q)
    {
      const std::size_t j = cols[q];
      const double *b = blocks + q * mm;
      if (transpose) // block (i, j) of K is block (j, i) of K^T, transposed
        for (unsigned int k = 0; k < m; ++k)
          for (unsigned int l = 0; l < m; ++l)
            dst[j * m + l] += b[k * m + l] * src[i * m + k];
      else
        for (unsigned int k = 0; k < m; ++k)
          for (unsigned int l = 0; l < m; ++l)
            dst[i * m + k] += b[k * m + l] * src[j * m + l];
    }
}

template <bool transpose>
void block_product(std::size_t n, unsigned int m, const std::size_t *rowstart,
                   const types::global_dof_index *cols, const double *blocks, double *dst,
                   const double *src)
{
  switch (m)
  {
    case 1: return block_product<transpose, 1>(n, m, rowstart, cols, blocks, dst, src);
    case 2: return block_product<transpose, 2>(n, m, rowstart, cols, blocks, dst, src);
    case 3: return block_product<transpose, 3>(n, m, rowstart, cols, blocks, dst, src);
    case 4: return block_product<transpose, 4>(n, m, rowstart, cols, blocks, dst, src);
    default: return block_product<transpose, 0>(n, m, rowstart, cols, blocks, dst, src);
  }
}
} // namespace

void KronBlocks::vmult(double *dst, const double *src) const
{
  block_product<false>(n, m, rowstart.data(), cols.data(), blocks.data(), dst, src);
}

void KronBlocks::Tvmult(double *dst, const double *src) const
{
  block_product<true>(n, m, rowstart.data(), cols.data(), blocks.data(), dst, src);
}

void vmult_kron(const std::vector<KronTerm> &terms, const Vector<double> &src,
                Vector<double> &dst, bool transpose)
{
  const unsigned int m = terms.at(0).T.m();
  const auto n = terms[0].S->m();
  const SlabLayout slab{m};
  dst.reinit(n * m);
  Vector<double> x(n), y(n), u(n);
  std::vector<Vector<double>> Sy(m, Vector<double>(n));
  for (const auto &t : terms)
  {
    for (unsigned int l = 0; l < m; ++l)
    {
      extract_block(src, l, m, x);
      if (transpose)
        t.S->Tvmult(Sy[l], x);
      else
        t.S->vmult(Sy[l], x);
    }
    for (unsigned int k = 0; k < m; ++k)
    {
      u = 0.;
      for (unsigned int l = 0; l < m; ++l)
      {
        const double c = transpose ? t.T(l, k) : t.T(k, l);
        if (c != 0.)
          u.add(c, Sy[l]);
      }
      for (types::global_dof_index i = 0; i < n; ++i)
        dst(slab.index(i, k)) += u(i);
    }
  }
}
} // namespace anisodwr
