#include "base/blas_threads.h"

#include <dlfcn.h>

namespace anisodwr
{
int blas_threads()
{
  if (auto get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads")))
    return get();
  return 0;
}

void set_blas_threads(int n)
{
  if (auto set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
    set(n);
}

ScopedBlasThreads::ScopedBlasThreads(int n)
{
  if (n <= 0)
    return;
  before = blas_threads();
  if (before > 0)
    set_blas_threads(n);
}

ScopedBlasThreads::~ScopedBlasThreads()
{
  if (before > 0)
    set_blas_threads(before);
}
} // namespace anisodwr
