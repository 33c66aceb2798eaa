#include "adaptivity/refinement.h"
#include "base/errors.h"
#include "scene/scene.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_accessor.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <array>
#include <cmath>
#include <numeric>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// Indices of the ceil(theta n) largest values.
std::vector<unsigned int> largest(const std::vector<double> &v, double theta)
{
  std::vector<unsigned int> order(v.size());
  std::iota(order.begin(), order.end(), 0u);
  const unsigned int k =
      std::min<std::size_t>(v.size(), std::ceil(theta * v.size() - 1e-12));
  std::partial_sort(order.begin(), order.begin() + k, order.end(),
                    [&](unsigned int a, unsigned int b) { return v[a] > v[b]; });
  order.resize(k);
  return order;
}

/// Indices of the fewest largest values (v >= 0) whose sum reaches theta sum(v), the
/// bulk (Doerfler) criterion; none if theta = 0 or every value is 0.
std::vector<unsigned int> bulk(const std::vector<double> &v, double theta)
{
  std::vector<unsigned int> order(v.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](unsigned int a, unsigned int b) { return v[a] > v[b]; });
  const double goal = theta * std::accumulate(v.begin(), v.end(), 0.);
  double sum = 0;
  std::size_t k = 0;
  // a relative slack so that theta = 1 selects every nonzero value despite rounding
  while (k < order.size() && sum < goal * (1 - 1e-12) && v[order[k]] > 0)
    sum += v[order[k++]];
  order.resize(k);
  return order;
}

/// The marked indices by options.marking_criterion (count or bulk) with fraction theta_h.
std::vector<unsigned int> selected(const std::vector<double> &v,
                                   const MarkingOptions &options)
{
  return options.marking_criterion == MarkingCriterion::bulk
             ? bulk(v, options.theta_h)
             : largest(v, options.theta_h);
}

/// The refinement case of each active cell from the directional indicators
/// (adaptivity.mode and adaptivity.marking), before the mesh closure; n active cells.
template <int dim>
std::vector<RefinementCase<dim>> refinement_cases(unsigned int n,
                                                  const Indicators<dim> &ind,
                                                  const MarkingOptions &options)
{
  std::vector<RefinementCase<dim>> cut(n, RefinementCase<dim>::no_refinement);
  if (options.mode == AdaptivityMode::uniform)
    std::fill(cut.begin(), cut.end(), RefinementCase<dim>::isotropic_refinement);
  else if (options.mode == AdaptivityMode::isotropic)
  {
    std::vector<double> eta(n);
    for (unsigned int c = 0; c < n; ++c)
      eta[c] = std::abs(
          std::accumulate(ind.eta_h_cell[c].begin(), ind.eta_h_cell[c].end(), 0.));
    for (unsigned int c : selected(eta, options))
      cut[c] = RefinementCase<dim>::isotropic_refinement;
  }
  else if (options.marking == Marking::joint)
  {
    // all (cell, direction) pairs ranked together; the theta_h * dim * n largest marked
    std::vector<double> eta(n * dim);
    for (unsigned int c = 0; c < n; ++c)
      for (unsigned int i = 0; i < dim; ++i)
        eta[c * dim + i] = std::abs(ind.eta_h_cell[c][i]);
    for (unsigned int ci : selected(eta, options))
      cut[ci / dim] = cut[ci / dim] | RefinementCase<dim>::cut_axis(ci % dim);
  }
  else if (options.marking == Marking::cell)
  {
    std::vector<double> eta(n, 0.);
    for (unsigned int c = 0; c < n; ++c)
      for (unsigned int i = 0; i < dim; ++i)
        eta[c] += std::abs(ind.eta_h_cell[c][i]);
    for (unsigned int c : selected(eta, options))
    {
      double strongest = 0;
      for (unsigned int i = 0; i < dim; ++i)
        strongest = std::max(strongest, std::abs(ind.eta_h_cell[c][i]));
      for (unsigned int i = 0; i < dim; ++i)
        if (std::abs(ind.eta_h_cell[c][i]) >= options.kappa * strongest)
          cut[c] = cut[c] | RefinementCase<dim>::cut_axis(i);
    }
  }
  else
    for (unsigned int i = 0; i < dim; ++i)
    {
      std::vector<double> eta(n);
      for (unsigned int c = 0; c < n; ++c)
        eta[c] = std::abs(ind.eta_h_cell[c][i]);
      for (unsigned int c : selected(eta, options))
        cut[c] = cut[c] | RefinementCase<dim>::cut_axis(i);
    }
  return cut;
}
} // namespace

