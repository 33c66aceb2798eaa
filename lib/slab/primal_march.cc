#include "slab/primal_march.h"

#include "base/errors.h"

#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace anisodwr
{
using namespace dealii;

template <int dim>
void assemble_slab_load(const Space<dim> &space, const TemporalBasis &basis, double t0,
                        double tau, Vector<double> &F)
{
  const unsigned int m = basis.n_dofs();
  std::vector<double> sq, wq;
  gauss_rule(m + 1, sq, wq);
  F.reinit(space.n_dofs() * m);
  std::vector<double> times(sq.size());
  for (unsigned int q = 0; q < sq.size(); ++q)
    times[q] = t0 + sq[q] * tau;
  std::vector<Vector<double>> Fq;
  space.assemble_loads(times, tau, Fq);
  for (unsigned int q = 0; q < sq.size(); ++q)
    add_kron_vector(tau * wq[q], basis.values(sq[q]), Fq[q], F);
}

void guarded_slab_solve(const MarchOptions &options, const std::string &kind,
                        unsigned int n, const TimeMesh &mesh,
                        const std::function<void()> &solve, const Vector<double> &result,
                        double bound)
{
  std::ostringstream name;
  name << options.label << ", " << kind << " slab " << n + 1 << "/" << mesh.n_slabs()
       << " (t in [" << mesh.t[n] << ", " << mesh.t[n + 1] << "])";
  try
  {
    solve();
  }
  catch (const NumericalError &)
  {
    throw;
  }
  catch (const std::bad_alloc &)
  {
    throw;
  }
  catch (const std::exception &e)
  {
    // library errors (deal.II, UMFPACK) span many lines with a stack trace: the
    // message keeps one line ("Additional information" if there is one), the whole
    // text goes to summary.json
    const std::string what = e.what();
    const auto info = what.find("Additional information:");
    std::string text = info == std::string::npos ? what : what.substr(info + 23);
    if (const auto end = text.find("Stacktrace"); end != std::string::npos)
      text.resize(end);
    std::string line;
    for (const char c : text)
      if (c == '\n' || c == '\t' || c == '\r' || c == ' ')
      {
        if (!line.empty() && line.back() != ' ')
          line += ' ';
      }
      else if (c != '-' || !line.empty())
        line += c;
    while (!line.empty() && line.back() == ' ')
      line.pop_back();
    if (line.size() > 300)
      line = line.substr(0, 297) + "...";
    throw NumericalError(name.str() + ": slab solver failed: " + line +
                             (line == what ? "" : " (full text in summary.json)"),
                         line == what ? "" : what);
  }
  if (!std::isfinite(result.l2_norm()))
    throw NumericalError(name.str() + ": " + kind + " solution contains NaN/Inf");
  if (bound > 0 && result.linfty_norm() > bound)
  {
    std::ostringstream what;
    what << name.str() << ": " << kind << " solution grew to " << result.linfty_norm()
         << ", more than discretization.growth_limit = " << options.growth_limit
         << " times the data bound " << bound / options.growth_limit
         << " (max|u_0| + max|g| + int max|f| dt): the discretization is unstable (e.g. "
            "slabs shorter than delta_K with discretization.supg_tau_factor = 0)";
    throw NumericalError(what.str());
  }
  if (options.progress)
    std::cout << "  [" << name.str() << "] |U| = " << result.l2_norm() << std::endl;
}

template <int dim> double data_bound(const Space<dim> &space, const TimeMesh &mesh)
{
  const Scene<dim> &scene = space.scene;
  const auto box = scene.bounding_box();
  constexpr unsigned int k = 32;
  std::vector<Point<dim>> grid;
  static_assert(dim == 2, "data_bound: 2d grid");
  for (unsigned int i = 0; i <= k; ++i)
    for (unsigned int j = 0; j <= k; ++j)
    {
      const Point<dim> x(box[0][0] + (box[1][0] - box[0][0]) * i / k,
                         box[0][1] + (box[1][1] - box[0][1]) * j / k);
      if (scene.contains(x))
        grid.push_back(x);
    }
  double u0 = 0, g = 0, f = 0;
  for (const auto &x : grid)
    u0 = std::max(u0, std::abs(scene.initial_value(x)));
  for (const auto &cell : space.dof_handler().active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary() && scene.dirichlet_ids.count(face->boundary_id()))
        for (unsigned int v = 0; v < face->n_vertices(); ++v)
          for (unsigned int n = 0; n <= mesh.n_slabs(); ++n)
            g = std::max(g, std::abs(scene.boundary_value(face->vertex(v), mesh.t[n],
                                                          face->boundary_id())));
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    double fn = 0;
    for (const auto &x : grid)
      fn = std::max(fn, std::abs(scene.rhs(x, mesh.start(n) + 0.5 * mesh.tau(n))));
    f += mesh.tau(n) * fn;
  }
  return std::max(1., u0 + g + f);
}

