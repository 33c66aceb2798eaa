// goal.kind = flux: the diffusive flux through Dirichlet boundaries Gamma over I,
//   J(u) = int_I int_Gamma eps grad u . n ds dt   (n: the domain's outer normal),
// in the variational form of Babuska and Miller: with psi = 1 on the vertices of Gamma
// and 0 on all other vertices (bilinear on each cell, so psi is in every Q_p space on
// the mesh), Green's formula and the PDE give, for the exact solution,
//   J(u) = (u(T) - u_0, psi) + int_I a(u)(psi) - (f, psi) - <g_N, psi>_{Gamma_N} dt,
//   a(u)(psi) = (eps grad u, grad psi) + (b.grad u + alpha u, psi),
// an affine goal with j_t = a(.)(psi), j_T = (., psi) and a constant from the data. Its
// error converges like the energy error squared, not like the gradient's. Faces of
// other boundaries that touch Gamma at a corner carry psi over one cell, so a flux over
// a closed curve (a hole) or the whole boundary is exact; on a part of the boundary the
// corner cells add a term that vanishes with h.
#include "base/errors.h"
#include "base/nested_quadrature.h"
#include "goal/goal_type.h"
#include "scene/scene.h"
#include "space/space.h"
#include "space/weak_form.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <set>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// The boundary ids of a flux goal's Gamma (GoalSpec::location).
std::vector<unsigned int> boundary_ids(const GoalSpec &g)
{
  return std::vector<unsigned int>(g.location.begin(), g.location.end());
}
using Cell = Triangulation<2>::active_cell_iterator;

/// The values of psi at the vertices of `tria`: 1 on the boundary faces with an id of
/// `ids`, 0 elsewhere, and at a hanging vertex the mean of the two ends of the coarse
/// face it halves (so that psi is continuous and lies in the constrained space).
std::vector<double> vertex_values(const Triangulation<2> &tria,
                                  const std::vector<unsigned int> &ids)
{
  std::vector<double> value(tria.n_vertices(), 0.);
  const std::set<unsigned int> gamma(ids.begin(), ids.end());
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary() && gamma.count(face->boundary_id()))
        for (unsigned int v = 0; v < GeometryInfo<2>::vertices_per_face; ++v)
          value[face->vertex_index(v)] = 1.;
  // hanging vertices, coarse faces first
  for (unsigned int sweep = 0; sweep < 2; ++sweep)
    for (const auto &cell : tria.active_cell_iterators())
      for (unsigned int f = 0; f < GeometryInfo<2>::faces_per_cell; ++f)
        if (!cell->at_boundary(f) && cell->neighbor_is_coarser(f))
        {
          const auto coarse = cell->neighbor(f)->face(cell->neighbor_of_coarser_neighbor(f).first);
          const double mean =
              0.5 * (value[coarse->vertex_index(0)] + value[coarse->vertex_index(1)]);
          for (unsigned int v = 0; v < GeometryInfo<2>::vertices_per_face; ++v)
          {
            const unsigned int i = cell->face(f)->vertex_index(v);
            if (i != coarse->vertex_index(0) && i != coarse->vertex_index(1))
              value[i] = mean;
          }
        }
  return value;
}

/// The outer unit normal of the straight face f of `cell`.
template <class Iterator> Tensor<1, 2> outer_normal(const Iterator &cell, unsigned int f)
{
  const Point<2> a = cell->face(f)->vertex(0), b = cell->face(f)->vertex(1);
  Tensor<1, 2> n({b[1] - a[1], a[0] - b[0]});
  n /= n.norm();
  return n * (cell->face(f)->center() - cell->center()) > 0 ? n : -n;
}

/// psi on the cells that touch Gamma: the sum of the bilinear hat functions of the
/// cell's vertices on Gamma, at the points of `q`.
class Extension
{
public:
  Extension(const Triangulation<2> &tria, const std::vector<unsigned int> &ids,
            const Mapping<2> &mapping, const Quadrature<2> &q)
      : value(vertex_values(tria, ids)), q1(1),
        values(mapping, q1, q, update_values | update_gradients)
  {
  }
  /// Whether psi is nonzero on `cell`; then psi and grad psi at the points.
  bool reinit(const Cell &cell)
  {
    bool touches = false;
    for (unsigned int v = 0; v < GeometryInfo<2>::vertices_per_cell; ++v)
      touches |= value[cell->vertex_index(v)] != 0.;
    if (!touches)
      return false;
    values.reinit(cell);
    const unsigned int n = values.n_quadrature_points;
    psi.assign(n, 0.);
    grad_psi.assign(n, Tensor<1, 2>());
    // FE_Q(1) numbers its shape functions as the cell's vertices
    for (unsigned int v = 0; v < GeometryInfo<2>::vertices_per_cell; ++v)
      if (const double c = value[cell->vertex_index(v)]; c != 0.)
        for (unsigned int k = 0; k < n; ++k)
        {
          psi[k] += c * values.shape_value(v, k);
          grad_psi[k] += c * values.shape_grad(v, k);
        }
    return true;
  }
  std::vector<double> psi;
  std::vector<Tensor<1, 2>> grad_psi;
  /// psi at the vertices of the mesh
  const std::vector<double> value;

private:
  FE_Q<2> q1;
  FEValues<2> values;
};

