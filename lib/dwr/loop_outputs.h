#pragma once
// The per-loop outputs of u_h(T) in a DWR run: probes, cut lines and the VTU.
#include "adaptivity/estimator.h"
#include "config/parameters.h"
#include "io/loop_report.h"
#include "scene/scene.h"
#include "space/space.h"
#include "dwr/probes.h"

#include <deal.II/lac/vector.h>

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace anisodwr
{
/// Probes of u(T) into row (row.probes, u_min, u_max), the cut lines of probe_spec to
/// cut_<line>_loop-NNNN.csv, and in every output.vtu_loops-th loop and the last (`last`:
/// the loop cap, the tolerance or the wall-time budget stops after it) the VTU of u(T)
/// with the indicators and aspect ratios per cell (record added to vtu_records,
/// loops.pvd rewritten).
void write_loop_outputs(const Parameters &prm, const Scene<2> &scene,
                        const ProbeSpec<2> &probe_spec, LoopRow &row, const Space<2> &primal,
                        const dealii::Vector<double> &uT, const Indicators<2> &ind,
                        const std::vector<double> &ar_cell, bool last,
                        std::vector<std::pair<double, std::string>> &vtu_records);

/// The uncertainties of goal.reference, one per goal (empty without references).
std::vector<double> reference_uncertainties(const std::vector<GoalSpec> &goals);
/// The goals' names.
std::vector<std::string> goal_names(const std::vector<GoalSpec> &goals);
/// The columns of probes.csv: loop, sizes, J per goal and the probes.
std::vector<std::string> probe_columns(const std::vector<GoalSpec> &goals);

/// The loop table's copy of the estimator's sums.
void copy_indicators(const Indicators<2> &ind, LoopRow &row);

/// One goal's own estimate and its signed parts into row (eta_<goal>, eta_hx_<goal>, ...).
void add_goal_estimate(LoopRow &row, const Indicators<2> &goal_ind);

/// The first line of a DWR run on `out`: scene, degrees (adjoint degree q), adaptivity
/// mode and the goals, each with its exact value (has_exact; J_exact per goal) and its
/// reference uncertainty if goal.reference gave one; the cells' MappingQ degree if
/// above 1.
void print_run_line(std::ostream &out, const Parameters &prm, const Scene<2> &scene,
                    unsigned int q, const std::vector<GoalSpec> &goals,
                    const std::vector<double> &J_exact, bool has_exact,
                    unsigned int mapping_degree);
} // namespace anisodwr
