#include "solver/mumps_solver.h"

#include "base/mpi.h"
#include "solver/direct_solver.h"

#include <dmumps_c.h>
#include <mpi.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace anisodwr
{
namespace
{
// MUMPS's 1-based control and information arrays
MUMPS_INT &icntl(DMUMPS_STRUC_C &id, int k) { return id.icntl[k - 1]; }
MUMPS_INT infog(const DMUMPS_STRUC_C &id, int k) { return id.infog[k - 1]; }

/// MUMPS's sizes in entries: negative values count millions.
double entries(MUMPS_INT v) { return v >= 0 ? double(v) : -1e6 * double(v); }

const char *phase_name(int job)
{
  switch (job)
  {
  case 1:
    return "analysis";
  case 2:
    return "factorization";
  case 3:
    return "solve";
  default:
    return "call";
  }
}
} // namespace

struct MumpsSolver::Instance
{
  DMUMPS_STRUC_C id{};
  std::vector<MUMPS_INT> irn, jcn;
  std::vector<double> a;
  bool initialized = false;

  /// Runs `job`; on too little work space (INFOG(1) = -8, -9, -11, -14, -17, -20) the
  /// factorization is retried with ICNTL(14) doubled, up to 3 times.
  void run(int job)
  {
    id.job = job;
    dmumps_c(&id);
    for (int retry = 0; retry < 3 && job == 2; ++retry)
    {
      const int e = infog(id, 1);
      if (e != -8 && e != -9 && e != -11 && e != -14 && e != -17 && e != -20)
        break;
      icntl(id, 14) *= 2;
      dmumps_c(&id);
    }
    const int e = infog(id, 1);
    if (e >= 0)
      return;
    std::string what = e == -10 ? ": the matrix is singular"
                                : " failed with INFOG(1) = " + std::to_string(e);
    throw std::runtime_error(std::string("MUMPS: ") + phase_name(job) + what +
                             "\nMUMPS INFOG(1) = " + std::to_string(e) +
                             ", INFOG(2) = " + std::to_string(infog(id, 2)) +
                             " for a matrix of " + std::to_string(id.n) + " rows");
  }
};

MumpsSolver::MumpsSolver(unsigned int refinement_steps) : refinement_steps(refinement_steps)
{
}

MumpsSolver::~MumpsSolver() { clear(); }

void MumpsSolver::clear()
{
  if (mumps && mumps->initialized)
  {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized)
    {
      mumps->id.job = -2;
      dmumps_c(&mumps->id);
    }
  }
  mumps.reset();
  have_factors = false;
}

void MumpsSolver::analyze(const dealii::SparseMatrix<double> &A, DirectSolverInfo &info)
{
  clear();
  ensure_mpi();
  if (A.m() >= std::size_t(std::numeric_limits<MUMPS_INT>::max()))
    throw std::runtime_error("MUMPS: " + std::to_string(A.m()) +
                             " rows exceed its 32-bit indices");
  mumps = std::make_unique<Instance>();
  auto &id = mumps->id;
  id.comm_fortran = MUMPS_INT(MPI_Comm_c2f(MPI_COMM_WORLD));
  id.par = 1; // the host works too
  id.sym = 0;
  mumps->run(-1);
  mumps->initialized = true;
  icntl(id, 1) = icntl(id, 2) = icntl(id, 3) = -1; // no output
  icntl(id, 4) = 0;
  icntl(id, 18) = 3; // each rank gives its own entries
  icntl(id, 10) = -int(refinement_steps);
  // this rank's contiguous block of rows
  const std::size_t n_rows = A.m(), ranks = mpi_ranks(), rank = mpi_rank(),
                    i0 = n_rows * rank / ranks, i1 = n_rows * (rank + 1) / ranks;
  std::size_t nnz = 0;
  for (std::size_t i = i0; i < i1; ++i)
    nnz += A.get_row_length(i);
  mumps->irn.reserve(nnz);
  mumps->jcn.reserve(nnz);
  mumps->a.reserve(nnz);
  for (std::size_t i = i0; i < i1; ++i)
    for (auto e = A.begin(i); e != A.end(i); ++e)
    {
      mumps->irn.push_back(MUMPS_INT(i + 1));
      mumps->jcn.push_back(MUMPS_INT(e->column() + 1));
      mumps->a.push_back(e->value());
    }
  id.n = MUMPS_INT(n_rows);
  id.nnz_loc = MUMPS_INT8(nnz);
  id.irn_loc = mumps->irn.data();
  id.jcn_loc = mumps->jcn.data();
  id.a_loc = mumps->a.data();
  mumps->run(1);
  // INFOG(17): MB over all ranks (in core); INFOG(3): factor entries
  info.predicted_peak_mb = infog(id, 17);
  info.predicted_factor_mb = entries(infog(id, 3)) * sizeof(double) / (1024. * 1024.);
}

void MumpsSolver::factorize(DirectSolverInfo &info)
{
  if (!mumps)
    throw std::logic_error("MumpsSolver::factorize before analyze");
  mumps->run(2);
  have_factors = true;
  const auto &id = mumps->id;
  info.peak_mb = infog(id, 19); // MB allocated by the factorization, over all ranks
  info.factor_mb = (entries(infog(id, 9)) * sizeof(double) +
                    entries(infog(id, 10)) * sizeof(MUMPS_INT)) /
                   (1024. * 1024.);
  if (refinement_steps == 0)
  {
    // the solves do not read A
    std::vector<MUMPS_INT>().swap(mumps->irn);
    std::vector<MUMPS_INT>().swap(mumps->jcn);
    std::vector<double>().swap(mumps->a);
  }
}

void MumpsSolver::solve(dealii::Vector<double> &x, bool transpose) const
{
  auto &id = mumps->id;
  icntl(id, 9) = transpose ? 0 : 1; // 1: A x = b, otherwise A^T x = b
  icntl(id, 20) = 0;                // dense right-hand side on the host
  icntl(id, 21) = 0;                // solution on the host, in place
  id.nrhs = 1;
  id.lrhs = id.n;
  id.rhs = mpi_rank() == 0 ? x.begin() : nullptr;
  mumps->run(3);
  if (mpi_ranks() > 1)
    MPI_Bcast(x.begin(), int(x.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}
} // namespace anisodwr
