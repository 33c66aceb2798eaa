// check_against_exact (lib/scene/custom_scene.h): the data of a scene against its exact
// solution, by difference quotients at sample points.
#include "base/errors.h"
#include "scene/custom_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// Step sizes of the difference quotients, as fractions of the length and of T.
constexpr double steps[] = {1e-2, 1e-3, 1e-4, 1e-5};

/// Derivatives of u at (x, t) by fourth-order central differences with steps hx, ht.
struct Derivatives
{
  double u, ut, ux, uy, lap;
  double size = 0; ///< the largest |u| in the stencils
};
Derivatives derivatives(const ExactSolution<2> &u, const Point<2> &x, double t, double hx,
                        double ht)
{
  Derivatives d;
  d.u = u.value(x, t);
  double s[2][4]; // u at x -+ h, x -+ 2h in each direction
  for (unsigned int k = 0; k < 2; ++k)
  {
    Tensor<1, 2> e;
    e[k] = hx;
    s[k][0] = u.value(x - 2. * e, t);
    s[k][1] = u.value(x - e, t);
    s[k][2] = u.value(x + e, t);
    s[k][3] = u.value(x + 2. * e, t);
  }
  const auto d1 = [](const double *v, double h)
  { return (v[0] - 8. * v[1] + 8. * v[2] - v[3]) / (12. * h); };
  const auto d2 = [&](const double *v, double h)
  { return (-v[0] + 16. * v[1] - 30. * d.u + 16. * v[2] - v[3]) / (12. * h * h); };
  d.ux = d1(s[0], hx);
  d.uy = d1(s[1], hx);
  d.lap = d2(s[0], hx) + d2(s[1], hx);
  const double tt[4] = {u.value(x, t - 2. * ht), u.value(x, t - ht), u.value(x, t + ht),
                        u.value(x, t + 2. * ht)};
  d.ut = d1(tt, ht);
  d.size = std::abs(d.u);
  for (const auto &v : s)
    for (const double w : v)
      d.size = std::max(d.size, std::abs(w));
  for (const double w : tt)
    d.size = std::max(d.size, std::abs(w));
  return d;
}

/// The largest residual of one check, where it was found, and the check's scale.
struct Worst
{
  double residual = 0, scale = 0;
  Point<2> x;
  double t = 0;
  bool found = false;
  void add(double r, const Point<2> &at, double time)
  {
    if (!found || !(r <= residual)) // NaN wins
    {
      residual = r;
      x = at;
      t = time;
      found = true;
    }
  }
};

std::string g(double v)
{
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

void report(const Worst &w, double tolerance, const std::string &where,
            const DataKeys &keys, const std::string &key, const std::string &what,
            const std::string &scale)
{
  if (!w.found || w.residual <= tolerance * w.scale)
    return;
  const auto source = keys.sources.find(key);
  throw InputError((source == keys.sources.end() ? where : source->second) + ": key '" +
                   key + "' does not match scene.exact_solution: " + what + " is " +
                   g(w.residual) + " at (x, y, t) = (" + g(w.x[0]) + ", " + g(w.x[1]) +
                   ", " + g(w.t) + "); allowed: scene.check_tolerance " + g(tolerance) +
                   " x " + g(w.scale) + " (" + scale + ")");
}
/// The PDE's residual at the sample points: per point the smallest over the steps;
/// scale: the largest sum of the terms' sizes.
Worst pde_residual(const Scene<2> &scene, const ExactSolution<2> &u, const SamplePoints &points)
{
  const double eps = scene.epsilon, L = points.length, T = scene.end_time;
  Worst pde;
  for (const double t : points.times)
    for (const auto &x : points.interior)
    {
      const Tensor<1, 2> b = scene.convection(x, t);
      const double alpha = scene.reaction(x, t), f = scene.rhs(x, t);
      double best = std::nan(""), terms = 0; // NaN if no step gives a finite residual
      for (const double h : steps)
      {
        const Derivatives d = derivatives(u, x, t, h * L, h * T);
        const double parts[5] = {d.ut, -eps * d.lap, b[0] * d.ux + b[1] * d.uy,
                                 alpha * d.u, -f};
        double r = 0, sum = 0;
        for (const double p : parts)
        {
          r += p;
          sum += std::abs(p);
        }
        // the round-off of the difference quotients (and of f) at this step: a
        // residual below 16 times it is no evidence against the data (u = x y has
        // exact derivatives, and its residual is pure round-off)
        const double hx = h * L, ht = h * T, machine = std::numeric_limits<double>::epsilon();
        const double noise =
            machine * (d.size * (1.5 / ht + 10. * eps / (hx * hx) +
                                 3. * (std::abs(b[0]) + std::abs(b[1])) / hx + std::abs(alpha)) +
                       std::abs(f));
        if (std::isfinite(r) && std::abs(r) <= 16. * noise)
          r = 0.;
        if (std::isfinite(r) && !(std::abs(r) >= best))
        {
          best = std::abs(r);
          terms = sum;
        }
      }
      pde.add(best, x, t);
      pde.scale = std::max(pde.scale, terms);
    }
  return pde;
}
} // namespace