template <int dim>
MarkingStats mark_cells(Triangulation<dim> &tria, const Indicators<dim> &ind,
                        const MarkingOptions &options)
{
  const unsigned int n = tria.n_active_cells();
  const std::vector<RefinementCase<dim>> cut = refinement_cases(n, ind, options);
  std::vector<bool> coarsen(n, false);
  if (options.theta_coarsen > 0 && options.mode != AdaptivityMode::uniform)
  {
    std::vector<double> eta(n);
    for (unsigned int c = 0; c < n; ++c)
      eta[c] = -std::abs(
          std::accumulate(ind.eta_h_cell[c].begin(), ind.eta_h_cell[c].end(), 0.));
    for (unsigned int c : largest(eta, options.theta_coarsen))
      coarsen[c] = cut[c] == RefinementCase<dim>::no_refinement;
  }
  MarkingStats stats;
  for (const auto &cell : tria.active_cell_iterators())
  {
    const auto c = cell->active_cell_index();
    if (cut[c] != RefinementCase<dim>::no_refinement)
    {
      cell->set_refine_flag(cut[c]);
      ++stats.marked;
      if (cut[c] == RefinementCase<dim>::isotropic_refinement)
        ++stats.cut_both;
      else if (cut[c] == RefinementCase<dim>::cut_axis(0))
        ++stats.cut_x;
      else
        ++stats.cut_y;
    }
    else if (coarsen[c])
      cell->set_coarsen_flag();
  }
  tria.prepare_coarsening_and_refinement();
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->refine_flag_set() != RefinementCase<dim>::no_refinement)
    {
      ++stats.refined;
      if (cell->refine_flag_set() != cut[cell->active_cell_index()])
        ++stats.closure;
    }
  return stats;
}

TimeMesh refine_time(const TimeMesh &mesh, const std::vector<double> &eta_tau_slab,
                     double theta_tau)
{
  std::vector<double> eta(eta_tau_slab.size());
  for (unsigned int n = 0; n < eta.size(); ++n)
    eta[n] = std::abs(eta_tau_slab[n]);
  std::vector<bool> split(eta.size(), false);
  if (theta_tau > 0)
    for (unsigned int n : largest(eta, theta_tau))
      split[n] = true;
  TimeMesh out;
  out.t.push_back(mesh.t[0]);
  for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
  {
    if (split[n])
      out.t.push_back(0.5 * (mesh.t[n] + mesh.t[n + 1]));
    out.t.push_back(mesh.t[n + 1]);
  }
  return out;
}

template <int dim>
double max_aspect_ratio(const Triangulation<dim> &tria, const Mapping<dim> &mapping,
                        std::vector<double> *per_cell)
{
  const FE_Nothing<dim> fe;
  const QGauss<dim> quad(2);
  FEValues<dim> fv(mapping, fe, quad, update_jacobians);
  double ar = 1;
  if (per_cell)
    per_cell->assign(tria.n_active_cells(), 1.);
  for (const auto &cell : tria.active_cell_iterators())
  {
    fv.reinit(cell);
    double cell_ar = 1;
    for (unsigned int q = 0; q < quad.size(); ++q)
    {
      // singular values of J: square roots of the eigenvalues of G = J^T J, in closed
      // form (deal.II's eigenvalues() asserts distinct ones, which a square cell has not)
      static_assert(dim == 2, "the aspect ratio's closed form is 2D");
      const Tensor<2, dim> J = Tensor<2, dim>(fv.jacobian(q));
      const Tensor<2, dim> G = transpose(J) * J;
      const double mean = 0.5 * (G[0][0] + G[1][1]), half = 0.5 * (G[0][0] - G[1][1]);
      const double d = std::sqrt(half * half + G[0][1] * G[0][1]);
      const double hi = mean + d, lo = determinant(J) * determinant(J) / hi;
      cell_ar = std::max(cell_ar, std::sqrt(hi / lo));
    }
    if (per_cell)
      (*per_cell)[cell->active_cell_index()] = cell_ar;
    ar = std::max(ar, cell_ar);
  }
  return ar;
}

template <int dim> double max_hanging_gap(const Triangulation<dim> &tria)
{
  static_assert(dim == 2, "faces with one hanging vertex: 2D");
  double worst = 0;
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
    {
      const auto face = cell->face(f);
      if (cell->at_boundary(f) || !face->has_children())
        continue;
      const Point<dim> a = face->vertex(0), b = face->vertex(1),
                       v = face->child(0)->vertex(1);
      const Tensor<1, dim> t = (b - a) / (b - a).norm();
      const Tensor<1, dim> off = (v - a) - ((v - a) * t) * t;
      double thin = 1e300;
      for (unsigned int s = 0; s < face->n_children(); ++s)
        thin = std::min(thin,
                        cell->neighbor_child_on_subface(f, s)->minimum_vertex_distance());
      worst = std::max(worst, off.norm() / thin);
    }
  return worst;
}

