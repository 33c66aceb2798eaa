#pragma once
// The heap UMFPACK really uses (internal to lib/solver/). UMFPACK's Info figures miss
// part of it: on moving_hump's slab matrices the measured heap peak of a mode
// factorization exceeds UMFPACK_PEAK_MEMORY plus the solver's copy of the matrix by
// 20-60 bytes per stored entry (doc/results.md, "Memory estimate"). SuiteSparse's
// allocator is routed through per-thread counters, so that a factorization measures
// the growth of its own thread's SuiteSparse heap; the factorizations of the primal
// and the adjoint march in two threads do not mix.

namespace anisodwr::umfpack
{
/// Started before an analysis or factorization, read after it: the largest growth of
/// this thread's SuiteSparse heap since the start and the growth still held (MB).
class HeapMeter
{
public:
  HeapMeter();
  void restart();
  /// The peak from now on (the start stays).
  void reset_peak();
  double peak_mb() const;
  double held_mb() const;

private:
  double start = 0;
};
} // namespace anisodwr::umfpack