/// j_t(phi) = a(phi)(psi) (over I) or j_T(phi) = (phi, psi) (at T).
class FluxPart : public GoalPart<2>
{
public:
  FluxPart(const GoalSpec &g, const Scene<2> &scene, const Mapping<2> &mapping,
           const FiniteElement<2> &fe, const Triangulation<2> &tria, bool stiffness)
      : scene(scene), stiffness(stiffness), q(fe.degree + 2),
        extension(tria, boundary_ids(g), mapping, q),
        values(mapping, fe, q,
               update_values | update_gradients | update_quadrature_points |
                   update_JxW_values)
  {
  }
  bool add_cell_vector(const Cell &cell, double weight, Vector<double> &j) const override
  {
    if (!extension.reinit(cell))
      return false;
    values.reinit(cell);
    for (unsigned int k = 0; k < q.size(); ++k)
    {
      const double psi = extension.psi[k];
      const Tensor<1, 2> &grad_psi = extension.grad_psi[k];
      const auto c = weak_form::coefficients(scene, values.quadrature_point(k), 0.);
      const double w = weight * values.JxW(k);
      for (unsigned int l = 0; l < j.size(); ++l)
        j(l) += w * (stiffness ? weak_form::galerkin(c, values.shape_value(l, k),
                                                     values.shape_grad(l, k), psi, grad_psi)
                               : values.shape_value(l, k) * psi);
    }
    return true;
  }

private:
  const Scene<2> &scene;
  bool stiffness;
  QGauss<2> q;
  mutable Extension extension;
  mutable FEValues<2> values;
};

class FluxGoal : public GoalType
{
public:
  std::string name() const override { return "flux"; }
  std::string doc() const override
  {
    return "the diffusive flux int_I int_Gamma eps grad u . n ds dt through the Dirichlet "
           "boundary ids 'id,id,...; ...' of goal.locations (one goal per group; over I "
           "only, goal.over_time = true), in the variational form of Babuska and Miller";
  }
  std::string noun() const override { return "boundary id list"; }
  std::string syntax() const override { return "id,id,..."; }
  std::string example() const override { return "0"; }
  unsigned int n_numbers() const override { return 0; }

  void set_location(const std::vector<double> &v, const Scene<2> &scene,
                    const std::string &bad, GoalSpec &g) const override
  {
    std::string dirichlet;
    for (const auto id : scene.dirichlet_ids)
      dirichlet += (dirichlet.empty() ? "" : ", ") + std::to_string(id);
    g.location.clear();
    for (const double x : v)
    {
      // the rule of scene.dirichlet and scene.neumann: any id of deal.II's range
      if (!(x >= 0 && x == std::floor(x) && x < double(numbers::internal_face_boundary_id)))
        throw InputError(bad + "a boundary id is an integer in [0, " +
                         std::to_string(numbers::internal_face_boundary_id) + ")");
      const auto id = static_cast<types::boundary_id>(x);
      if (!scene.dirichlet_ids.count(id))
        throw InputError(bad + "boundary id " + std::to_string(id) +
                         (scene.neumann_ids.count(id)
                              ? " is a Neumann boundary, whose flux is its data"
                              : " is not a boundary of the domain") +
                         "; expected Dirichlet ids of scene '" + scene.name() + "' (" +
                         dirichlet + ")");
      g.location.push_back(id);
    }
    if (!g.over_time)
      throw InputError(bad + "a flux goal is integrated over I; set goal.over_time = "
                             "true (scene.goals_over_time for scene.goals)");
    if (scene.coefficients_depend_on_time())
      throw InputError(bad + "flux goals need coefficients constant in time; scene '" +
                       scene.name() + "' has time-dependent ones");
  }

  std::unique_ptr<GoalPart<2>> part(const GoalSpec &g, const Scene<2> &scene,
                                    const Mapping<2> &mapping, const FiniteElement<2> &fe,
                                    const Triangulation<2> &tria,
                                    bool over_time) const override
  {
    return std::make_unique<FluxPart>(g, scene, mapping, fe, tria, over_time);
  }