template <int dim>
std::vector<unsigned char>
cells_out_of_bounds(const DoFHandler<dim> &dofs, const std::vector<Vector<double>> &u,
                    double u_min, double u_max, double threshold, double min_aspect,
                    const std::function<Tensor<1, dim>(const Point<dim> &)> &b)
{
  const auto &tria = dofs.get_triangulation();
  std::vector<unsigned char> cuts(tria.n_active_cells(), 0);
  std::vector<types::global_dof_index> idx(dofs.get_fe().n_dofs_per_cell());
  for (const auto &cell : dofs.active_cell_iterators())
  {
    cell->get_dof_indices(idx);
    bool out = false;
    for (const auto &v : u)
      for (const auto i : idx)
        out = out || v[i] < u_min - threshold || v[i] > u_max + threshold;
    if (!out)
      continue;
    const Tensor<1, dim> beta = b(cell->center());
    // the cell's local axes d: from vertex 0 to the vertex 2^d
    std::array<Tensor<1, dim>, dim> e;
    unsigned int axis = 0;
    double best = -1.;
    for (unsigned int d = 0; d < dim; ++d)
    {
      e[d] = cell->vertex(1u << d) - cell->vertex(0);
      const double c = std::abs(e[d] * beta) / std::max(e[d].norm(), 1e-300);
      if (c > best)
        best = c, axis = d;
    }
    double shortest = 1e300;
    for (unsigned int d = 0; d < dim; ++d)
      if (d != axis)
        shortest = std::min(shortest, e[d].norm());
    if (e[axis].norm() >= min_aspect * shortest)
      cuts[cell->active_cell_index()] = static_cast<unsigned char>(1 + axis);
  }
  return cuts;
}

template <int dim>
unsigned int add_cuts(Triangulation<dim> &tria, const std::vector<unsigned char> &cuts)
{
  unsigned int changed = 0;
  for (const auto &cell : tria.active_cell_iterators())
  {
    const unsigned char c = cuts[cell->active_cell_index()];
    if (c == 0)
      continue;
    const RefinementCase<dim> cut = RefinementCase<dim>::cut_axis(c - 1);
    const RefinementCase<dim> old = cell->refine_flag_set();
    const RefinementCase<dim> both = old | cut;
    if (both != old)
    {
      cell->clear_coarsen_flag();
      cell->set_refine_flag(both);
      ++changed;
    }
  }
  return changed;
}

namespace
{
/// The target thickness of `cell` across its face `f` if that face is an outflow part
/// of the Dirichlet boundary (b.n > 0 at the face's centre at t = 0, T/2 or T, n the
/// outward normal of the straight face): factor eps / max_t b.n; 0 otherwise.
double wall_target(const Triangulation<2>::active_cell_iterator &cell, unsigned int f,
                   const Scene<2> &scene, double factor)
{
  const auto face = cell->face(f);
  if (!face->at_boundary() || !scene.dirichlet_ids.count(face->boundary_id()))
    return 0.;
  const double bn = outflow_speed(*cell, f, scene).second;
  return bn > 0. ? factor * scene.epsilon / bn : 0.;
}

} // namespace

