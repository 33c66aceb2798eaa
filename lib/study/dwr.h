#pragma once
// The adaptive DWR loop (SPEC §6): primal forward, adjoint backward in FE_Q(q),
// indicators, marking, refinement in space (per direction) and time; the per-loop
// table loops.csv / loops.tex written as each loop ends, summary.json, VTU.
#include "config/parameters.h"
#include "goal/goal_spec.h"
#include "scene/scene.h"

#include <vector>

namespace anisodwr
{
/// The goals of a run from the [goal] section (InputError naming the key on bad input).
std::vector<GoalSpec> make_goals(const Parameters &prm, const Scene<2> &scene);

void run_dwr(const Parameters &prm);
} // namespace anisodwr
