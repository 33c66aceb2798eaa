#include "solver/temporal_schur.h"

#include "time/slab_vector.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

extern "C" void dgees_(const char *jobvs, const char *sort,
                       int (*select)(double *, double *), const int *n, double *a,
                       const int *lda, int *sdim, double *wr, double *wi, double *vs,
                       const int *ldvs, double *work, const int *lwork, int *bwork,
                       int *info);

namespace anisodwr
{
TemporalSchur::TemporalSchur(const dealii::FullMatrix<double> &T1,
                             const dealii::FullMatrix<double> &T2, bool transpose)
    : m(T1.m())
{
  const int mi = static_cast<int>(m);
  dealii::FullMatrix<double> A1(m, m), A2(m, m), G(m, m);
  for (unsigned int i = 0; i < m; ++i)
    for (unsigned int j = 0; j < m; ++j)
    {
      A1(i, j) = transpose ? T1(j, i) : T1(i, j);
      A2(i, j) = transpose ? T2(j, i) : T2(i, j);
    }
  T2inv.reinit(m, m);
  T2inv.invert(A2);
  T2inv.mmult(G, A1);
  // Real Schur form (LAPACK, column major): orthogonal Q, no eigenvector conditioning.
  std::vector<double> a(m * m), vs(m * m), wr(m), wi(m), work(8 * m + 16);
  for (unsigned int i = 0; i < m; ++i)
    for (unsigned int j = 0; j < m; ++j)
      a[i + j * m] = G(i, j);
  int sdim = 0, info = 0, lwork = static_cast<int>(work.size());
  std::vector<int> bwork(m);
  dgees_("V", "N", nullptr, &mi, a.data(), &mi, &sdim, wr.data(), wi.data(), vs.data(),
         &mi, work.data(), &lwork, bwork.data(), &info);
  if (info != 0)
    throw std::runtime_error("temporal Schur form: dgees failed, info = " +
                             std::to_string(info));
  T.reinit(m, m);
  Q.reinit(m, m);
  for (unsigned int i = 0; i < m; ++i)
    for (unsigned int j = 0; j < m; ++j)
    {
      T(i, j) = a[i + j * m];
      Q(i, j) = vs[i + j * m];
    }
  P.reinit(m, m);
  Q.Tmmult(P, T2inv); // P = Q^T T2^{-1}

  for (unsigned int j = 0; j < m;)
  {
    ModeBlock blk;
    blk.first = j;
    if (j + 1 < m && T(j + 1, j) != 0.)
    {
      // LAPACK's standardized 2x2 block [[a, b], [c, a]], b c < 0
      blk.size = 2;
      blk.alpha = 0.5 * (T(j, j) + T(j + 1, j + 1));
      const double b = T(j, j + 1), c = T(j + 1, j);
      blk.beta = std::sqrt(std::max(0., -b * c));
      blk.sigma = -blk.beta / b;
      blk.rho = blk.beta / c;
      blk.shift = blk.alpha + blk.beta;
    }
    else
    {
      blk.size = 1;
      blk.shift = T(j, j);
    }
    blocks.push_back(blk);
    j += blk.size;
  }
}

unsigned int TemporalSchur::n_real() const
{
  return static_cast<unsigned int>(std::count_if(
      blocks.begin(), blocks.end(), [](const ModeBlock &b) { return b.size == 1; }));
}

unsigned int TemporalSchur::n_complex_pairs() const
{
  return static_cast<unsigned int>(blocks.size()) - n_real();
}

namespace
{
/// sum_l A(k, l) v(l)
template <class V> double row_product(const dealii::FullMatrix<double> &A, unsigned int k, V v)
{
  double s = 0;
  for (unsigned int l = 0; l < A.n(); ++l)
    s += A(k, l) * v(l);
  return s;
}
} // namespace

void gather_modes(const dealii::FullMatrix<double> &A, const double *x, std::size_t n,
                  const std::vector<double *> &y)
{
  const SlabLayout slab{static_cast<unsigned int>(A.m())};
  for (std::size_t i = 0; i < n; ++i)
    for (unsigned int k = 0; k < slab.m; ++k)
      y[k][i] = row_product(A, k, [&](unsigned int l) { return x[slab.index(i, l)]; });
}

void scatter_modes(const dealii::FullMatrix<double> &A,
                   const std::vector<const double *> &y, std::size_t n, double *out,
                   double alpha, double beta)
{
  const SlabLayout slab{static_cast<unsigned int>(A.m())};
  for (std::size_t i = 0; i < n; ++i)
    for (unsigned int k = 0; k < slab.m; ++k)
    {
      const double s = row_product(A, k, [&](unsigned int l) { return y[l][i]; });
      double &o = out[slab.index(i, k)];
      o = (beta == 0. ? 0. : beta * o) + alpha * s;
    }
}
} // namespace anisodwr
