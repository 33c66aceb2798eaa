#include "solver/direct_solver.h"

#include "solver/mumps_solver.h"
#include "solver/umfpack_status.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace anisodwr
{
namespace
{
/// Throws with a first line for the console and the details below it (summary.json).
void check(const char *call, long status, std::size_t n, std::size_t nnz)
{
  umfpack::check(call, status,
                 "a matrix of " + std::to_string(n) + " rows and " + std::to_string(nnz) +
                     " stored entries");
}

using umfpack::megabytes;
} // namespace

DirectSolver::DirectSolver(unsigned int refinement_steps, DirectEngine engine)
    : mumps(engine == DirectEngine::mumps ? std::make_unique<MumpsSolver>(refinement_steps)
                                          : nullptr)
{
  static_assert(sizeof(control) / sizeof(double) == UMFPACK_CONTROL, "UMFPACK control size");
  umfpack_dl_defaults(control);
  control[UMFPACK_IRSTEP] = refinement_steps;
}

DirectSolver::~DirectSolver() { clear(); }

bool DirectSolver::factorized() const
{
  return mumps ? mumps->factorized() : numeric != nullptr;
}

void DirectSolver::clear()
{
  if (mumps)
    mumps->clear();
  if (numeric)
    umfpack_dl_free_numeric(&numeric);
  if (symbolic)
    umfpack_dl_free_symbolic(&symbolic);
  numeric = symbolic = nullptr;
  release_matrix();
  figures = DirectSolverInfo();
}

double DirectSolver::copy_mb() const
{
  return double(Ap.capacity() * sizeof(long) + Ai.capacity() * sizeof(long) +
                Ax.capacity() * sizeof(double)) /
         (1024. * 1024.);
}

void DirectSolver::release_matrix()
{
  std::vector<long>().swap(Ap);
  std::vector<long>().swap(Ai);
  std::vector<double>().swap(Ax);
}

const DirectSolverInfo &DirectSolver::analyze(const dealii::SparseMatrix<double> &A)
{
  clear();
  n_rows = A.m();
  if (mumps)
  {
    mumps->analyze(A, figures);
    return figures;
  }
  const auto n = A.m();
  Ap.assign(n + 1, 0);
  Ai.resize(A.n_nonzero_elements());
  Ax.resize(A.n_nonzero_elements());
  // Row-wise, column indices ascending (deal.II stores the diagonal first): UMFPACK
  // reads the rows as the columns of A^T.
  std::vector<std::pair<long, double>> row;
  for (dealii::types::global_dof_index i = 0; i < n; ++i)
  {
    row.clear();
    for (auto e = A.begin(i); e != A.end(i); ++e)
      row.emplace_back(long(e->column()), e->value());
    std::sort(row.begin(), row.end(),
              [](const auto &a, const auto &b) { return a.first < b.first; });
    const long start = Ap[i];
    for (std::size_t k = 0; k < row.size(); ++k)
    {
      Ai[start + k] = row[k].first;
      Ax[start + k] = row[k].second;
    }
    Ap[i + 1] = start + long(row.size());
  }
  double info[UMFPACK_INFO];
  meter.restart();
  check("umfpack_dl_symbolic",
        umfpack_dl_symbolic(long(n), long(n), Ap.data(), Ai.data(), Ax.data(), &symbolic,
                            control, info),
        n, Ax.size());
  figures.predicted_peak_mb = megabytes(info, UMFPACK_PEAK_MEMORY_ESTIMATE);
  figures.predicted_factor_mb = megabytes(info, UMFPACK_NUMERIC_SIZE_ESTIMATE);
  figures.heap_peak_mb = meter.peak_mb() + copy_mb();
  return figures;
}

void DirectSolver::factorize()
{
  if (mumps)
    return mumps->factorize(figures);
  if (!symbolic || Ap.empty())
    throw std::logic_error("DirectSolver::factorize before analyze");
  if (numeric)
    umfpack_dl_free_numeric(&numeric);
  double info[UMFPACK_INFO];
  meter.reset_peak();
  const long status =
      umfpack_dl_numeric(Ap.data(), Ai.data(), Ax.data(), symbolic, &numeric, control, info);
  if (status != UMFPACK_OK && numeric) // (a singular matrix still gets factors)
    umfpack_dl_free_numeric(&numeric);
  check("umfpack_dl_numeric", status, Ap.size() - 1, Ax.size());
  figures.peak_mb = megabytes(info, UMFPACK_PEAK_MEMORY);
  figures.factor_mb = megabytes(info, UMFPACK_NUMERIC_SIZE);
  figures.heap_peak_mb = std::max(figures.heap_peak_mb, meter.peak_mb() + copy_mb());
  figures.heap_held_mb = meter.held_mb();
  // Without iterative refinement the solves do not read A: its copy can go.
  if (control[UMFPACK_IRSTEP] == 0)
    release_matrix();
}

void DirectSolver::factorize(const dealii::SparseMatrix<double> &A)
{
  analyze(A);
  factorize();
}

void DirectSolver::solve(dealii::Vector<double> &x, bool transpose) const
{
  if (!factorized())
    throw std::logic_error("DirectSolver::solve before factorize");
  if (x.size() != n_rows)
    throw std::invalid_argument("DirectSolver::solve: vector of size " +
                                std::to_string(x.size()) + ", matrix of " +
                                std::to_string(n_rows) + " rows");
  if (mumps)
    return mumps->solve(x, transpose);
  const dealii::Vector<double> b(x);
  check("umfpack_dl_solve",
        umfpack_dl_solve(transpose ? UMFPACK_A : UMFPACK_At, Ap.data(), Ai.data(), Ax.data(),
                         x.begin(), b.begin(), numeric, control, nullptr),
        n_rows, Ax.size());
}
} // namespace anisodwr
