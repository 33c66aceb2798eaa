#pragma once
// Runs of the program: one primal solve (study.mode = single) or a convergence
// study under uniform refinement in h, tau or both (study.mode = convergence).
#include "config/parameters.h"

#include <string>

namespace anisodwr
{
/// Runs what the parameters ask for and writes every output to
/// prm.output.directory. Throws InputError / NumericalError; files written before a
/// failure stay on disk (tables are flushed row by row, summary.json records the error).
void run_study(const Parameters &prm);
} // namespace anisodwr
