#include "dwr/probes.h"

#include "base/mpi.h"
#include "io/table.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

/// Parameter interval [s0, s1] of the line a + s d (s in [0, L]) inside the convex
/// polygon of a 2D cell (vertices 0, 1, 3, 2 in counter-clockwise order); false if the
/// line misses the cell.
template <typename Cell>
bool clip(const Cell &cell, const Point<2> &a, const Tensor<1, 2> &d, double L,
          double &s0, double &s1)
{
  const std::array<Point<2>, 4> v{
      {cell->vertex(0), cell->vertex(1), cell->vertex(3), cell->vertex(2)}};
  auto cross = [](const Tensor<1, 2> &x, const Tensor<1, 2> &y)
  { return x[0] * y[1] - x[1] * y[0]; };
  const double orientation = cross(v[1] - v[0], v[2] - v[0]) >= 0 ? 1. : -1.;
  const double scale = (v[2] - v[0]).norm();
  s0 = 0;
  s1 = L;
  for (unsigned int e = 0; e < 4; ++e)
  {
    const Tensor<1, 2> edge = v[(e + 1) % 4] - v[e];
    // inside: orientation * cross(edge, x - v_e) >= 0, linear in s: c0 + s c1
    const double c0 = orientation * cross(edge, a - v[e]),
                 c1 = orientation * cross(edge, d);
    const double tol = 1e-13 * scale * edge.norm();
    if (std::abs(c1) <= 1e-300)
    {
      if (c0 < -tol)
        return false;
      continue;
    }
    const double s = -c0 / c1;
    if (c1 > 0)
      s0 = std::max(s0, s);
    else
      s1 = std::min(s1, s);
  }
  return s1 - s0 > 1e-12 * L;
}
} // namespace

template <int dim>
LineEvaluator<dim>::LineEvaluator(const DoFHandler<dim> &dofs,
                                  const Mapping<dim> &mapping, const Vector<double> &u,
                                  const Point<dim> &start, const Point<dim> &end)
    : mapping(mapping), u(u), a(start), d(end - start), L(d.norm())
{
  static_assert(dim == 2, "LineEvaluator clips 2D cells only");
  d /= L;
  for (const auto &cell : dofs.active_cell_iterators())
  {
    double s0, s1;
    if (clip(cell, a, d, L, s0, s1))
      pieces.push_back({s0, s1, cell});
  }
  std::sort(pieces.begin(), pieces.end(),
            [](const Piece &x, const Piece &y) { return x.s0 < y.s0; });
}

template <int dim> double LineEvaluator<dim>::value_in(const Piece &piece, double s) const
{
  const Point<dim> xi = mapping.transform_real_to_unit_cell(piece.cell, point(s));
  const auto &fe = piece.cell->get_fe();
  Vector<double> local(fe.n_dofs_per_cell());
  piece.cell->get_dof_values(u, local);
  double v = 0;
  for (unsigned int i = 0; i < local.size(); ++i)
    v += local[i] * fe.shape_value(i, xi);
  return v;
}

template <int dim> double LineEvaluator<dim>::value(double s) const
{
  for (const auto &piece : pieces)
    if (s >= piece.s0 - 1e-14 * L && s <= piece.s1 + 1e-14 * L)
      return value_in(piece, std::min(std::max(s, piece.s0), piece.s1));
  return NaN;
}

template <int dim> std::vector<double> LineEvaluator<dim>::breakpoints() const
{
  std::vector<double> s;
  for (const auto &piece : pieces)
  {
    s.push_back(piece.s0);
    s.push_back(piece.s1);
  }
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end(),
                      [this](double x, double y)
                      { return std::abs(x - y) <= 1e-12 * L; }),
          s.end());
  return s;
}

template <int dim>
double LineEvaluator<dim>::first_crossing(double level, unsigned int scan) const
{
  for (const auto &piece : pieces)
  {
    double s_prev = piece.s0, g_prev = value_in(piece, s_prev) - level;
    if (g_prev == 0.)
      return s_prev;
    for (unsigned int k = 1; k <= scan; ++k)
    {
      const double s = piece.s0 + (piece.s1 - piece.s0) * k / scan;
      const double g = value_in(piece, s) - level;
      if (g == 0.)
        return s;
      if ((g > 0) != (g_prev > 0))
      {
        double lo = s_prev, hi = s, g_lo = g_prev;
        while (hi - lo > 1e-13 * L)
        {
          const double mid = 0.5 * (lo + hi), g_mid = value_in(piece, mid) - level;
          if ((g_mid > 0) == (g_lo > 0))
          {
            lo = mid;
            g_lo = g_mid;
          }
          else
            hi = mid;
        }
        return 0.5 * (lo + hi);
      }
      s_prev = s;
      g_prev = g;
    }
  }
  return NaN;
}

