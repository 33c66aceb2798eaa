#pragma once
// Derived outputs of a finite element function u_h (doc/method.md §10, hemker): values
// along a segment, first crossings of a level found by bisection on u_h itself, a layer
// width, and over-/undershoots.
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/vector.h>

#include "scene/scene.h"

#include <string>
#include <utility>
#include <vector>

namespace anisodwr
{
/// u_h restricted to the segment x(s) = start + s (end - start)/|end - start|, s in
/// [0, L]. The segment is cut at the cell boundaries (cells are the straight-edged,
/// convex images of MappingQ(1)), so u_h is smooth on each piece.
template <int dim> class LineEvaluator
{
public:
  /// `u` is a full vector with constraints distributed.
  LineEvaluator(const dealii::DoFHandler<dim> &dofs, const dealii::Mapping<dim> &mapping,
                const dealii::Vector<double> &u, const dealii::Point<dim> &start,
                const dealii::Point<dim> &end);

  double length() const { return L; }
  dealii::Point<dim> point(double s) const { return a + s * d; }
  /// u_h(x(s)); NaN if x(s) is outside the mesh.
  double value(double s) const;
  /// Parameters where the segment crosses a cell boundary (sorted, with 0 and L if
  /// inside the mesh).
  std::vector<double> breakpoints() const;
  /// The first s >= 0 with u_h(x(s)) = level: each piece is scanned at `scan` points
  /// for a sign change of u_h - level, which is then bisected to |ds| <= 1e-13 L.
  /// NaN if u_h does not reach the level on the segment.
  double first_crossing(double level, unsigned int scan = 8) const;

private:
  struct Piece
  {
    double s0, s1;
    typename dealii::DoFHandler<dim>::active_cell_iterator cell;
  };
  const dealii::Mapping<dim> &mapping;
  const dealii::Vector<double> &u;
  dealii::Point<dim> a;
  dealii::Tensor<1, dim> d;
  double L;
  std::vector<Piece> pieces;
  double value_in(const Piece &piece, double s) const;
};

struct ProbeResult
{
  double layer_width = std::numeric_limits<double>::quiet_NaN();
  /// Positions of the crossings of layer_levels[1] (s_hi) and layer_levels[0] (s_lo).
  double s_hi = std::numeric_limits<double>::quiet_NaN(),
         s_lo = std::numeric_limits<double>::quiet_NaN();
  /// max(u_h - u_max, 0) and max(u_min - u_h, 0): whole domain and strip.
  double overshoot = 0, undershoot = 0, overshoot_strip = 0, undershoot_strip = 0;
  /// ... in the box of ProbeSpec::box (NaN without one)
  double overshoot_box = 0, undershoot_box = 0;
  /// where the undershoot over the domain is largest (NaN if there is none)
  double undershoot_x = std::numeric_limits<double>::quiet_NaN(),
         undershoot_y = std::numeric_limits<double>::quiet_NaN();
  /// where the undershoot in the box is largest (NaN if there is none)
  double undershoot_goals_x = std::numeric_limits<double>::quiet_NaN(),
         undershoot_goals_y = std::numeric_limits<double>::quiet_NaN();
  /// where the overshoot over the domain and in the box is largest (NaN if none)
  double overshoot_x = std::numeric_limits<double>::quiet_NaN(),
         overshoot_y = std::numeric_limits<double>::quiet_NaN(),
         overshoot_goals_x = std::numeric_limits<double>::quiet_NaN(),
         overshoot_goals_y = std::numeric_limits<double>::quiet_NaN();
  double u_min = 0, u_max = 0; ///< the bounds used
  /// Where the bounds come from: "scene" (the scene's own), "exact" (the exact
  /// solution's extrema at T), "data" (the maximum principle on the data, see
  /// data_bounds) or "none: <reason>" (over-/undershoots are then NaN).
  std::string bounds = "none";

  /// The per-loop outputs by name, in the column order of probes.csv.
  std::vector<std::pair<std::string, double>> named() const
  {
    return {{"layer_width", layer_width},
            {"s_hi", s_hi},
            {"s_lo", s_lo},
            {"overshoot", overshoot},
            {"undershoot", undershoot},
            {"overshoot_strip", overshoot_strip},
            {"undershoot_strip", undershoot_strip},
            {"overshoot_goals", overshoot_box},
            {"undershoot_goals", undershoot_box},
            {"undershoot_x", undershoot_x},
            {"undershoot_y", undershoot_y},
            {"undershoot_goals_x", undershoot_goals_x},
            {"undershoot_goals_y", undershoot_goals_y},
            {"u_min", u_min},
            {"u_max", u_max},
            {"overshoot_x", overshoot_x},
            {"overshoot_y", overshoot_y},
            {"overshoot_goals_x", overshoot_goals_x},
            {"overshoot_goals_y", overshoot_goals_y}};
  }
};

/// Bounds of the solution from its data by the maximum principle of
/// u_t - eps Lap u + b.grad u + alpha u = f on [0, T] (alpha >= 0, homogeneous Neumann
/// data): with m, M the extrema of u_0 and g_D (and 0 where alpha > 0 somewhere),
/// m - T max(f^-) <= u <= M + T max(f^+). The data are sampled at the mesh's vertices
/// (u_0, f, alpha) and at the vertices of Dirichlet and Neumann faces (g_D, the Neumann
/// flux), at 17 equidistant times in [0, T]. `applies` is false, with the reason, where
/// the principle does not hold: alpha < 0 somewhere, or Neumann data not zero.
struct DataBounds
{
  bool applies = false;
  std::string reason;
  double u_min = 0, u_max = 0;
};
template <int dim>
DataBounds data_bounds(const dealii::DoFHandler<dim> &dofs, const Scene<dim> &scene);

/// Over-/undershoots are taken at the points of the p-times iterated trapezoidal rule
/// on every cell (the vertices for Q1, where a Q1 function takes its extrema).
/// Bounds NaN in `spec` are the extrema of scene.exact() at T at the same points.
template <int dim>
ProbeResult evaluate_probes(const dealii::DoFHandler<dim> &dofs,
                            const dealii::Mapping<dim> &mapping,
                            const dealii::Vector<double> &u, const ProbeSpec<dim> &spec,
                            const Scene<dim> &scene, double time);

/// Writes s, x, y, u_h along the line: every breakpoint and `per_piece` interior
/// points per piece.
template <int dim>
void write_line_csv(const std::string &path, const LineEvaluator<dim> &line,
                    unsigned int per_piece);
} // namespace anisodwr