WallLayer refine_wall_layer(Triangulation<2> &tria, const Scene<2> &scene, double factor)
{
  WallLayer w;
  w.cells_before = w.cells_after = tria.n_active_cells();
  if (!(factor > 0.))
    return w;
  // the halvings the thickest wall cell needs, checked before the mesh grows
  double ratio = 1.;
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (const double target = wall_target(cell, f, scene, factor); target > 0.)
        ratio = std::max(ratio, thickness_across(*cell, f) / target);
  if (std::log2(ratio) > WallLayer::max_passes)
  {
    std::ostringstream m;
    m << "discretization.wall_layer = " << factor << ": the cells at the outflow Dirichlet "
      << "boundary would need " << std::ceil(std::log2(ratio)) << " halvings to be "
      << "wall_layer * eps / (b.n) thick (eps = " << scene.epsilon << "); expected at most "
      << WallLayer::max_passes << " (a larger wall_layer, more initial_refinements, or 0)";
    throw InputError(m.str());
  }
  for (;;)
  {
    unsigned int flagged = 0;
    for (const auto &cell : tria.active_cell_iterators())
    {
      RefinementCase<2> cut = RefinementCase<2>::no_refinement;
      for (const unsigned int f : cell->face_indices())
      {
        const double target = wall_target(cell, f, scene, factor);
        if (target > 0. && thickness_across(*cell, f) > target)
        {
          cut = cut | RefinementCase<2>::cut_axis(f / 2);
          w.thinnest_target = w.thinnest_target > 0. ? std::min(w.thinnest_target, target)
                                                     : target;
        }
      }
      if (cut != RefinementCase<2>::no_refinement)
      {
        cell->set_refine_flag(cut);
        ++flagged;
      }
    }
    if (flagged == 0)
      break;
    // a bound beside the check above: the closure's tangential cuts tilt a curved wall's
    // faces, which changes b.n and so the targets of the cells they leave
    if (w.passes > WallLayer::max_passes)
      break;
    tria.execute_coarsening_and_refinement();
    ++w.passes;
  }
  w.cells_after = tria.n_active_cells();
  return w;
}

std::string wall_layer_text(const WallLayer &w)
{
  if (w.passes == 0)
    return "wall layer: no outflow Dirichlet face is thicker than its target, mesh "
           "unchanged";
  std::ostringstream s;
  s << "wall layer: " << w.passes << " halvings at the outflow Dirichlet boundary, cells "
    << w.cells_before << " -> " << w.cells_after << ", thinnest target "
    << std::setprecision(3) << w.thinnest_target;
  return s.str();
}

namespace
{
/// One goal's upstream path: its points, the unit direction of b on each segment, and
/// the support's width across b there.
struct Streak
{
  std::vector<Point<2>> path;
  std::vector<Tensor<1, 2>> along;
  std::vector<double> width;
};

bool inside_mesh(const Triangulation<2> &tria, const Point<2> &p)
{
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->bounding_box().point_inside(p) && cell->point_inside(p))
      return true;
  return false;
}

/// The upstream path of a point or mean goal's centre (empty for other kinds).
Streak trace_streak(const Triangulation<2> &tria, const Scene<2> &scene, const GoalSpec &g)
{
  Streak s;
  std::array<double, 4> r;
  if (!support_rectangle(g, r))
    return s;
  // a point goal's centre as given (the square's mid-point can differ in the last bit)
  Point<2> x = g.kind == "point" ? Point<2>(g.location[0], g.location[1])
                                 : Point<2>(0.5 * (r[0] + r[2]), 0.5 * (r[1] + r[3]));
  constexpr unsigned int steps = 400;
  const double dt = scene.end_time / steps;
  double t = scene.end_time;
  s.path.push_back(x);
  for (unsigned int k = 0; k < steps; ++k, t -= dt)
  {
    const Tensor<1, 2> b = scene.convection(x, t);
    if (b.norm() == 0.)
      break;
    const Point<2> mid = x - 0.5 * dt * b;
    const Tensor<1, 2> bm = scene.convection(mid, t - 0.5 * dt);
    if (bm.norm() == 0.)
      break;
    const Tensor<1, 2> e = bm / bm.norm();
    x = x - dt * bm;
    s.along.push_back(e);
    s.width.push_back(support_extent(g, -e[1], e[0])); // across b: along e's normal
    s.path.push_back(x);
    if (!inside_mesh(tria, x))
      break;
  }
  return s;
}

/// The distance from p to the segment [a, b].
double distance_to_segment(const Point<2> &p, const Point<2> &a, const Point<2> &b)
{
  const Tensor<1, 2> d = b - a;
  const double l2 = d.norm_square();
  const double t = l2 > 0. ? std::clamp((p - a) * d / l2, 0., 1.) : 0.;
  return p.distance(a + t * d);
}

/// The local axes of a quadrilateral cell (the mean of its opposite edges).
std::array<Tensor<1, 2>, 2> local_axes(const Triangulation<2>::active_cell_iterator &cell)
{
  return {{0.5 * ((cell->vertex(1) - cell->vertex(0)) + (cell->vertex(3) - cell->vertex(2))),
           0.5 * ((cell->vertex(2) - cell->vertex(0)) + (cell->vertex(3) - cell->vertex(1)))}};
}

double cross(const Tensor<1, 2> &a, const Tensor<1, 2> &e)
{
  return std::abs(a[0] * e[1] - a[1] * e[0]);
}

/// The width of `cell` across the unit direction e.
double width_across(const Triangulation<2>::active_cell_iterator &cell, const Tensor<1, 2> &e)
{
  const auto axis = local_axes(cell);
  return cross(axis[0], e) + cross(axis[1], e);
}

