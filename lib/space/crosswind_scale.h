#pragma once
// The residual-based switch of the crosswind diffusion (discretization.crosswind_form =
// residual, doc/method.md §3): a factor per cell computed from a discrete solution.
#include "space/space.h"

#include <deal.II/lac/vector.h>

#include <vector>

namespace anisodwr
{
/// s_K = min(1, sum_n tau_n int_K |R_n| / sum_n tau_n int_K |b| |grad u_n|) per active
/// cell of `space`'s mesh (by active cell index), with u_n the solution at the end t_n of
/// slab n (`ends`, on `space`'s DoFs; `times` = t_0 < ... < t_N), tau_n = t_n - t_{n-1}
/// and R_n = (u_n - u_{n-1}) / tau_n - eps Lap u_n + b.grad u_n + alpha u_n - f the
/// strong residual at t_n (u_0 the initial data). This is the ratio |R(u_h)| / (|b|
/// |grad u_h|) of residual-based crosswind (SOLD) terms: where u_h solves the transport
/// along b (a layer along b, a smooth solution) it is small, and where u_h changes along
/// b against the equation (the spurious oscillations SUPG leaves) it is about 1. 0 where
/// u_h is constant on K (mean |b| |grad u_h| below 1e-10 max|b| max|u_h| / the diagonal of
/// the bounding box of Omega).
/// The factor is raised to the power `exponent` (discretization.crosswind_exponent).
template <int dim>
std::vector<double> crosswind_scale(const Space<dim> &space, const std::vector<double> &times,
                                    const std::vector<dealii::Vector<double>> &ends,
                                    double exponent = 1.);
} // namespace anisodwr
