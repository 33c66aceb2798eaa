#pragma once
// Globally adaptive nested Gauss quadrature in 1D and 2D (an outer integral of inner
// integrals sharing one evaluation budget), for integrals of functions with thin
// layers: the cost grows with the logarithm of the layer width. Used for the exact
// values of the goals (goal/exact_goal.cc and the goal kinds).
#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

namespace anisodwr::nested
{
/// Evaluation budget shared by all (nested) integrals of one exact goal value.
struct Budget
{
  std::size_t remaining;
  bool exhausted = false;
};

struct Integral
{
  double value = 0, error = 0, l1 = 0; ///< l1: estimate of int |f|
  bool converged = true;
};

/// One piece of the interval in integrate(): 10-point Gauss on the whole piece and on
/// its halves (with the same for |f|) and the error estimate |left + right - whole|.
struct Piece
{
  double lo, hi, whole, left, right, abs_left, abs_right, err;
  bool operator<(const Piece &o) const { return err < o.err; }
};

/// 10-point Gauss of f on [lo, hi] (abs_sum: of |f|), charged to the budget.
template <typename F>
double gauss(const F &f, double lo, double hi, double &abs_sum, Budget &budget)
{
  static const dealii::QGauss<1> q(10);
  double s = 0, t = 0;
  for (unsigned int i = 0; i < q.size(); ++i)
  {
    const double v = f(lo + (hi - lo) * q.point(i)[0]);
    s += q.weight(i) * v;
    t += q.weight(i) * std::abs(v);
  }
  budget.remaining -= std::min<std::size_t>(budget.remaining, q.size());
  abs_sum = t * (hi - lo);
  return s * (hi - lo);
}

/// The piece [lo, hi] whose Gauss value on the whole is `whole`.
template <typename F>
Piece make_piece(const F &f, double lo, double hi, double whole, Budget &budget)
{
  Piece p{lo, hi, whole, 0, 0, 0, 0, 0};
  const double m = 0.5 * (lo + hi);
  p.left = gauss(f, lo, m, p.abs_left, budget);
  p.right = gauss(f, m, hi, p.abs_right, budget);
  p.err = std::abs(p.left + p.right - p.whole);
  if (!std::isfinite(p.err))
    p.err = std::numeric_limits<double>::infinity();
  return p;
}

/// The sums over the frozen pieces, then over the open ones (largest error first).
inline Integral piece_totals(const std::vector<Piece> &frozen,
                             std::priority_queue<Piece> pieces)
{
  Integral r;
  auto add = [&](const Piece &p)
  {
    r.value += p.left + p.right;
    r.l1 += p.abs_left + p.abs_right;
    r.error += p.err;
  };
  for (const auto &p : frozen)
    add(p);
  for (; !pieces.empty(); pieces.pop())
    add(pieces.top());
  return r;
}

/// Globally adaptive 1D quadrature: on every piece, 10-point Gauss on the piece and on
/// its two halves; their difference is the piece's error estimate. The piece with the
/// largest estimate is bisected until the sum of the estimates is at most
/// rel_tol * int |f| + abs_tol. The cost follows the integrand's features: a layer of
/// width w in [a, b] costs about log2((b - a)/w) bisections, not (b - a)/w. Pieces
/// narrower than 1e-13 (b - a) are not bisected further (features below round-off of
/// the coordinates); an empty budget stops the bisection (converged = false).
template <typename F>
Integral integrate(const F &f, double a, double b, double rel_tol, double abs_tol,
                   Budget &budget)
{
  Integral result;
  if (!(b > a))
    return result;
  double unused;
  std::priority_queue<Piece> pieces;
  std::vector<Piece> frozen;
  const double min_width = 1e-13 * (b - a);
  pieces.push(make_piece(f, a, b, gauss(f, a, b, unused, budget), budget));
  // running sums (exact sums are recomputed before stopping)
  Integral run = piece_totals(frozen, pieces);
  double frozen_error = 0;
  while (true)
  {
    // stop when converged, or when only the pieces that cannot be bisected keep the
    // error above the tolerance
    const double target = rel_tol * run.l1 + abs_tol;
    if (run.error <= target || run.error - frozen_error <= 0.1 * target ||
        pieces.empty() || budget.remaining == 0)
    {
      result = piece_totals(frozen, pieces);
      if (!std::isfinite(result.value) || !std::isfinite(result.error))
      {
        result.converged = false;
        return result;
      }
      if (result.error <= rel_tol * result.l1 + abs_tol)
        return result;
      if (pieces.empty() || budget.remaining == 0 ||
          result.error - frozen_error <= 0.1 * (rel_tol * result.l1 + abs_tol))
      {
        if (budget.remaining == 0)
          budget.exhausted = true;
        result.converged = false;
        return result;
      }
      run = result;
    }
    const Piece p = pieces.top();
    pieces.pop();
    const double m = 0.5 * (p.lo + p.hi);
    if (p.hi - p.lo < min_width || !(m > p.lo && m < p.hi))
    {
      frozen.push_back(p);
      frozen_error += p.err;
      continue;
    }
    const Piece l = make_piece(f, p.lo, m, p.left, budget),
                r = make_piece(f, m, p.hi, p.right, budget);
    run.value += l.left + l.right + r.left + r.right - p.left - p.right;
    run.l1 +=
        l.abs_left + l.abs_right + r.abs_left + r.abs_right - p.abs_left - p.abs_right;
    run.error += l.err + r.err - p.err;
    pieces.push(l);
    pieces.push(r);
  }
}

/// Evaluations of the integrand allowed for one nested integral (about a second).
constexpr std::size_t budget_limit = 40'000'000;

/// The nested integrals of one exact goal value, sharing one budget: the inner ones are
/// computed 10x more accurately than the outer one needs, so that their errors do not
/// look like features of the outer integrand. Each outer integral takes two passes: a
/// cheap first pass (one bisection per integral) estimates the scale
/// S = int |integrand|, the second one integrates to tol * S; without the absolute part,
/// the tails of the mollifier (values near the underflow limit) would never meet a
/// relative tolerance.
struct NestedIntegrals
{
  explicit NestedIntegrals(double tol) : tol(tol) {}

  double tol;
  Budget budget{budget_limit};
  double error = 0, scale = 0;
  bool converged = true;
  /// tolerances of the current pass
  bool coarse = true;
  double abs_outer = 0, abs_inner = 0, coarse_l1 = 0, inner_rel = 0;

  template <typename F> double outer(const F &inner_f, double a, double b)
  {
    if (coarse)
    {
      const double inf = std::numeric_limits<double>::infinity();
      abs_outer = abs_inner = inf;
      const Integral r = integrate(inner_f, a, b, 1., inf, budget);
      coarse_l1 = r.l1;
      coarse = false;
      abs_outer = 1e-2 * tol * r.l1;
      abs_inner = 1e-3 * tol * r.l1 / std::max(b - a, std::numeric_limits<double>::min());
    }
    const Integral r = integrate(inner_f, a, b, tol, abs_outer, budget);
    coarse = true;
    error += r.error;
    scale += std::max(r.l1, coarse_l1);
    converged = converged && r.converged;
    return r.value;
  }

  template <typename F> double inner(const F &f, double a, double b)
  {
    const Integral r = integrate(f, a, b, 0.1 * tol, abs_inner, budget);
    if (!coarse && !r.converged)
      inner_rel = std::max(inner_rel,
                           r.error / std::max(r.l1, std::numeric_limits<double>::min()));
    return r.value;
  }
};
} // namespace anisodwr::nested