namespace
{
/// Extrema of the data sampled by data_bounds.
struct DataExtrema
{
  double lo = 1e300, hi = -1e300; ///< of u_0 and g_D
  double f_lo = 0., f_hi = 0., alpha_min = 1e300, alpha_max = -1e300, flux_max = 0.;
};

/// u_0 at the vertices, f and alpha at the vertices at the times time(k), k < n_times.
template <int dim, typename Time>
void sample_interior_data(const Triangulation<dim> &tria, const Scene<dim> &scene,
                          const Time &time, unsigned int n_times, DataExtrema &e)
{
  std::vector<bool> seen(tria.n_vertices(), false);
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
    {
      if (seen[cell->vertex_index(v)])
        continue;
      seen[cell->vertex_index(v)] = true;
      const Point<dim> &x = cell->vertex(v);
      const double u0 = scene.initial_value(x);
      e.lo = std::min(e.lo, u0);
      e.hi = std::max(e.hi, u0);
      for (unsigned int k = 0; k < n_times; ++k)
      {
        const double f = scene.rhs(x, time(k)), alpha = scene.reaction(x, time(k));
        e.f_lo = std::min(e.f_lo, f);
        e.f_hi = std::max(e.f_hi, f);
        e.alpha_min = std::min(e.alpha_min, alpha);
        e.alpha_max = std::max(e.alpha_max, alpha);
      }
    }
}

/// g_D (into lo, hi) and |g_N| (into flux_max) at the boundary faces' vertices at the
/// times time(k), k < n_times.
template <int dim, typename Time>
void sample_boundary_data(const Triangulation<dim> &tria, const Scene<dim> &scene,
                          const Time &time, unsigned int n_times, DataExtrema &e)
{
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
      {
        const auto id = cell->face(f)->boundary_id();
        const bool dirichlet = scene.dirichlet_ids.count(id) > 0,
                   neumann = scene.neumann_ids.count(id) > 0;
        if (!dirichlet && !neumann)
          continue;
        const auto face = cell->face(f);
        Tensor<1, dim> n;
        if constexpr (dim == 2)
        {
          const Tensor<1, dim> edge = face->vertex(1) - face->vertex(0);
          n[0] = edge[1];
          n[1] = -edge[0];
          n /= n.norm();
          if (n * (face->center() - cell->center()) < 0)
            n *= -1.;
        }
        for (unsigned int v = 0; v < face->n_vertices(); ++v)
          for (unsigned int k = 0; k < n_times; ++k)
            if (dirichlet)
            {
              const double g = scene.boundary_value(face->vertex(v), time(k), id);
              e.lo = std::min(e.lo, g);
              e.hi = std::max(e.hi, g);
            }
            else
              e.flux_max = std::max(
                  e.flux_max, std::abs(scene.boundary_flux(face->vertex(v), n, time(k), id)));
      }
}

} // namespace

template <int dim>
DataBounds data_bounds(const DoFHandler<dim> &dofs, const Scene<dim> &scene)
{
  DataBounds b;
  constexpr unsigned int n_times = 17;
  const double T = scene.end_time;
  const auto time = [&](unsigned int k) { return T * k / (n_times - 1); };
  const auto &tria = dofs.get_triangulation();
  DataExtrema e;
  sample_interior_data(tria, scene, time, n_times, e);
  sample_boundary_data(tria, scene, time, n_times, e);
  if (!std::isfinite(e.lo) || !std::isfinite(e.hi) || !std::isfinite(e.f_lo) ||
      !std::isfinite(e.f_hi))
  {
    b.reason = "none: the data are not finite at a vertex";
    return b;
  }
  if (e.alpha_min < 0.)
  {
    b.reason = "none: alpha < 0 somewhere (no maximum principle)";
    return b;
  }
  if (e.flux_max > 0.)
  {
    b.reason = "none: Neumann data not zero (no maximum principle)";
    return b;
  }
  if (e.alpha_max > 0.)
  {
    e.lo = std::min(e.lo, 0.);
    e.hi = std::max(e.hi, 0.);
  }
  b.applies = true;
  b.reason = "data";
  b.u_min = e.lo + T * e.f_lo;
  b.u_max = e.hi + T * e.f_hi;
  return b;
}

/// The bounds of u_h(T) into r (u_min, u_max, bounds): the scene's, else the exact
/// solution's extrema at T at the points of fv on every cell, else the data's
/// (data_bounds). False where none applies.
template <int dim>
bool set_bounds(const DoFHandler<dim> &dofs, FEValues<dim> &fv, const ProbeSpec<dim> &spec,
                const Scene<dim> &scene, double time, ProbeResult &r)
{
  const bool spec_bounds = !std::isnan(spec.u_min) && !std::isnan(spec.u_max);
  const bool exact_bounds = !spec_bounds && scene.exact();
  // neither the scene's bounds nor an exact solution (a custom scene): the data's
  DataBounds from_data;
  if (!spec_bounds && !exact_bounds)
    from_data = data_bounds(dofs, scene);
  r.bounds = spec_bounds ? "scene" : exact_bounds ? "exact" : from_data.reason;
  r.u_min = spec_bounds ? spec.u_min : exact_bounds ? 1e300 : from_data.u_min;
  r.u_max = spec_bounds ? spec.u_max : exact_bounds ? -1e300 : from_data.u_max;
  if (exact_bounds)
    for (const auto &cell : dofs.active_cell_iterators())
    {
      fv.reinit(cell);
      for (const auto &x : fv.get_quadrature_points())
      {
        const double ue = scene.exact()->value(x, time);
        r.u_min = std::min(r.u_min, ue);
        r.u_max = std::max(r.u_max, ue);
      }
    }
  return spec_bounds || exact_bounds || from_data.applies;
}

