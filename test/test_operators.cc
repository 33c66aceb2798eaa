// The estimator's reconstruction operators (doc/method.md §7): R_i / R_h, the patch
// lift I_2h, the directional lift I_2h,i on isotropic and anisotropic meshes, the Radau
// reconstruction E_tau, and the exact goal values.
#include "adaptivity/spatial_operators.h"
#include "adaptivity/temporal_reconstruction.h"
#include "config/parameters.h"
#include "goal/goal.h"
#include "scene/scene.h"
#include "study/options.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

using namespace anisodwr;
using namespace dealii;

namespace
{
using Poly = std::function<double(const Point<2> &)>;

/// x^a y^b plus lower-order terms.
Poly poly(unsigned int a, unsigned int b)
{
  return [a, b](const Point<2> &x)
  {
    return std::pow(x[0] - 0.3, a) * std::pow(x[1] + 0.2, b) +
           0.7 * std::pow(x[0], a / 2) - 0.4 * x[1];
  };
}

} // namespace

// (outside the anonymous namespace: the test fixture below, which gtest derives global
// classes from, takes it as a parameter type; -Wsubobject-linkage otherwise)
enum class MeshKind
{
  isotropic,
  aniso_x,
  aniso_y,
  mixed
};

namespace
{

/// Meshes on a rectangle (0,2)x(0,1) made of 2x1 coarse cells.
void make_mesh(Triangulation<2> &tria, MeshKind kind)
{
  GridGenerator::subdivided_hyper_rectangle(tria, {2, 1}, Point<2>(0, 0), Point<2>(2, 1));
  tria.refine_global(1);
  for (auto &cell : tria.active_cell_iterators())
  {
    if (kind == MeshKind::isotropic)
      cell->set_refine_flag();
    else if (kind == MeshKind::aniso_x)
      cell->set_refine_flag(RefinementCase<2>::cut_x);
    else if (kind == MeshKind::aniso_y)
      cell->set_refine_flag(RefinementCase<2>::cut_y);
    else
      cell->set_refine_flag(cell->center()[0] < 1 ? RefinementCase<2>::cut_x
                                                  : RefinementCase<2>::cut_xy);
  }
  tria.execute_coarsening_and_refinement();
}

struct MeshSetup
{
  Triangulation<2> tria;
  MappingQ<2> mapping{1};
  FE_Q<2> fe;
  DoFHandler<2> dofs;
  MeshSetup(MeshKind kind, unsigned int p) : fe(p), dofs(tria)
  {
    make_mesh(tria, kind);
    dofs.distribute_dofs(fe);
  }
  Vector<double> interpolate(const Poly &f) const
  {
    Vector<double> u(dofs.n_dofs());
    VectorTools::interpolate(mapping, dofs, ScalarFunctionFromFunctionObject<2>(f), u);
    return u;
  }
};

/// max over W support points of |local - f|.
double error_on_cell(const SpatialOperators<2> &ops, const Mapping<2> &mapping,
                     const DoFHandler<2>::active_cell_iterator &cell,
                     const Vector<double> &w, const Poly &f)
{
  double e = 0;
  const auto &pts = ops.weight_element().get_unit_support_points();
  for (unsigned int m = 0; m < pts.size(); ++m)
    e = std::max(e,
                 std::abs(w(m) - f(mapping.transform_unit_to_real_cell(cell, pts[m]))));
  return e;
}
} // namespace

class Lifts : public ::testing::TestWithParam<std::tuple<MeshKind, unsigned int>>
{
};

TEST_P(Lifts, DirectionalLiftReproducesDegree2pAlongI)
{
  const auto [kind, p] = GetParam();
  MeshSetup s(kind, p);
  const SpatialOperators<2> ops(s.dofs, 2 * p);
  for (unsigned int i = 0; i < 2; ++i)
  {
    const Poly v = i == 0 ? poly(2 * p, p) : poly(p, 2 * p);
    const Vector<double> u = s.interpolate(v);
    unsigned int with_patch = 0;
    for (const auto &cell : s.dofs.active_cell_iterators())
    {
      const LocalMap lift = ops.directional_lift(cell, i);
      if (!lift.exists)
        continue;
      ++with_patch;
      Vector<double> w;
      lift.apply(u, w);
      EXPECT_LT(error_on_cell(ops, s.mapping, cell, w, v), 1e-10)
          << "direction " << i << ", cell " << cell->center();
    }
    EXPECT_EQ(with_patch, s.tria.n_active_cells()) << "every cell has a 1D patch here";
  }
}

