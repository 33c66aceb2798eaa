#pragma once
// UMFPACK's status codes and Info figures, shared by the real (direct_solver.cc) and the
// complex (complex_direct_solver.cc) sparse LU (internal to lib/solver/).
#include <umfpack.h>

#include <stdexcept>
#include <string>

namespace anisodwr::umfpack
{
/// Throws unless status is UMFPACK_OK: a first line for the console, the details below
/// it (summary.json). `matrix` says which matrix ("a matrix of n rows and ...").
inline void check(const char *call, long status, const std::string &matrix)
{
  if (status == UMFPACK_OK)
    return;
  const std::string what = status == UMFPACK_WARNING_singular_matrix
                               ? ": the matrix is singular"
                               : " failed with status " + std::to_string(status);
  throw std::runtime_error(std::string("UMFPACK: ") + call + what + "\nUMFPACK status " +
                           std::to_string(status) + " for " + matrix);
}

/// An Info entry given in units (UMFPACK_SIZE_OF_UNIT bytes) in MB.
inline double megabytes(const double *info, int entry)
{
  return info[entry] * info[UMFPACK_SIZE_OF_UNIT] / (1024. * 1024.);
}
} // namespace anisodwr::umfpack