void check_against_exact(const Scene<2> &scene, const SamplePoints &points,
                         double tolerance, const std::string &where, const DataKeys &keys)
{
  const ExactSolution<2> *u = scene.exact();
  if (!u)
    return;
  const double eps = scene.epsilon, L = points.length, T = scene.end_time;
  std::vector<double> times_0 = points.times;
  times_0.insert(times_0.begin(), 0.);

  // max |u| over all samples: the scale of the value checks
  double u_max = 0;
  for (const double t : times_0)
  {
    for (const auto &x : points.interior)
      u_max = std::max(u_max, std::abs(u->value(x, t)));
    for (const auto &p : points.boundary)
      u_max = std::max(u_max, std::abs(u->value(p.x, t)));
  }

  const Worst pde = pde_residual(scene, *u, points);
  report(pde, tolerance, where, keys, keys.rhs,
         "the PDE residual u_t - eps Lap u + b.grad u + alpha u - f",
         "the largest sum of "
         "|terms| of the PDE at the sample points");

  Worst initial;
  initial.scale = u_max;
  for (const auto &x : points.interior)
    initial.add(std::abs(scene.initial_value(x) - u->value(x, 0.)), x, 0.);
  for (const auto &p : points.boundary)
    initial.add(std::abs(scene.initial_value(p.x) - u->value(p.x, 0.)), p.x, 0.);
  report(initial, tolerance, where, keys, keys.initial_value, "u_0 - u(., 0)",
         "max |u| at the sample points");

  Worst dirichlet, neumann;
  dirichlet.scale = u_max;
  neumann.scale = eps * u_max / L;
  for (const auto &p : points.boundary)
    for (const double t : times_0)
      if (scene.dirichlet_ids.count(p.id))
        dirichlet.add(std::abs(scene.boundary_value(p.x, t, p.id) - u->value(p.x, t)),
                      p.x, t);
      else if (scene.neumann_ids.count(p.id))
      {
        const double gN = scene.boundary_flux(p.x, p.normal, t, p.id);
        double best = std::nan("");
        for (const double h : steps)
        {
          const Derivatives d = derivatives(*u, p.x, t, h * L, h * T);
          const double flux = eps * (d.ux * p.normal[0] + d.uy * p.normal[1]);
          const double r = gN - flux;
          if (std::isfinite(r) && !(std::abs(r) >= best))
          {
            best = std::abs(r);
            neumann.scale = std::max(neumann.scale, std::abs(flux));
          }
        }
        neumann.add(best, p.x, t);
      }
  report(dirichlet, tolerance, where, keys, keys.dirichlet, "g_D - u",
         "max |u| at the sample points");
  report(neumann, tolerance, where, keys, keys.neumann, "g_N - eps grad u.n",
         "max |eps grad u.n| at the sample points, at least eps max|u| / diameter");
}
} // namespace anisodwr