/// The cut that halves `cell` across the streak's direction e where it spans more than
/// `target` across e (each local axis at least 45 degrees across e).
RefinementCase<2> cut_across(const Triangulation<2>::active_cell_iterator &cell,
                             const Tensor<1, 2> &e, double target)
{
  const auto axis = local_axes(cell);
  RefinementCase<2> cut = RefinementCase<2>::no_refinement;
  for (unsigned int i = 0; i < 2; ++i)
  {
    const double along = std::abs(axis[i] * e);
    const double across = cross(axis[i], e);
    if (across > target && across >= along)
      cut = cut | RefinementCase<2>::cut_axis(i);
  }
  return cut;
}
} // namespace

GoalStreak refine_goal_streak(Triangulation<2> &tria, const Scene<2> &scene,
                              const std::vector<GoalSpec> &goals, double factor)
{
  GoalStreak r;
  r.cells_before = r.cells_after = tria.n_active_cells();
  if (!(factor > 0.))
    return r;
  std::vector<Streak> streaks;
  for (const GoalSpec &g : goals)
    if (Streak s = trace_streak(tria, scene, g); !s.along.empty())
      streaks.push_back(std::move(s));
  r.goals = streaks.size();
  // the cut of a cell near a streak, and the target it is halved to
  const auto cut_of = [&](const Triangulation<2>::active_cell_iterator &cell, double &target)
  {
    RefinementCase<2> cut = RefinementCase<2>::no_refinement;
    const Point<2> c = cell->center();
    for (const Streak &s : streaks)
      for (unsigned int k = 0; k < s.along.size(); ++k)
        if (distance_to_segment(c, s.path[k], s.path[k + 1]) <=
            0.5 * (s.width[k] + width_across(cell, s.along[k])))
        {
          const double w = s.width[k] / factor;
          const RefinementCase<2> more = cut_across(cell, s.along[k], w);
          if (more != RefinementCase<2>::no_refinement)
            target = target > 0. ? std::min(target, w) : w;
          cut = cut | more;
        }
    return cut;
  };
  for (;;)
  {
    unsigned int flagged = 0;
    for (const auto &cell : tria.active_cell_iterators())
    {
      double target = 0.;
      const RefinementCase<2> cut = cut_of(cell, target);
      if (cut == RefinementCase<2>::no_refinement)
        continue;
      if (r.passes == 0 && std::log2(cell->diameter() / target) > GoalStreak::max_passes)
      {
        std::ostringstream m;
        m << "discretization.goal_streak = " << factor << ": a cell of diameter "
          << cell->diameter() << " on a goal's upstream path would need more than "
          << GoalStreak::max_passes << " halvings to be " << target << " thick across b "
          << "(a goal's support width / goal_streak); expected a smaller goal_streak, "
          << "more initial_refinements, or 0";
        throw InputError(m.str());
      }
      r.thinnest_target = r.thinnest_target > 0. ? std::min(r.thinnest_target, target) : target;
      cell->set_refine_flag(cut);
      ++flagged;
    }
    if (flagged == 0 || r.passes > GoalStreak::max_passes)
      break;
    tria.execute_coarsening_and_refinement();
    ++r.passes;
  }
  r.cells_after = tria.n_active_cells();
  return r;
}

std::string goal_streak_text(const GoalStreak &s)
{
  std::ostringstream m;
  if (s.passes == 0)
    m << "goal streak: " << s.goals << " goals traced upstream, no cell thicker than its "
      << "target, mesh unchanged";
  else
    m << "goal streak: " << s.passes << " halvings along " << s.goals
      << " goals' upstream paths, cells " << s.cells_before << " -> " << s.cells_after
      << ", thinnest target " << std::setprecision(3) << s.thinnest_target;
  return m.str();
}

template std::vector<unsigned char>
cells_out_of_bounds<2>(const DoFHandler<2> &, const std::vector<Vector<double>> &, double,
                       double, double, double, const std::function<Tensor<1, 2>(const Point<2> &)> &);
template unsigned int add_cuts<2>(Triangulation<2> &, const std::vector<unsigned char> &);
template double max_hanging_gap<2>(const Triangulation<2> &);
template MarkingStats mark_cells<2>(Triangulation<2> &, const Indicators<2> &,
                                    const MarkingOptions &);
template double max_aspect_ratio<2>(const Triangulation<2> &, const Mapping<2> &,
                                    std::vector<double> *);
} // namespace anisodwr
