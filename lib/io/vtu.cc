#include "io/vtu.h"

#include <deal.II/base/function.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <fstream>
#include <iomanip>
#include <sstream>

namespace anisodwr
{
using namespace dealii;


template <int dim>
std::string write_vtu(const Space<dim> &space, const Vector<double> &u, double t,
                      const std::string &dir, const std::string &name, unsigned int index,
                      const CellData &cell_data)
{
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
  std::ostringstream file;
  file << name << "-" << std::setw(4) << std::setfill('0') << index << ".vtu";
  std::ofstream f(dir + "/" + file.str());
  out.write_vtu(f);
  return file.str();
}

void write_pvd(const std::string &dir, const std::string &name,
               const std::vector<std::pair<double, std::string>> &records)
{
  std::ofstream f(dir + "/" + name + ".pvd");
  DataOutBase::write_pvd_record(f, records);
}

template std::string write_vtu<2>(const Space<2> &, const Vector<double> &, double,
                                  const std::string &, const std::string &, unsigned int,
                                  const CellData &);
} // namespace anisodwr
