// The value of Hemker's goal J_1 for eps -> 0 from matched asymptotics, independent of
// the finite element code (doc/results.md, "Hemker: the circle's polygon moves the
// layer"). Build and run:
//
//   g++ -O2 -o hemker_asymptotics scripts/hemker_asymptotics.cc && ./hemker_asymptotics
//
// 1. The inner problem at the circle's top (0, 1), where the wall turns tangential to
//    b = (1, 0): with x = eps^(1/3) X, y - 1 = eps^(2/3) Y the steady equation
//    u_x = eps Lap u becomes u_X = u_YY on Y > Y_w(X), u = 1 on the wall
//    Y_w(X) = -X^2/2, u -> 0 for Y -> infinity. Downstream the layer is an erfc profile
//    centred at Y = c, c = lim_{X->inf} (int (u - H(-Y)) dY): the wall's mass
//    shifts the interior layer up by delta = c eps^(2/3). Solved by marching in X
//    (Crank-Nicolson; implicit Euler for a polygonal wall) in the wall distance
//    eta = Y - Y_w(X), where v_X - Y_w'(X) v_eta = v_etaeta.
//    The same with Y_w the polygon through the points X = k Lx of the parabola: the
//    wall of a Q1 map whose boundary vertices lie Lx eps^(1/3) apart along x.
// 2. J_1 = int_0^T u(x_e1, t) dt mollified (x_e1 = (4, 1), radius s = 0.01, the
//    goal's mollifier C exp(1 - 1/(1 - r^2/s^2))). With U = int_0^T u dt,
//    b.grad U - eps Lap U = -u(T), so J_1 = int phi ((T - x) u_s + V) where u_s is the
//    steady layer 0.5 erfc((y - 1 - delta) / sqrt(4 eps x)) and V solves the outer
//    equation V_x = eps V_yy with V(0, y) = sqrt(1 - y^2) for y < 1 (the shadow behind
//    the circle, reached sqrt(1 - y^2) earlier than the top's streamline): V is that
//    profile smoothed by the heat kernel of variance 2 eps x. For the polygon the
//    wall's x at height y is that of its chord.
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace
{
/// c of the inner problem with wall Y_w (derivative dYw): march X from -X0 to X1 on
/// eta in (0, H) with step deta, dX; theta = 0.5 Crank-Nicolson, 1 implicit Euler.
double wall_mass(const std::function<double(double)> &Yw,
                 const std::function<double(double)> &dYw, double theta)
{
  const double X0 = 6, X1 = 6, H = 50, deta = 0.005, dX = 0.0005;
  const int n = int(H / deta);
  std::vector<double> v(n + 1), a(n + 1), b(n + 1), c(n + 1), d(n + 1), w(n + 1);
  double X = -X0;
  for (int j = 0; j <= n; ++j) // the exponential layer of the wall moving into the flow
    v[j] = std::exp(-std::abs(dYw(X)) * j * deta);
  v[n] = 0;
  const int steps = int((X0 + X1) / dX + 0.5);
  for (int s = 0; s < steps; ++s)
  {
    const double slope_old = dYw(X), slope = dYw(X + dX - 0.5 * dX * (theta == 1.));
    for (int j = 1; j < n; ++j)
    {
      const double rhs = (v[j + 1] - 2 * v[j] + v[j - 1]) / (deta * deta) +
                         slope_old * (v[j + 1] - v[j - 1]) / (2 * deta);
      a[j] = -theta * dX * (1 / (deta * deta) - slope / (2 * deta));
      b[j] = 1 + theta * dX * 2 / (deta * deta);
      c[j] = -theta * dX * (1 / (deta * deta) + slope / (2 * deta));
      d[j] = v[j] + (1 - theta) * dX * rhs;
    }
    d[1] -= a[1]; // v = 1 on the wall, 0 at eta = H
    for (int j = 2; j < n; ++j)
    {
      const double m = a[j] / b[j - 1];
      b[j] -= m * c[j - 1];
      d[j] -= m * d[j - 1];
    }
    w[0] = 1;
    w[n] = 0;
    w[n - 1] = d[n - 1] / b[n - 1];
    for (int j = n - 2; j >= 1; --j)
      w[j] = (d[j] - c[j] * w[j + 1]) / b[j];
    v.swap(w);
    X += dX;
  }
  double integral = 0;
  for (int j = 0; j < n; ++j)
    integral += 0.5 * (v[j] + v[j + 1]) * deta;
  return integral + Yw(X); // int_{Y_w}^inf u dY - int_{Y_w}^0 1 dY
}

/// The polygon through the parabola's points X = k Lx.
double polygon(double X, double Lx)
{
  const double k = std::floor(X / Lx), a = k * Lx, b = a + Lx;
  return -a * a / 2 + (a * a - b * b) / 2 * (X - a) / Lx;
}

/// The distance behind the top at which the wall of height y < 1 lies: sqrt(1 - y^2)
/// on the circle, the chords between its points x = k L if L > 0.
double wall_x(double y, double L)
{
  if (y >= 1)
    return 0;
  const double x = std::sqrt(1 - y * y);
  if (L <= 0)
    return x;
  const double k = std::floor(x / L), ya = std::sqrt(1 - k * L * k * L),
               yb = std::sqrt(std::max(0., 1 - (k + 1) * L * (k + 1) * L));
  return k * L + L * (ya - y) / (ya - yb);
}

/// The mollified J_1 for the layer shift delta, with the wall's chords of length L
/// along x behind the top (L = 0: the circle).
double j1(double eps, double delta, double L = 0)
{
  const double s = 0.01, T = 9;
  const int N = 240, K = 60;
  double weight = 0, sum = 0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
    {
      const double X = -1 + (i + 0.5) * 2 / N, Y = -1 + (j + 0.5) * 2 / N,
                   r2 = X * X + Y * Y;
      if (r2 >= 1)
        continue;
      const double phi = std::exp(1 - 1 / (1 - r2)), x = 4 + s * X, y = 1 + s * Y;
      const double us = 0.5 * std::erfc((y - 1 - delta) / std::sqrt(4 * eps * x));
      // V: sqrt(1 - y^2)_+ smoothed by the Gaussian of variance 2 eps x (Simpson-like
      // midpoint sum over +-6 standard deviations)
      const double sd = std::sqrt(2 * eps * x);
      double v = 0, g = 0;
      for (int k = -K; k <= K; ++k)
      {
        const double z = 6. * k / K, gk = std::exp(-z * z / 2), yy = y + sd * z;
        v += gk * wall_x(yy, L);
        g += gk;
      }
      weight += phi;
      sum += phi * ((T - x) * us + v / g);
    }
  return sum / weight;
}
} // namespace

int main()
{
  const double eps = 1e-6, scale = std::cbrt(eps); // x = eps^(1/3) X
  const double c = wall_mass([](double X) { return -X * X / 2; },
                             [](double X) { return -X; }, 0.5);
  std::printf("inner problem, parabolic wall: c = %.4f, delta = c eps^(2/3) = %.4e\n", c,
              c * scale * scale);
  std::printf("J_1 (eps = %g, asymptotic) = %.4f\n\n", eps, j1(eps, c * scale * scale));
  std::printf("| vertex spacing along x at the top | c | delta | J_1 |\n|---|---|---|---|\n");
  for (double L : {0.0025, 0.005, 0.01, 0.02, 0.049})
  {
    const double Lx = L / scale;
    const double cL = wall_mass([Lx](double X) { return polygon(X, Lx); },
                                [Lx](double X)
                                { return (polygon(X + 1e-7, Lx) - polygon(X - 1e-7, Lx)) / 2e-7; },
                                1.0);
    std::printf("| %g | %.4f | %.3e | %.4f |\n", L, cL, cL * scale * scale,
                j1(eps, cL * scale * scale, L));
  }
}
