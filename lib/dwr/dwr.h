#pragma once
// The adaptive DWR loop (doc/method.md §9): primal forward, adjoint backward in FE_Q(q),
// indicators, marking, refinement in space (per direction) and time; the per-loop
// table loops.csv / loops.tex written as each loop ends, summary.json, VTU.
#include "config/parameters.h"

namespace anisodwr
{
void run_dwr(const Parameters &prm);
} // namespace anisodwr
