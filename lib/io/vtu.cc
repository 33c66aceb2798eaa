#include "io/vtu.h"

#include "base/mpi.h"
#include "io/table.h"

#include <deal.II/base/function.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <fstream>
#include <iomanip>
#include <sstream>

namespace anisodwr
{
using namespace dealii;


namespace
{
/// One row per active cell: the vertices in counter-clockwise order (0, 1, 3, 2), u at
/// them, and the cell data: enough for postprocess/charts.py to draw the mesh.
template <int dim>
void write_cells_csv(const Space<dim> &space, const Vector<double> &u,
                     const CellData &cell_data, const std::string &path)
{
  static_assert(dim == 2, "cells.csv is written for 2D meshes");
  std::ostringstream f;
  f << std::setprecision(10) << "x0,y0,x1,y1,x2,y2,x3,y3,u0,u1,u2,u3";
  for (const auto &entry : cell_data)
    f << "," << entry.first;
  f << "\n";
  const unsigned int order[4] = {0, 1, 3, 2};
  unsigned int c = 0;
  for (const auto &cell : space.dof_handler().active_cell_iterators())
  {
    for (unsigned int v : order)
      f << (v ? "," : "") << cell->vertex(v)[0] << "," << cell->vertex(v)[1];
    for (unsigned int v : order)
      f << "," << u(cell->vertex_dof_index(v, 0));
    for (const auto &entry : cell_data)
      f << "," << entry.second[c];
    f << "\n";
    ++c;
  }
  write_file_atomically_here(path, f.str());
}
} // namespace

template <int dim>
std::string write_vtu(const Space<dim> &space, const Vector<double> &u, double t,
                      const std::string &dir, const std::string &name, unsigned int index,
                      const CellData &cell_data)
{
  std::ostringstream file;
  file << name << "-" << std::setw(4) << std::setfill('0') << index << ".vtu";
  if (!writes_output())
    return file.str();
  DataOut<dim> out;
  out.attach_dof_handler(space.dof_handler());
  out.add_data_vector(u, "u");
  Vector<double> exact;
  if (space.scene.exact())
  {
    exact.reinit(space.n_dofs());
    const ExactSolution<dim> &u_exact = *space.scene.exact();
    VectorTools::interpolate(space.mapping(), space.dof_handler(),
                             ScalarFunctionFromFunctionObject<dim>(
                               [&](const Point<dim> &x) { return u_exact.value(x, t); }),
                             exact);
    out.add_data_vector(exact, "u_exact");
  }
  for (const auto &[field, values] : cell_data)
    out.add_data_vector(values, field, DataOut<dim>::type_cell_data);
  out.build_patches(space.mapping(), space.degree());
  DataOutBase::VtkFlags flags(t, index);
  out.set_flags(flags);
  std::ostringstream f;
  out.write_vtu(f);
  write_file_atomically_here(dir + "/" + file.str(), f.str());
  write_cells_csv(space, u, cell_data,
                  dir + "/" + file.str().substr(0, file.str().size() - 4) + ".cells.csv");
  return file.str();
}

void write_pvd(const std::string &dir, const std::string &name,
               const std::vector<std::pair<double, std::string>> &records)
{
  if (!writes_output())
    return;
  std::ostringstream f;
  DataOutBase::write_pvd_record(f, records);
  write_file_atomically_here(dir + "/" + name + ".pvd", f.str());
}

template std::string write_vtu<2>(const Space<2> &, const Vector<double> &, double,
                                  const std::string &, const std::string &, unsigned int,
                                  const CellData &);
} // namespace anisodwr
