#pragma once
// The thread count of the BLAS under UMFPACK and MUMPS when it is OpenBLAS (found at
// run time through dlsym: Debian's deal.II links libblas.so.3, which OpenBLAS provides
// through update-alternatives; with another BLAS these calls do nothing).

namespace anisodwr
{
/// OpenBLAS's thread count, 0 if the BLAS in use is not OpenBLAS.
int blas_threads();
/// Sets OpenBLAS's thread count (process-wide; nothing without OpenBLAS).
void set_blas_threads(int n);

/// OpenBLAS on n threads for the lifetime of this object, then back to the count
/// before; n = 0 changes nothing. Two marches running on the two cores use it: OpenBLAS's
/// own threads would compete with the other march (and spin-wait between calls).
class ScopedBlasThreads
{
public:
  explicit ScopedBlasThreads(int n);
  ~ScopedBlasThreads();
  ScopedBlasThreads(const ScopedBlasThreads &) = delete;
  ScopedBlasThreads &operator=(const ScopedBlasThreads &) = delete;

private:
  int before = 0;
};
} // namespace anisodwr
