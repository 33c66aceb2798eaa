#pragma once
// VTU snapshots of a spatial finite element function and the PVD time series.
#include "space/space.h"

#include <string>
#include <utility>
#include <vector>

namespace anisodwr
{
/// Named per-cell values (indicators, aspect ratio), one entry per active cell.
using CellData = std::vector<std::pair<std::string, dealii::Vector<double>>>;

/// Writes dir/<name>-<index>.vtu with the field "u", "u_exact" when known and the
/// given cell data, and dir/<name>-<index>.cells.csv (per cell: vertices, u at them,
/// the cell data) for the chart script; returns the VTU file name relative to dir.
template <int dim>
std::string write_vtu(const Space<dim> &space, const dealii::Vector<double> &u, double t,
                      const std::string &dir, const std::string &name, unsigned int index,
                      const CellData &cell_data = {});

/// Writes dir/<name>.pvd listing (time, file) pairs (ParaView opens it).
void write_pvd(const std::string &dir, const std::string &name,
               const std::vector<std::pair<double, std::string>> &records);
} // namespace anisodwr
