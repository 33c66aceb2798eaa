#include "time/kronecker.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

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

void assemble_kron(const std::vector<KronTerm> &terms, const SparsityPattern &pattern,
                   SparseMatrix<double> &K)
{
  if (terms.empty())
    throw std::logic_error("assemble_kron: no terms");
  const SparsityPattern &spatial = terms[0].S->get_sparsity_pattern();
  for (const auto &t : terms)
    if (&t.S->get_sparsity_pattern() != &spatial)
      throw std::logic_error("assemble_kron: spatial matrices must share one pattern");
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
  if (terms.empty())
    throw std::logic_error("KronBlocks: no terms");
  const SparsityPattern &pattern = terms[0].S->get_sparsity_pattern();
  for (const auto &t : terms)
    if (&t.S->get_sparsity_pattern() != &pattern)
      throw std::logic_error("KronBlocks: spatial matrices must share one pattern");
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
  const std::size_t mm = std::size_t(m) * m;
  blocks.assign(cols.size() * mm, 0.);
  std::vector<double> T(mm);
  for (const auto &t : terms)
  {
    for (unsigned int k = 0; k < m; ++k)
      for (unsigned int l = 0; l < m; ++l)
        T[k * m + l] = t.T(k, l);
    for (std::size_t i = 0; i < n; ++i)
    {
      std::size_t q = rowstart[i];
      for (auto it = t.S->begin(i); it != t.S->end(i); ++it, ++q)
      {
        const double s = it->value();
        double *b = blocks.data() + q * mm;
        for (std::size_t e = 0; e < mm; ++e)
          b[e] += T[e] * s;
      }
    }
  }
}

namespace
{
/// The block products for a block size known at compile time (M > 0) or not (M = 0).
template <unsigned int M>
void block_vmult(std::size_t n, unsigned int m_run, const std::size_t *rowstart,
                 const types::global_dof_index *cols, const double *blocks, double *dst,
                 const double *src)
{
  const unsigned int m = M ? M : m_run;
  const std::size_t mm = std::size_t(m) * m;
  for (std::size_t i = 0; i < n; ++i)
  {
    double *y = dst + i * m;
    for (unsigned int k = 0; k < m; ++k)
      y[k] = 0.;
    for (std::size_t q = rowstart[i]; q < rowstart[i + 1]; ++q)
    {
      const double *x = src + std::size_t(cols[q]) * m, *b = blocks + q * mm;
      for (unsigned int k = 0; k < m; ++k)
        for (unsigned int l = 0; l < m; ++l)
          y[k] += b[k * m + l] * x[l];
    }
  }
}

template <unsigned int M>
void block_Tvmult(std::size_t n, unsigned int m_run, const std::size_t *rowstart,
                  const types::global_dof_index *cols, const double *blocks, double *dst,
                  const double *src)
{
  const unsigned int m = M ? M : m_run;
  const std::size_t mm = std::size_t(m) * m;
  std::fill(dst, dst + n * m, 0.);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double *x = src + i * m;
    for (std::size_t q = rowstart[i]; q < rowstart[i + 1]; ++q)
    {
      double *y = dst + std::size_t(cols[q]) * m;
      const double *b = blocks + q * mm;
      for (unsigned int k = 0; k < m; ++k)
        for (unsigned int l = 0; l < m; ++l)
          y[l] += b[k * m + l] * x[k];
    }
  }
}

} // namespace

void KronBlocks::vmult(double *dst, const double *src) const
{
  const auto run = [&](auto kernel)
  { kernel(n, m, rowstart.data(), cols.data(), blocks.data(), dst, src); };
  switch (m)
  {
    case 1: run(block_vmult<1>); break;
    case 2: run(block_vmult<2>); break;
    case 3: run(block_vmult<3>); break;
    case 4: run(block_vmult<4>); break;
    default: run(block_vmult<0>);
  }
}

void KronBlocks::Tvmult(double *dst, const double *src) const
{
  const auto run = [&](auto kernel)
  { kernel(n, m, rowstart.data(), cols.data(), blocks.data(), dst, src); };
  switch (m)
  {
    case 1: run(block_Tvmult<1>); break;
    case 2: run(block_Tvmult<2>); break;
    case 3: run(block_Tvmult<3>); break;
    case 4: run(block_Tvmult<4>); break;
    default: run(block_Tvmult<0>);
  }
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
