#include "base/mpi.h"

#include "base/errors.h"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace anisodwr
{
namespace
{
bool mpi_active()
{
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}

void finalize_mpi()
{
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized)
    MPI_Finalize();
}
} // namespace

unsigned int mpi_ranks()
{
  int n = 1;
  if (mpi_active())
    MPI_Comm_size(MPI_COMM_WORLD, &n);
  return unsigned(n);
}

unsigned int mpi_rank()
{
  int r = 0;
  if (mpi_active())
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return unsigned(r);
}

unsigned int mpi_ranks_on_this_machine()
{
  if (!mpi_active())
    return 1;
  MPI_Comm local;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
  int n = 1;
  MPI_Comm_size(local, &n);
  MPI_Comm_free(&local);
  return unsigned(n);
}

void ensure_mpi()
{
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized)
    return;
  MPI_Init(nullptr, nullptr);
  std::atexit(finalize_mpi);
}

void on_output_rank(const std::function<void()> &write)
{
  if (mpi_ranks() == 1)
    return write();
  int failed = 0;
  if (writes_output())
  {
    try
    {
      write();
    }
    catch (...)
    {
      failed = 1;
      MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
      throw;
    }
  }
  MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (failed)
    throw OutputError("writing the output failed on rank 0");
}

double mpi_max(double x)
{
  if (mpi_ranks() > 1)
    MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return x;
}

void allreduce_sum(std::vector<double> &x)
{
  if (mpi_ranks() == 1)
    return;
  // in pieces of at most INT_MAX entries (MPI counts are int)
  const std::size_t piece = std::numeric_limits<int>::max();
  for (std::size_t i = 0; i < x.size(); i += piece)
    MPI_Allreduce(MPI_IN_PLACE, x.data() + i, int(std::min(piece, x.size() - i)), MPI_DOUBLE,
                  MPI_SUM, MPI_COMM_WORLD);
}
} // namespace anisodwr
