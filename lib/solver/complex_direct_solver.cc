#include "solver/complex_direct_solver.h"

#include "solver/umfpack_memory.h"
#include "solver/umfpack_status.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>

namespace anisodwr
{
namespace
{
void check(const char *call, long status, std::size_t n)
{
  umfpack::check(call, status, "a complex mode matrix of " + std::to_string(n) + " rows");
}

using umfpack::megabytes;
} // namespace

ComplexDirectSolver::ComplexDirectSolver(unsigned int refinement_steps)
{
  static_assert(sizeof(control) / sizeof(double) == UMFPACK_CONTROL,
                "UMFPACK control size");
  umfpack_zl_defaults(control);
  control[UMFPACK_IRSTEP] = refinement_steps;
}

ComplexDirectSolver::~ComplexDirectSolver()
{
  clear();
}

void ComplexDirectSolver::clear()
{
  if (numeric)
    umfpack_zl_free_numeric(&numeric);
  numeric = nullptr;
  std::vector<long>().swap(Ap);
  std::vector<long>().swap(Ai);
  std::vector<double>().swap(Ax);
  std::vector<double>().swap(Az);
  figures = DirectSolverInfo();
}

void ComplexDirectSolver::factorize(std::complex<double> z,
                                    const dealii::SparseMatrix<double> &S1,
                                    const dealii::SparseMatrix<double> &S2)
{
  clear();
  if (&S1.get_sparsity_pattern() != &S2.get_sparsity_pattern())
    throw std::invalid_argument("ComplexDirectSolver: S1 and S2 on different patterns");
  const auto n = S1.m();
  n_rows = n;
  const auto nnz = S1.n_nonzero_elements();
  Ap.assign(n + 1, 0);
  Ai.resize(nnz);
  Ax.resize(nnz);
  Az.resize(nnz);
  // Row-wise with ascending columns: UMFPACK reads the rows as the columns of C^T.
  std::vector<std::tuple<long, double, double>> row;
  for (dealii::types::global_dof_index i = 0; i < n; ++i)
  {
    row.clear();
    auto e2 = S2.begin(i);
    for (auto e1 = S1.begin(i); e1 != S1.end(i); ++e1, ++e2)
    {
      const double s1 = e1->value(), s2 = e2->value();
      row.emplace_back(long(e1->column()), z.real() * s1 + s2, z.imag() * s1);
    }
    std::sort(row.begin(), row.end(),
              [](const auto &a, const auto &b)
              { return std::get<0>(a) < std::get<0>(b); });
    const long start = Ap[i];
    for (std::size_t k = 0; k < row.size(); ++k)
      std::tie(Ai[start + k], Ax[start + k], Az[start + k]) = row[k];
    Ap[i + 1] = start + long(row.size());
  }
  double info[UMFPACK_INFO];
  void *symbolic = nullptr;
  umfpack::HeapMeter meter;
  check("umfpack_zl_symbolic",
        umfpack_zl_symbolic(long(n), long(n), Ap.data(), Ai.data(), Ax.data(), Az.data(),
                            &symbolic, control, info),
        n);
  figures.predicted_peak_mb = megabytes(info, UMFPACK_PEAK_MEMORY_ESTIMATE);
  figures.predicted_factor_mb = megabytes(info, UMFPACK_NUMERIC_SIZE_ESTIMATE);
  const double copy_mb =
      double(Ap.capacity() * sizeof(long) + Ai.capacity() * sizeof(long) +
             (Ax.capacity() + Az.capacity()) * sizeof(double)) /
      (1024. * 1024.);
  figures.heap_peak_mb = meter.peak_mb() + copy_mb;
  meter.reset_peak();
  const long status = umfpack_zl_numeric(Ap.data(), Ai.data(), Ax.data(), Az.data(),
                                         symbolic, &numeric, control, info);
  umfpack_zl_free_symbolic(&symbolic);
  if (status != UMFPACK_OK && numeric)
    umfpack_zl_free_numeric(&numeric);
  check("umfpack_zl_numeric", status, n);
  figures.peak_mb = megabytes(info, UMFPACK_PEAK_MEMORY);
  figures.factor_mb = megabytes(info, UMFPACK_NUMERIC_SIZE);
  figures.heap_peak_mb = std::max(figures.heap_peak_mb, meter.peak_mb() + copy_mb);
  figures.heap_held_mb = meter.held_mb();
  if (control[UMFPACK_IRSTEP] == 0)
  {
    // the solves do not read the matrix
    std::vector<long>().swap(Ap);
    std::vector<long>().swap(Ai);
    std::vector<double>().swap(Ax);
    std::vector<double>().swap(Az);
  }
}

void ComplexDirectSolver::solve(dealii::Vector<double> &re, dealii::Vector<double> &im,
                                bool transpose) const
{
  if (!numeric)
    throw std::logic_error("ComplexDirectSolver::solve before factorize");
  if (re.size() != n_rows || im.size() != n_rows)
    throw std::invalid_argument("ComplexDirectSolver::solve: vector size " +
                                std::to_string(re.size()) + ", matrix of " +
                                std::to_string(n_rows) + " rows");
  const dealii::Vector<double> bx(re), bz(im);
  // UMFPACK holds C^T: C x = b is its array transpose (UMFPACK_Aat, no conjugation).
  const long *ap = Ap.empty() ? nullptr : Ap.data(),
             *ai = Ai.empty() ? nullptr : Ai.data();
  const double *ax = Ax.empty() ? nullptr : Ax.data(),
               *az = Az.empty() ? nullptr : Az.data();
  check("umfpack_zl_solve",
        umfpack_zl_solve(transpose ? UMFPACK_A : UMFPACK_Aat, ap, ai, ax, az, re.begin(),
                         im.begin(), bx.begin(), bz.begin(), numeric, control, nullptr),
        n_rows);
}
} // namespace anisodwr