template <int dim>
ProbeResult evaluate_probes(const DoFHandler<dim> &dofs, const Mapping<dim> &mapping,
                            const Vector<double> &u, const ProbeSpec<dim> &spec,
                            const Scene<dim> &scene, double time)
{
  ProbeResult r;
  const auto &fe = dofs.get_fe();
  const QIterated<dim> points(QTrapezoid<1>(), std::max(1u, fe.degree));
  FEValues<dim> fv(mapping, fe, points, update_values | update_quadrature_points);
  std::vector<double> uh(points.size());
  const bool no_bounds = !set_bounds(dofs, fv, spec, scene, time, r);
  for (const auto &cell : dofs.active_cell_iterators())
  {
    if (no_bounds)
      break;
    fv.reinit(cell);
    fv.get_function_values(u, uh);
    for (unsigned int q = 0; q < uh.size(); ++q)
    {
      const double over = std::max(uh[q] - r.u_max, 0.),
                   under = std::max(r.u_min - uh[q], 0.);
      const auto &x = fv.quadrature_point(q);
      if (over > r.overshoot)
      {
        r.overshoot = over;
        r.overshoot_x = x[0];
        r.overshoot_y = x[1];
      }
      if (under > r.undershoot)
      {
        r.undershoot = under;
        r.undershoot_x = x[0];
        r.undershoot_y = x[1];
      }
      if (spec.has_strip && x[0] > spec.strip[0] && x[0] < spec.strip[1])
      {
        r.overshoot_strip = std::max(r.overshoot_strip, over);
        r.undershoot_strip = std::max(r.undershoot_strip, under);
      }
      if (spec.has_box && x[0] > spec.box[0] && x[0] < spec.box[1] &&
          x[1] > spec.box[2] && x[1] < spec.box[3])
      {
        if (over > r.overshoot_box)
        {
          r.overshoot_box = over;
          r.overshoot_goals_x = x[0];
          r.overshoot_goals_y = x[1];
        }
        if (under > r.undershoot_box)
        {
          r.undershoot_box = under;
          r.undershoot_goals_x = x[0];
          r.undershoot_goals_y = x[1];
        }
      }
    }
  }
  if (no_bounds)
  {
    r.u_min = r.u_max = r.overshoot = r.undershoot = r.undershoot_x = r.undershoot_y = NaN;
    r.overshoot_strip = r.undershoot_strip = r.overshoot_box = r.undershoot_box = NaN;
  }
  if (!spec.has_strip)
    r.overshoot_strip = r.undershoot_strip = NaN;
  if (!spec.has_box)
    r.overshoot_box = r.undershoot_box = NaN;
  if (spec.has_layer)
  {
    const LineEvaluator<dim> line(dofs, mapping, u, spec.layer_ray.start,
                                  spec.layer_ray.end);
    r.s_hi = line.first_crossing(spec.layer_levels[1]);
    r.s_lo = line.first_crossing(spec.layer_levels[0]);
    r.layer_width = std::abs(r.s_lo - r.s_hi);
  }
  return r;
}

template <int dim>
void write_line_csv(const std::string &path, const LineEvaluator<dim> &line,
                    unsigned int per_piece)
{
  if (!writes_output())
    return;
  std::ostringstream f;
  f << "s,x,y,u\n" << std::setprecision(10);
  const auto bp = line.breakpoints();
  auto row = [&](double s)
  {
    const Point<dim> x = line.point(s);
    f << s << "," << x[0] << "," << x[1] << "," << line.value(s) << "\n";
  };
  for (std::size_t k = 0; k < bp.size(); ++k)
  {
    row(bp[k]);
    if (k + 1 < bp.size())
      for (unsigned int j = 1; j <= per_piece; ++j)
        row(bp[k] + (bp[k + 1] - bp[k]) * j / (per_piece + 1));
  }
  write_file_atomically_here(path, f.str());
}

template class LineEvaluator<2>;
template DataBounds data_bounds<2>(const DoFHandler<2> &, const Scene<2> &);
template ProbeResult evaluate_probes<2>(const DoFHandler<2> &, const Mapping<2> &,
                                        const Vector<double> &, const ProbeSpec<2> &,
                                        const Scene<2> &, double);
template void write_line_csv<2>(const std::string &, const LineEvaluator<2> &,
                                unsigned int);
} // namespace anisodwr
