#include "solver/umfpack_memory.h"

#include <SuiteSparse_config.h>
#include <malloc.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>

namespace anisodwr::umfpack
{
namespace
{
// Bytes this thread has allocated through SuiteSparse minus the bytes it freed, and the
// largest value since the last HeapMeter (re)start in this thread. (Memory freed by
// another thread than its allocator's lowers that thread's count: a meter reads
// differences within one thread, which a factorization is.)
thread_local double live = 0, peak = 0;

void grow(void *p)
{
  if (!p)
    return;
  live += double(malloc_usable_size(p));
  peak = std::max(peak, live);
}
void shrink(void *p)
{
  if (p)
    live -= double(malloc_usable_size(p));
}

void *counted_malloc(std::size_t n)
{
  void *p = std::malloc(n);
  grow(p);
  return p;
}
void *counted_calloc(std::size_t n, std::size_t size)
{
  void *p = std::calloc(n, size);
  grow(p);
  return p;
}
void *counted_realloc(void *old, std::size_t n)
{
  const double before = old ? double(malloc_usable_size(old)) : 0.;
  void *p = std::realloc(old, n);
  if (p || n == 0)
  {
    live -= before;
    grow(p);
  }
  return p;
}
void counted_free(void *p)
{
  shrink(p);
  std::free(p);
}

void install()
{
  static std::once_flag once;
  std::call_once(once,
                 []()
                 {
                   SuiteSparse_config.malloc_func = counted_malloc;
                   SuiteSparse_config.calloc_func = counted_calloc;
                   SuiteSparse_config.realloc_func = counted_realloc;
                   SuiteSparse_config.free_func = counted_free;
                 });
}
constexpr double MB = 1024. * 1024.;
} // namespace

HeapMeter::HeapMeter()
{
  restart();
}

void HeapMeter::restart()
{
  install();
  start = peak = live;
}

void HeapMeter::reset_peak()
{
  peak = live;
}

double HeapMeter::peak_mb() const
{
  return (peak - start) / MB;
}

double HeapMeter::held_mb() const
{
  return (live - start) / MB;
}
} // namespace anisodwr::umfpack