namespace
{
/// The forward march; prepare(t0, tau) readies the slab's operator and returns its jump
/// mass M(t_{n-1}), solve(t0, load, U) solves the slab system.
template <int dim, typename Prepare, typename Solve>
std::vector<Vector<double>> march(const Space<dim> &space, const TimeMesh &mesh,
                                  const TemporalBasis &basis, const MarchOptions &options,
                                  const Prepare &prepare, const Solve &solve)
{
  const double bound =
      options.growth_limit > 0 ? options.growth_limit * data_bound(space, mesh) : 0.;
  std::vector<Vector<double>> U(mesh.n_slabs());
  Vector<double> coupling, last, load;
  space.assemble_initial(mesh.tau(0), coupling); // (u_0, phi + delta b.grad phi)
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    const double t0 = mesh.start(n), tau = mesh.tau(n);
    guarded_slab_solve(
        options, "primal", n, mesh,
        [&]()
        {
          const SparseMatrix<double> &jump_mass = prepare(t0, tau);
          if (n > 0)
          {
            combine_blocks(U[n - 1], basis.right_trace(), last); // u(t_{n-1}^-)
            jump_mass.vmult(coupling, last);
          }
          assemble_slab_load(space, basis, t0, tau, load);
          add_kron_vector(1., basis.left_trace(), coupling, load);
          solve(t0, load, U[n]);
        },
        U[n], bound);
  }
  return U;
}
} // namespace

template <int dim>
std::vector<Vector<double>>
march_primal(const Space<dim> &space, const TimeMesh &mesh, const TemporalBasis &basis,
             SlabOperator<dim> &op, const MarchOptions &options)
{
  return march(
      space, mesh, basis, options,
      [&](double t0, double tau) -> const SparseMatrix<double> &
      {
        op.prepare(t0, tau);
        return op.jump_mass();
      },
      [&](double, const Vector<double> &load, Vector<double> &U) { op.solve(load, U); });
}

template <int dim>
std::vector<Vector<double>>
march_primal_prepared(const Space<dim> &space, const TimeMesh &mesh,
                      const TemporalBasis &basis, const SlabOperator<dim> &op,
                      const MarchOptions &options)
{
  if (!op.prepared_for(mesh))
    throw std::logic_error("march_primal_prepared: the operator is not prepared for the "
                           "march's slabs");
  return march(
      space, mesh, basis, options,
      [&](double, double) -> const SparseMatrix<double> & { return op.jump_mass(); },
      [&](double t0, const Vector<double> &load, Vector<double> &U)
      { op.solve_prepared(t0, load, U); });
}

template std::vector<Vector<double>> march_primal<2>(const Space<2> &, const TimeMesh &,
                                                     const TemporalBasis &,
                                                     SlabOperator<2> &,
                                                     const MarchOptions &);
template std::vector<Vector<double>>
march_primal_prepared<2>(const Space<2> &, const TimeMesh &, const TemporalBasis &,
                         const SlabOperator<2> &, const MarchOptions &);
template double data_bound<2>(const Space<2> &, const TimeMesh &);
template void assemble_slab_load<2>(const Space<2> &, const TemporalBasis &, double,
                                    double, Vector<double> &);
} // namespace anisodwr
