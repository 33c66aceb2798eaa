#pragma once
// f(x, t) of an expression as a short sum of products a_k(t) g_k(x), found numerically,
// so that the custom scene's loads are assembled once per mesh and combined per time as
// for the built-in scenes (Scene::separable_rhs).
#include "scene/scene.h"

#include <functional>
#include <vector>

namespace anisodwr
{
/// Finds f(x, t) = sum_k a_k(t) f(x, t_k) for k < max_terms on samples of x and t by a
/// skeleton (interpolative) decomposition of the matrix F_ij = f(x_i, t_j) at `points`
/// and 4 max_terms times: the times t_k are columns chosen by pivoted Gram-Schmidt until
/// the rest is below 1e-12 of F, the points x_k rows chosen by pivoting, and
/// a(t) = F(x_k, t_l)^{-1} f(x_k, t), which interpolates f at the points x_k for every t.
/// Accepted only if it reproduces f to 1e-11 of max |f| at `points` at the times between
/// the sampled ones and at `check_points` (a denser set: a feature of f that `points`
/// miss must show there) at three other times; then `terms` holds the products and the
/// result is true. An f without t gives one term. `f` must be thread-safe; the terms
/// evaluate it (g_k: once per x, a: max_terms times per t).
bool separate_in_time(const std::function<double(const dealii::Point<2> &, double)> &f,
                      bool uses_t, const std::vector<dealii::Point<2>> &points,
                      const std::vector<dealii::Point<2>> &check_points, double end_time,
                      std::vector<LoadTerm<2>> &terms, unsigned int max_terms = 4);
} // namespace anisodwr