TEST_P(Lifts, DirectionalLiftOfDegreePAlongIIsIdentity)
{
  const auto [kind, p] = GetParam();
  MeshSetup s(kind, p);
  const SpatialOperators<2> ops(s.dofs, 2 * p);
  const FullMatrix<double> P = ops.interpolation_from(s.fe);
  for (unsigned int i = 0; i < 2; ++i)
  {
    // degree p along i, anything (here random nodal values) across
    const Vector<double> u = s.interpolate(i == 0 ? poly(p, 3 * p) : poly(3 * p, p));
    std::vector<types::global_dof_index> idx(s.fe.n_dofs_per_cell());
    for (const auto &cell : s.dofs.active_cell_iterators())
    {
      const LocalMap lift = ops.directional_lift(cell, i);
      ASSERT_TRUE(lift.exists);
      Vector<double> w, loc(idx.size()), pu(P.m());
      lift.apply(u, w);
      cell->get_dof_indices(idx);
      for (unsigned int l = 0; l < idx.size(); ++l)
        loc(l) = u(idx[l]);
      P.vmult(pu, loc);
      w -= pu;
      EXPECT_LT(w.linfty_norm(), 1e-10) << "direction " << i;
    }
  }
}

TEST_P(Lifts, PatchLiftReproducesPolynomialsOfThePatch)
{
  const auto [kind, p] = GetParam();
  if (kind == MeshKind::mixed)
    return; // patches of different kinds: covered by the pure meshes
  MeshSetup s(kind, p);
  const SpatialOperators<2> ops(s.dofs, 2 * p);
  // isotropic patches: Q_2p; cut_x patches: 2p in x, p in y; cut_y: p in x, 2p in y
  const Poly v = kind == MeshKind::isotropic ? poly(2 * p, 2 * p)
                 : kind == MeshKind::aniso_x ? poly(2 * p, p)
                                             : poly(p, 2 * p);
  const Vector<double> u = s.interpolate(v);
  for (const auto &cell : s.dofs.active_cell_iterators())
  {
    const LocalMap lift = ops.patch_lift(cell);
    ASSERT_TRUE(lift.exists);
    Vector<double> w;
    lift.apply(u, w);
    EXPECT_LT(error_on_cell(ops, s.mapping, cell, w, v), 1e-10);
  }
  // and a degree beyond the patch's is not reproduced (the test can fail)
  const Poly too_high = poly(2 * p + 1, 2 * p + 1);
  const Vector<double> u2 = s.interpolate(too_high);
  double worst = 0;
  for (const auto &cell : s.dofs.active_cell_iterators())
  {
    Vector<double> w;
    ops.patch_lift(cell).apply(u2, w);
    worst = std::max(worst, error_on_cell(ops, s.mapping, cell, w, too_high));
  }
  EXPECT_GT(worst, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(
    Meshes, Lifts,
    ::testing::Combine(::testing::Values(MeshKind::isotropic, MeshKind::aniso_x,
                                         MeshKind::aniso_y, MeshKind::mixed),
                       ::testing::Values(1u, 2u)));

TEST(Restriction, ProjectionsThatKeepDegreePAlongI)
{
  for (unsigned int p : {1u, 2u})
  {
    MeshSetup s(MeshKind::mixed, 2 * p);
    // s.dofs holds FE_Q(2p); the operators need a degree-p primal DoFHandler
    FE_Q<2> fe_p(p);
    DoFHandler<2> dofs_p(s.tria);
    dofs_p.distribute_dofs(fe_p);
    const SpatialOperators<2> ops(dofs_p, 2 * p);
    const unsigned int n = ops.weight_element().n_dofs_per_cell();
    for (unsigned int i = 0; i <= 2; ++i)
    {
      FullMatrix<double> RR(n, n);
      ops.restriction(i).mmult(RR, ops.restriction(i));
      RR.add(-1., ops.restriction(i));
      EXPECT_LT(RR.frobenius_norm(), 1e-12) << "R_" << i << " is a projection";
    }
    // R_x keeps degree p in x (any degree in y) and maps x^2p to its degree-p
    // interpolant in x; R_h = R_x R_y
    const auto &pts = ops.weight_element().get_unit_support_points();
    Vector<double> keep(n), high(n), out(n);
    for (unsigned int m = 0; m < n; ++m)
    {
      keep(m) = std::pow(pts[m][0], p) * std::pow(pts[m][1], 2 * p);
      high(m) = std::pow(pts[m][0], 2 * p);
    }
    ops.restriction(0).vmult(out, keep);
    out -= keep;
    EXPECT_LT(out.linfty_norm(), 1e-12);
    ops.restriction(0).vmult(out, high);
    const QGaussLobatto<1> gl(p + 1);
    for (unsigned int m = 0; m < n; ++m)
    {
      std::vector<double> nodes;
      for (unsigned int a = 0; a < gl.size(); ++a)
        nodes.push_back(gl.point(a)[0]);
      double interp = 0;
      for (unsigned int a = 0; a < nodes.size(); ++a)
        interp += std::pow(nodes[a], 2 * p) * lagrange(nodes, a, pts[m][0]);
      EXPECT_NEAR(out(m), interp, 1e-12);
    }
    FullMatrix<double> Rxy(n, n);
    ops.restriction(0).mmult(Rxy, ops.restriction(1));
    Rxy.add(-1., ops.restriction(2));
    EXPECT_LT(Rxy.frobenius_norm(), 1e-12);
  }
}

TEST(Restriction, CellwiseApplicationStaysInTheFiniteElementSpace)
{
  // applied cell by cell to a continuous z in V_h^2p, then hanging-node constraints:
  // the result is a V_h^2p function that agrees with the cell-wise R_i z on every cell
  // without hanging faces (on a conforming mesh: on every cell, i.e. the cell-wise
  // results are continuous, and R_i is then a projection globally).
  for (MeshKind kind : {MeshKind::isotropic, MeshKind::mixed})
    for (unsigned int p : {1u, 2u})
    {
      MeshSetup s(kind, 2 * p);
      FE_Q<2> fe_p(p);
      DoFHandler<2> dofs_p(s.tria);
      dofs_p.distribute_dofs(fe_p);
      const SpatialOperators<2> ops(dofs_p, 2 * p);
      const unsigned int n = ops.weight_element().n_dofs_per_cell();
      AffineConstraints<double> hanging;
      DoFTools::make_hanging_node_constraints(s.dofs, hanging);
      hanging.close();
      std::mt19937 gen(5);
      std::uniform_real_distribution<double> dist(-1, 1);
      Vector<double> z(s.dofs.n_dofs());
      for (auto &v : z)
        v = dist(gen);
      hanging.distribute(z);
      std::vector<types::global_dof_index> idx(n);
      auto apply_global = [&](unsigned int i, const Vector<double> &in)
      {
        Vector<double> outg(in.size()), loc(n), r(n);
        for (const auto &cell : s.dofs.active_cell_iterators())
        {
          cell->get_dof_indices(idx);
          for (unsigned int l = 0; l < n; ++l)
            loc(l) = in(idx[l]);
          ops.restriction(i).vmult(r, loc);
          for (unsigned int l = 0; l < n; ++l)
            outg(idx[l]) = r(l);
        }
        hanging.distribute(outg);
        return outg;
      };
      for (unsigned int i = 0; i <= 2; ++i)
      {
        const Vector<double> Rz = apply_global(i, z);
        if (kind == MeshKind::isotropic)
        {
          Vector<double> RRz = apply_global(i, Rz);
          RRz -= Rz;
          EXPECT_LT(RRz.linfty_norm(), 1e-12) << "global R_" << i << " is a projection";
        }
        for (const auto &cell : s.dofs.active_cell_iterators())
        {
          bool hanging_face = false;
          for (unsigned int f = 0; f < 4; ++f)
            hanging_face |= !cell->at_boundary(f) && (cell->face(f)->has_children() ||
                                                      cell->neighbor_is_coarser(f));
          if (hanging_face)
            continue;
          Vector<double> loc(n), r(n);
          cell->get_dof_indices(idx);
          for (unsigned int l = 0; l < n; ++l)
            loc(l) = z(idx[l]);
          ops.restriction(i).vmult(r, loc);
          for (unsigned int l = 0; l < n; ++l)
            EXPECT_NEAR(Rz(idx[l]), r(l), 1e-12);
        }
      }
    }
}

TEST(RadauReconstruction, ReproducesDegreeRPlusOneAndIsContinuous)
{
  for (unsigned int r : {0u, 1u, 2u, 3u})
  {
    const TemporalBasis basis(r);
    const TemporalReconstruction E(basis);
    // v(s) = sum_j c_j s^j of degree r+1
    auto v = [r](double s)
    {
      double x = 0;
      for (unsigned int j = 0; j <= r + 1; ++j)
        x += (1. + 0.3 * j) * std::pow(s, j) * (j % 2 ? -1 : 1);
      return x;
    };
    auto dv = [r](double s)
    {
      double x = 0;
      for (unsigned int j = 1; j <= r + 1; ++j)
        x += (1. + 0.3 * j) * j * std::pow(s, j - 1) * (j % 2 ? -1 : 1);
      return x;
    };
    for (double s : {0., 0.13, 0.5, 0.77, 1.})
    {
      // primal: data v(s_k) at the right Radau nodes and v(0)
      const auto cp = E.primal(s), dp = E.primal(s, true);
      double ep = cp.outside * v(0.), dep = dp.outside * v(0.);
      for (unsigned int k = 0; k <= r; ++k)
      {
        ep += cp.slab[k] * v(basis.nodes()[k]);
        dep += dp.slab[k] * v(basis.nodes()[k]);
      }
      EXPECT_NEAR(ep, v(s), 1e-12) << "r = " << r;
      EXPECT_NEAR(dep, dv(s), 1e-10) << "r = " << r;
      // adjoint: z is the degree-r Lagrange interpolant at the right Radau nodes of a
      // degree-(r+1) v that equals it at the left Radau nodes: take v = z + c * w, w
      // vanishing at the left Radau nodes; E z must then reproduce v with z(1^+) = v(1).
      // Simplest check: for z of degree r and z(1^+) = z(1), E z = z.
      const auto ca = E.adjoint(s);
      auto zf = [](double x) { return 0.4 - 1.3 * x; };
      std::vector<double> Zk;
      for (unsigned int k = 0; k <= r; ++k)
        Zk.push_back(r == 0 ? zf(1.) : zf(basis.nodes()[k]));
      double ez = ca.outside * (r == 0 ? zf(1.) : zf(1.));
      for (unsigned int k = 0; k <= r; ++k)
        ez += ca.slab[k] * Zk[k];
      if (r > 0)
      {
        EXPECT_NEAR(ez, zf(s), 1e-12) << "adjoint reconstruction, r = " << r;
      }
    }
    // continuity: E u(0) = outside value, E u(1) = U_r; E z(1) = outside, E z(0) = z(0^+)
    const auto p0 = E.primal(0.), p1 = E.primal(1.), a1 = E.adjoint(1.),
               a0 = E.adjoint(0.);
    EXPECT_NEAR(p0.outside, 1., 1e-14);
    EXPECT_NEAR(p1.slab[r], 1., 1e-14);
    EXPECT_NEAR(a1.outside, 1., 1e-14);
    for (unsigned int k = 0; k <= r; ++k)
      EXPECT_NEAR(a0.slab[k], basis.left_trace()[k], 1e-12);
  }
}

TEST(ExactGoal, MovingHumpToTenDigits)
{
  const auto scene =
      create_scene<2>(Parameters::from_overrides({"scene.name=moving_hump"}));
  for (const auto &g : scene->default_goals(0.01))
  {
    const double J = exact_goal(*scene, g);
    // independent: a fine tensor Gauss rule over the mollifier's square support,
    // 16-point Gauss on 200 x 200 sub-squares
    const QIterated<1> q(QGauss<1>(16), 200);
    const Point<2> c(g.location[0], g.location[1]);
    const double s = g.radius, C = mollifier_constant(2, s);
    double ref = 0;
    for (unsigned int i = 0; i < q.size(); ++i)
      for (unsigned int j = 0; j < q.size(); ++j)
      {
        const Point<2> x(c[0] - s + 2 * s * q.point(i)[0],
                         c[1] - s + 2 * s * q.point(j)[0]);
        ref += 4 * s * s * q.weight(i) * q.weight(j) * mollifier(x, c, s, C) *
               scene->exact()->value(x, scene->end_time);
      }
    EXPECT_NEAR(J, ref, 1e-10 * std::abs(ref)) << g.name;
    EXPECT_GT(std::abs(J), 0.1);
  }
}