  /// -(u_0, psi) - int_I (f, psi) - <g_N, psi>_{Gamma_N} dt (Neumann faces: straight),
  /// the integrals over I by
  /// composite 8-point Gauss on 16 panels.
  double offset(const Space<2> &space, const GoalSpec &g) const override;

  /// int_Gamma eps grad u(t) . n ds over the coarse grid's faces of Gamma (straight).
  double exact_value(const Scene<2> &scene, const GoalSpec &g, double t,
                     nested::NestedIntegrals &n) const override
  {
    const auto *u = scene.exact();
    Triangulation<2> coarse;
    scene.make_coarse_grid(coarse);
    const std::vector<unsigned int> ids = boundary_ids(g);
    const std::set<unsigned int> gamma(ids.begin(), ids.end());
    double J = 0;
    for (const auto &cell : coarse.active_cell_iterators())
      for (unsigned int f = 0; f < GeometryInfo<2>::faces_per_cell; ++f)
        if (cell->face(f)->at_boundary() && gamma.count(cell->face(f)->boundary_id()))
        {
          if (cell->face(f)->manifold_id() != numbers::flat_manifold_id)
            throw InputError(
                "goal '" + g.name + "' (a flux through boundary id " +
                std::to_string(cell->face(f)->boundary_id()) +
                ", which is curved: it carries a manifold) has no exact value: the exact "
                "flux is integrated over straight faces only; expected a flux goal on "
                "straight boundaries, or no scene.exact_solution");
          const Point<2> a = cell->face(f)->vertex(0), b = cell->face(f)->vertex(1);
          const Tensor<1, 2> normal = outer_normal(cell, f);
          const double length = a.distance(b);
          J += n.outer(
              [&](double s)
              { return scene.epsilon * (u->gradient(a + s * (b - a), t) * normal) * length; },
              0., 1.);
        }
    return J;
  }

  bool weight_accepted(const GoalSpec &, const Scene<2> &, double) const override
  {
    return true; // psi lives on the mesh: nothing to resolve
  }
  std::string unresolved(const Space<2> &, const GoalSpec &, const GoalInput &,
                         const Scene<2> &, const std::string &) const override
  {
    return "";
  }
};

double FluxGoal::offset(const Space<2> &space, const GoalSpec &g) const
{
  const Scene<2> &scene = space.scene;
  const QGauss<2> q(space.degree() + 3);
  const QGauss<1> qf(space.degree() + 3);
  const QIterated<1> qt(QGauss<1>(8), 16);
  const auto &tria = space.dof_handler().get_triangulation();
  Extension extension(tria, boundary_ids(g), space.mapping(), q);
  FEValues<2> values(space.mapping(), space.finite_element(), q,
                     update_quadrature_points | update_JxW_values);
  const double T = scene.end_time;
  double c = 0;
  for (const auto &cell : tria.active_cell_iterators())
  {
    if (!extension.reinit(cell))
      continue;
    values.reinit(cell);
    for (unsigned int k = 0; k < q.size(); ++k)
    {
      const Point<2> &x = values.quadrature_point(k);
      double f = 0;
      for (unsigned int i = 0; i < qt.size(); ++i)
        f += qt.weight(i) * T * scene.rhs(x, qt.point(i)[0] * T);
      c -= (scene.initial_value(x) + f) * extension.psi[k] * values.JxW(k);
    }
    for (unsigned int fi = 0; fi < GeometryInfo<2>::faces_per_cell; ++fi)
    {
      const auto face = cell->face(fi);
      if (!face->at_boundary() || !scene.neumann_ids.count(face->boundary_id()))
        continue;
      const Point<2> a = face->vertex(0), b = face->vertex(1);
      const Tensor<1, 2> normal = outer_normal(cell, fi);
      for (unsigned int k = 0; k < qf.size(); ++k)
      {
        const double s = qf.point(k)[0];
        const double psi = (1. - s) * extension.value[face->vertex_index(0)] +
                           s * extension.value[face->vertex_index(1)];
        if (psi == 0.)
          continue;
        const Point<2> x = a + s * (b - a);
        double gN = 0;
        for (unsigned int i = 0; i < qt.size(); ++i)
          gN += qt.weight(i) * T *
                scene.boundary_flux(x, normal, qt.point(i)[0] * T, face->boundary_id());
        c -= gN * psi * qf.weight(k) * a.distance(b);
      }
    }
  }
  return c;
}
} // namespace

const GoalType &flux_goal()
{
  static const FluxGoal type;
  return type;
}
} // namespace anisodwr
