#include "solver/mode_solver.h"

#include <algorithm>
#include <stdexcept>

namespace anisodwr
{
ModeDirectSolver::ModeDirectSolver(unsigned int refinement_steps)
    : refinement_steps(refinement_steps)
{
}

ModeDirectSolver::~ModeDirectSolver() = default;

void ModeDirectSolver::clear()
{
  real_lu.clear();
  complex_lu.clear();
  S1 = nullptr;
  form = TemporalSchur();
  factors_mb = peak = 0;
  figures = ModeLuFigures();
}

void ModeDirectSolver::factorize(const KronSplit &k)
{
  clear();
  if (!k.S1 || !k.S2)
    throw std::logic_error("ModeDirectSolver::factorize without spatial matrices");
  form = TemporalSchur(k.T1, k.T2);
  RT.reinit(form.m, form.m);
  form.T2inv.Tmmult(RT, form.Q); // T2^{-T} Q
  real_lu.resize(form.blocks.size());
  complex_lu.resize(form.blocks.size());
  for (std::size_t b = 0; b < form.blocks.size(); ++b)
  {
    const ModeBlock &blk = form.blocks[b];
    double mode_peak = 0, mode_factor = 0;
    if (blk.size == 1)
    {
      dealii::SparseMatrix<double> A(k.S1->get_sparsity_pattern());
      A.copy_from(*k.S1);
      A *= blk.shift;
      A.add(1., *k.S2);
      auto lu = std::make_unique<DirectSolver>(refinement_steps);
      lu->analyze(A);
      if (refinement_steps == 0)
        A.clear(); // UMFPACK has its copy
      lu->factorize();
      mode_peak = lu->info().peak_mb;
      mode_factor = lu->info().factor_mb;
      figures.real_factor_mb = std::max(figures.real_factor_mb, lu->info().heap_held_mb);
      figures.real_peak_mb = std::max(figures.real_peak_mb, lu->info().heap_peak_mb);
      real_lu[b] = std::move(lu);
    }
    else
    {
      auto lu = std::make_unique<ComplexDirectSolver>(refinement_steps);
      lu->factorize({blk.alpha, blk.beta}, *k.S1, *k.S2);
      mode_peak = lu->info().peak_mb;
      mode_factor = lu->info().factor_mb;
      figures.complex_factor_mb = std::max(figures.complex_factor_mb, lu->info().heap_held_mb);
      figures.complex_peak_mb = std::max(figures.complex_peak_mb, lu->info().heap_peak_mb);
      complex_lu[b] = std::move(lu);
    }
    peak = std::max(peak, factors_mb + mode_peak);
    factors_mb += mode_factor;
  }
  S1 = k.S1;
}

void ModeDirectSolver::solve_block(std::size_t b, std::vector<dealii::Vector<double>> &y,
                                   bool transpose) const
{
  const ModeBlock &blk = form.blocks[b];
  const unsigned int j = blk.first;
  if (blk.size == 1)
  {
    real_lu[b]->solve(y[j], transpose);
    return;
  }
  // ((alpha + i beta) S1 + S2) (y1 + i zz) = r1 + i rho r2, y2 = sigma zz; transposed:
  // the transposed complex matrix, r1 - i r2 / rho, y2 = -rho zz
  // (solver/temporal_schur.h).
  dealii::Vector<double> &y1 = y[j], &y2 = y[j + 1];
  y2 *= transpose ? -1. / blk.rho : blk.rho;
  complex_lu[b]->solve(y1, y2, transpose);
  y2 *= transpose ? -blk.rho : blk.sigma;
}

void ModeDirectSolver::solve(dealii::Vector<double> &x, bool transpose) const
{
  if (!factorized())
    throw std::logic_error("ModeDirectSolver::solve before factorize");
  const unsigned int m = form.m;
  const std::size_t n = S1->m();
  if (x.size() != n * m)
    throw std::invalid_argument("ModeDirectSolver::solve: vector of the wrong size");
  std::vector<dealii::Vector<double>> y(m, dealii::Vector<double>(n)), z(m);
  std::vector<double *> yp(m);
  for (unsigned int k = 0; k < m; ++k)
    yp[k] = y[k].begin();
  const auto &T = form.T;
  const std::size_t nb = form.blocks.size();
  if (!transpose)
  {
    // y = (Q^T T2^{-1} (x) I) x; (T (x) S1 + I (x) S2) y' = y backward over the blocks
    gather_modes(form.P, x.begin(), n, yp);
    for (std::size_t bb = nb; bb-- > 0;)
    {
      const ModeBlock &blk = form.blocks[bb];
      const unsigned int j0 = blk.first, j1 = blk.first + blk.size;
      for (unsigned int j = j0; j < j1; ++j)
        for (unsigned int l = j1; l < m; ++l)
          if (T(j, l) != 0.)
            y[j].add(-T(j, l), z[l]);
      solve_block(bb, y, false);
      if (j0 > 0)
        for (unsigned int j = j0; j < j1; ++j)
        {
          z[j].reinit(n);
          S1->vmult(z[j], y[j]);
        }
    }
  }
  else
  {
    // y = (Q^T (x) I) x; (T^T (x) S1^T + I (x) S2^T) y' = y forward over the blocks
    dealii::FullMatrix<double> Qt(m, m);
    Qt.copy_transposed(form.Q);
    gather_modes(Qt, x.begin(), n, yp);
    for (std::size_t bb = 0; bb < nb; ++bb)
    {
      const ModeBlock &blk = form.blocks[bb];
      const unsigned int j0 = blk.first, j1 = blk.first + blk.size;
      for (unsigned int j = j0; j < j1; ++j)
        for (unsigned int l = 0; l < j0; ++l)
          if (T(l, j) != 0.)
            y[j].add(-T(l, j), z[l]);
      solve_block(bb, y, true);
      if (j1 < m)
        for (unsigned int j = j0; j < j1; ++j)
        {
          z[j].reinit(n);
          S1->Tvmult(z[j], y[j]);
        }
    }
  }
  std::vector<const double *> yc(y.size());
  for (unsigned int k = 0; k < m; ++k)
    yc[k] = y[k].begin();
  scatter_modes(transpose ? RT : form.Q, yc, n, x.begin());
}
} // namespace anisodwr
