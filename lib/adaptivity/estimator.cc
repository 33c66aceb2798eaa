#include "adaptivity/estimator.h"

#include "adaptivity/spatial_operators.h"
#include "adaptivity/temporal_reconstruction.h"
#include "time/slab_vector.h"

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/numerics/matrix_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>

namespace anisodwr
{
using namespace dealii;

namespace
{
/// Linear functionals on W-local coefficients at the r+2 temporal Gauss points of a
/// slab and at t_{n-1}^+:
///   value(v) = sum_m (val[m] . v(g_m) + dt[m] . d_t v(g_m)) + jump . w(t_{n-1}^+)
/// (for rho and S the "jump" slot multiplies the weight at t_{n-1}^+; for A and S' it
/// multiplies the jump v^+ - v^- of the primal-slot function).
struct SlabFunctional
{
  std::vector<Vector<double>> val, dt;
  Vector<double> jump;
  /// Zeroes the functional; reallocates only when the sizes change.
  void reset(unsigned int n_points, unsigned int n)
  {
    if (val.size() != n_points || jump.size() != n)
    {
      val.assign(n_points, Vector<double>(n));
      dt.assign(n_points, Vector<double>(n));
      jump.reinit(n);
      return;
    }
    for (auto &v : val)
      v = 0.;
    for (auto &v : dt)
      v = 0.;
    jump = 0.;
  }
};

/// A function of time on one slab in W-local coefficients: values and time
/// derivatives at the Gauss points, the value at t_{n-1}^+ and (for jumps) at t_{n-1}^-.
struct SlabFunction
{
  std::vector<Vector<double>> val, dt;
  Vector<double> plus, minus;
};

double apply(const SlabFunctional &F, const SlabFunction &v, bool jump_of_v)
{
  double s = 0;
  for (unsigned int m = 0; m < F.val.size(); ++m)
  {
    s += F.val[m] * v.val[m];
    if (v.dt.size())
      s += F.dt[m] * v.dt[m];
  }
  s += F.jump * v.plus;
  if (jump_of_v && v.minus.size())
    s -= F.jump * v.minus;
  return s;
}

/// The cell integrals of SPEC §5 on one cell and one slab.
template <int dim> class CellKernel
{
public:
  using cell_iterator = typename DoFHandler<dim>::active_cell_iterator;

  CellKernel(const Space<dim> &primal, const FE_Q<dim> &fe_w, const TemporalBasis &basis)
      : primal(primal), scene(primal.scene), fe_p(primal.finite_element()), fe_w(fe_w),
        basis(basis), quad(fe_w.degree + 2), fquad(fe_w.degree + 2),
        fv_p(primal.mapping(), fe_p, quad,
             update_values | update_gradients | update_hessians |
                 update_quadrature_points | update_JxW_values),
        fv_w(primal.mapping(), fe_w, quad,
             update_values | update_gradients | update_hessians),
        ff_p(primal.mapping(), fe_p, fquad,
             update_gradients | update_normal_vectors | update_quadrature_points |
                 update_JxW_values),
        ff_w(primal.mapping(), fe_w, fquad, update_values),
        fs_p(primal.mapping(), fe_p, fquad,
             update_gradients | update_normal_vectors | update_quadrature_points |
                 update_JxW_values),
        fs_w(primal.mapping(), fe_w, fquad, update_values),
        fn_p(primal.mapping(), fe_p, fquad, update_gradients | update_quadrature_points),
        fns_p(primal.mapping(), fe_p, fquad, update_gradients | update_quadrature_points),
        constant_coefficients(!scene.coefficients_depend_on_time())
  {
    gauss_rule(basis.n_dofs() + 1, g, omega);
    for (double s : g)
    {
      ell.push_back(basis.values(s));
      std::vector<double> d(basis.n_dofs());
      for (unsigned int k = 0; k < basis.n_dofs(); ++k)
        d[k] = basis.derivative(k, s);
      dell.push_back(d);
    }
  }

  unsigned int n_points() const { return g.size(); }
  double point(unsigned int m) const { return g[m]; }
  const std::vector<double> &values_at(unsigned int m) const { return ell[m]; }
  const std::vector<double> &derivatives_at(unsigned int m) const { return dell[m]; }

  void reinit(const cell_iterator &cell)
  {
    K = cell;
    fv_p.reinit(cell);
    fv_w.reinit(typename Triangulation<dim>::cell_iterator(cell));
    delta_h = primal.unbounded_delta(cell);
    if (constant_coefficients)
      build_adjoint_matrices();
    idx.resize(fe_p.n_dofs_per_cell());
    cell->get_dof_indices(idx);
    pieces.clear();
    for (unsigned int f = 0; f < GeometryInfo<dim>::faces_per_cell; ++f)
    {
      if (cell->at_boundary(f))
      {
        ff_p.reinit(cell, f);
        ff_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f);
        const auto id = cell->face(f)->boundary_id();
        add_piece(ff_p, ff_w, nullptr, {}, scene.neumann_ids.count(id) ? 1 : 2);
      }
      else if (cell->face(f)->has_children())
      {
        const unsigned int nn = cell->neighbor_of_neighbor(f);
        for (unsigned int sf = 0; sf < cell->face(f)->n_children(); ++sf)
        {
          const auto nb = cell->neighbor_child_on_subface(f, sf);
          fs_p.reinit(cell, f, sf);
          fs_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f, sf);
          fn_p.reinit(nb, nn);
          add_piece(fs_p, fs_w, &fn_p, dofs_of(nb), 0);
        }
      }
      else if (cell->neighbor_is_coarser(f))
      {
        const auto nb = cell->neighbor(f);
        const auto [nf, nsf] = cell->neighbor_of_coarser_neighbor(f);
        ff_p.reinit(cell, f);
        ff_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f);
        fns_p.reinit(nb, nf, nsf);
        add_piece(ff_p, ff_w, &fns_p, dofs_of(nb), 0);
      }
      else
      {
        const auto nb = cell->neighbor(f);
        ff_p.reinit(cell, f);
        ff_w.reinit(typename Triangulation<dim>::cell_iterator(cell), f);
        fn_p.reinit(nb, cell->neighbor_of_neighbor(f));
        add_piece(ff_p, ff_w, &fn_p, dofs_of(nb), 0);
      }
    }
  }

  const std::vector<types::global_dof_index> &dof_indices() const { return idx; }

  /// rho(u)(.) and S(u)(.) on slab (t0, t0+tau] for u = U_n (interleaved), with
  /// u(t_{n-1}^-) from U_prev's last node or, if null, from u_0.
  void primal_functionals(double t0, double tau, const Vector<double> &Un,
                          const Vector<double> *Uprev, SlabFunctional &rho,
                          SlabFunctional &supg) const
  {
    const unsigned int nw = fe_w.n_dofs_per_cell(), np = fe_p.n_dofs_per_cell();
    const unsigned int m1 = basis.n_dofs(), nq = quad.size();
    rho.reset(g.size(), nw);
    supg.reset(g.size(), nw);
    const double eps = scene.epsilon, delta = primal.bounded_delta(delta_h, tau);
    Vector<double> &c = scratch[0], &ct = scratch[1], &cn = scratch[2];
    c.reinit(np, true);
    ct.reinit(np, true);
    for (unsigned int m = 0; m < g.size(); ++m)
    {
      const double t = t0 + g[m] * tau, wt = tau * omega[m];
      combine(Un, idx, ell[m], 1., c);
      combine(Un, idx, dell[m], 1. / tau, ct);
      for (unsigned int q = 0; q < nq; ++q)
      {
        const Point<dim> &x = fv_p.quadrature_point(q);
        double uh = 0, ut = 0, lap = 0;
        Tensor<1, dim> grad;
        for (unsigned int l = 0; l < np; ++l)
        {
          uh += c(l) * fv_p.shape_value(l, q);
          ut += ct(l) * fv_p.shape_value(l, q);
          grad += c(l) * fv_p.shape_grad(l, q);
          lap += c(l) * trace(fv_p.shape_hessian(l, q));
        }
        const Tensor<1, dim> b = scene.convection(x, t);
        const double R =
            scene.rhs(x, t) + eps * lap - ut - b * grad - scene.reaction(x, t) * uh;
        const double jx = fv_p.JxW(q) * wt;
        for (unsigned int l = 0; l < nw; ++l)
        {
          rho.val[m](l) += jx * R * fv_w.shape_value(l, q);
          supg.val[m](l) -= jx * delta * R * (b * fv_w.shape_grad(l, q));
        }
      }
      // faces: half flux jump (interior), Neumann mismatch, -eps d_n u (Dirichlet)
      for (const auto &pc : pieces)
      {
        if (pc.kind == 0)
        {
          cn.reinit(np, true);
          combine(Un, pc.nb_dofs, ell[m], 1., cn);
        }
        for (unsigned int q = 0; q < pc.JxW.size(); ++q)
        {
          double gk = 0, gn = 0;
          for (unsigned int l = 0; l < np; ++l)
            gk += c(l) * pc.gradn(l, q);
          double flux;
          if (pc.kind == 0)
          {
            for (unsigned int l = 0; l < np; ++l)
              gn += cn(l) * pc.nb_gradn(l, q);
            flux = -0.5 * eps * (gk - gn);
          }
          else if (pc.kind == 1)
            flux = scene.neumann_value(pc.x[q], pc.normal[q], t) - eps * gk;
          else
            flux = -eps * gk;
          for (unsigned int l = 0; l < nw; ++l)
            rho.val[m](l) += wt * flux * pc.JxW[q] * pc.w(l, q);
        }
      }
    }
    // temporal jump at t_{n-1}: u^+ - u^-
    Vector<double> &cp = scratch[0], &cm = scratch[1];
    cp.reinit(np, true);
    cm.reinit(np);
    combine(Un, idx, basis.left_trace(), 1., cp);
    if (Uprev)
      for (unsigned int l = 0; l < np; ++l)
        cm(l) = (*Uprev)(SlabLayout{m1}.last(idx[l]));
    for (unsigned int q = 0; q < nq; ++q)
    {
      const Point<dim> &x = fv_p.quadrature_point(q);
      double jump = Uprev ? 0. : -scene.initial_value(x);
      for (unsigned int l = 0; l < np; ++l)
        jump += (cp(l) - cm(l)) * fv_p.shape_value(l, q);
      const Tensor<1, dim> b = scene.convection(x, t0);
      for (unsigned int l = 0; l < nw; ++l)
      {
        rho.jump(l) -= fv_p.JxW(q) * jump * fv_w.shape_value(l, q);
        supg.jump(l) += fv_p.JxW(q) * delta * jump * (b * fv_w.shape_grad(l, q));
      }
    }
  }

  /// A(.)(zt) (supg == false) or S'(., y = zt) (supg == true) on the slab, for zt given
  /// in W-local coefficients at the Gauss points (val) and at t_{n-1}^+ (plus).
  void adjoint_functional(double t0, double tau, const SlabFunction &zt, bool supg,
                          SlabFunctional &A) const
  {
    const unsigned int nw = fe_w.n_dofs_per_cell(), nq = quad.size();
    A.reset(g.size(), nw);
    if (constant_coefficients)
    {
      // the same functional through the cell matrices: val = wt K z, dt = wt M z
      // (S' matrices per unit delta_K)
      const auto &Kc = supg ? adj_matrices[2] : adj_matrices[0],
                 &Mc = supg ? adj_matrices[3] : adj_matrices[1];
      const double scale = supg ? primal.bounded_delta(delta_h, tau) : 1.;
      for (unsigned int m = 0; m < g.size(); ++m)
      {
        const double wt = tau * omega[m] * scale;
        Kc.vmult(A.val[m], zt.val[m]);
        A.val[m] *= wt;
        Mc.vmult(A.dt[m], zt.val[m]);
        A.dt[m] *= wt;
      }
      Mc.vmult(A.jump, zt.plus);
      A.jump *= scale;
      return;
    }
    const double eps = scene.epsilon, delta = primal.bounded_delta(delta_h, tau);
    for (unsigned int m = 0; m <= g.size(); ++m) // m == g.size(): the jump at t_{n-1}^+
    {
      const bool jump = m == g.size();
      const double t = jump ? t0 : t0 + g[m] * tau, wt = jump ? 1. : tau * omega[m];
      const Vector<double> &z = jump ? zt.plus : zt.val[m];
      for (unsigned int q = 0; q < nq; ++q)
      {
        const Point<dim> &x = fv_p.quadrature_point(q);
        double zq = 0;
        Tensor<1, dim> gz;
        for (unsigned int l = 0; l < nw; ++l)
        {
          zq += z(l) * fv_w.shape_value(l, q);
          gz += z(l) * fv_w.shape_grad(l, q);
        }
        const Tensor<1, dim> b = scene.convection(x, t);
        const double alpha = scene.reaction(x, t), jx = wt * fv_p.JxW(q);
        // the test side: zq (A) or delta b.grad y (S')
        const double test = supg ? delta * (b * gz) : zq;
        for (unsigned int l = 0; l < nw; ++l)
        {
          const double phi = fv_w.shape_value(l, q);
          if (jump)
          {
            A.jump(l) += jx * phi * test;
            continue;
          }
          const Tensor<1, dim> &gphi = fv_w.shape_grad(l, q);
          A.dt[m](l) += jx * phi * test;
          if (supg)
            A.val[m](l) +=
                jx * (-eps * trace(fv_w.shape_hessian(l, q)) + b * gphi + alpha * phi) *
                test;
          else
            A.val[m](l) += jx * (eps * (gphi * gz) + (b * gphi + alpha * phi) * zq);
        }
      }
    }
  }

  /// J'(v) on this cell: the part over I at the Gauss points, the end part at T.
  void goal_functional(double tau, const Vector<double> &jt, SlabFunctional &J) const
  {
    J.reset(g.size(), fe_w.n_dofs_per_cell());
    if (jt.size())
      for (unsigned int m = 0; m < g.size(); ++m)
        J.val[m].add(tau * omega[m], jt);
  }

private:
  struct Piece
  {
    int kind; // 0 interior, 1 Neumann, 2 Dirichlet
    std::vector<double> JxW;
    FullMatrix<double> w, gradn, nb_gradn;
    std::vector<Point<dim>> x;
    std::vector<Tensor<1, dim>> normal;
    std::vector<types::global_dof_index> nb_dofs;
  };

  std::vector<types::global_dof_index>
  dofs_of(const typename DoFHandler<dim>::cell_iterator &c)
  {
    std::vector<types::global_dof_index> d(fe_p.n_dofs_per_cell());
    c->get_dof_indices(d);
    return d;
  }

  void add_piece(const FEFaceValuesBase<dim> &fp, const FEFaceValuesBase<dim> &fw,
                 const FEFaceValuesBase<dim> *fn, std::vector<types::global_dof_index> nb,
                 int kind)
  {
    const unsigned int nq = fp.n_quadrature_points, np = fe_p.n_dofs_per_cell(),
                       nw = fe_w.n_dofs_per_cell();
    Piece pc;
    pc.kind = kind;
    pc.nb_dofs = std::move(nb);
    pc.w.reinit(nw, nq);
    pc.gradn.reinit(np, nq);
    if (fn)
      pc.nb_gradn.reinit(np, nq);
    for (unsigned int q = 0; q < nq; ++q)
    {
      pc.JxW.push_back(fp.JxW(q));
      pc.x.push_back(fp.quadrature_point(q));
      pc.normal.push_back(fp.normal_vector(q));
      for (unsigned int l = 0; l < nw; ++l)
        pc.w(l, q) = fw.shape_value(l, q);
      for (unsigned int l = 0; l < np; ++l)
        pc.gradn(l, q) = fp.shape_grad(l, q) * fp.normal_vector(q);
      if (fn) // match the neighbour's quadrature point to ours
      {
        unsigned int qn = 0;
        double best = 1e300;
        for (unsigned int k = 0; k < nq; ++k)
          if (const double d = fn->quadrature_point(k).distance(fp.quadrature_point(q));
              d < best)
          {
            best = d;
            qn = k;
          }
        for (unsigned int l = 0; l < np; ++l)
          pc.nb_gradn(l, q) = fn->shape_grad(l, qn) * fp.normal_vector(q);
      }
    }
    pieces.push_back(std::move(pc));
  }

  /// c_l = scale * sum_k a_k U(dofs_l (r+1) + k)
  void combine(const Vector<double> &U, const std::vector<types::global_dof_index> &dofs,
               const std::vector<double> &a, double scale, Vector<double> &c) const
  {
    const SlabLayout slab{basis.n_dofs()};
    for (unsigned int l = 0; l < dofs.size(); ++l)
    {
      double s = 0;
      for (unsigned int k = 0; k < slab.m; ++k)
        s += a[k] * U(slab.index(dofs[l], k));
      c(l) = scale * s;
    }
  }

  const Space<dim> &primal;
  const Scene<dim> &scene;
  const FiniteElement<dim> &fe_p;
  const FE_Q<dim> &fe_w;
  const TemporalBasis &basis;
  QGauss<dim> quad;
  QGauss<dim - 1> fquad;
  FEValues<dim> fv_p, fv_w;
  FEFaceValues<dim> ff_p, ff_w;
  FESubfaceValues<dim> fs_p, fs_w;
  FEFaceValues<dim> fn_p;
  FESubfaceValues<dim> fns_p;
  std::vector<double> g, omega;
  std::vector<std::vector<double>> ell, dell;
  cell_iterator K;
  double delta_h = 0; // delta_K before the bound by tau_n
  std::vector<types::global_dof_index> idx;
  std::vector<Piece> pieces;
  mutable std::array<Vector<double>, 3> scratch; // cell-local coefficient buffers

  /// For coefficients constant in time, A(.)(z) and S'(., z) are cell matrices applied
  /// to z (per unit temporal weight): [0] A's val part, [1] A's dt/jump part, [2] S'
  /// val part, [3] S' dt/jump part (rows: the first slot, columns: z).
  const bool constant_coefficients;
  std::array<FullMatrix<double>, 4> adj_matrices;
  void build_adjoint_matrices()
  {
    const unsigned int nw = fe_w.n_dofs_per_cell(), nq = quad.size();
    const double eps = scene.epsilon;
    for (auto &M : adj_matrices)
      M.reinit(nw, nw);
    for (unsigned int q = 0; q < nq; ++q)
    {
      const Point<dim> &x = fv_p.quadrature_point(q);
      const Tensor<1, dim> b = scene.convection(x, 0.);
      const double alpha = scene.reaction(x, 0.), jx = fv_p.JxW(q);
      for (unsigned int l = 0; l < nw; ++l)
      {
        const double phi = fv_w.shape_value(l, q);
        const Tensor<1, dim> &gphi = fv_w.shape_grad(l, q);
        const double op = -eps * trace(fv_w.shape_hessian(l, q)) + b * gphi + alpha * phi;
        for (unsigned int j = 0; j < nw; ++j)
        {
          const double zj = fv_w.shape_value(j, q);
          const Tensor<1, dim> &gz = fv_w.shape_grad(j, q);
          const double test_s = b * gz; // per unit delta_K
          adj_matrices[0](l, j) +=
              jx * (eps * (gphi * gz) + (b * gphi + alpha * phi) * zj);
          adj_matrices[1](l, j) += jx * phi * zj;
          adj_matrices[2](l, j) += jx * op * test_s;
          adj_matrices[3](l, j) += jx * phi * test_s;
        }
      }
    }
  }
};

/// W-local coefficients of temporal node k of an interleaved slab vector.
void gather(const Vector<double> &U, const std::vector<types::global_dof_index> &dofs,
            unsigned int m1, unsigned int k, const FullMatrix<double> &to_w,
            Vector<double> &out)
{
  const SlabLayout slab{m1};
  thread_local Vector<double> loc;
  loc.reinit(dofs.size(), true);
  for (unsigned int l = 0; l < dofs.size(); ++l)
    loc(l) = U(slab.index(dofs[l], k));
  out.reinit(to_w.m(), true);
  to_w.vmult(out, loc);
}

/// f = the slab function sum_k l_k(s) V_k from W-local nodal vectors V_k (f.minus is
/// left as it is; f's vectors are reused).
template <int dim>
void slab_function(const CellKernel<dim> &kernel, const TemporalBasis &basis, double tau,
                   const std::vector<Vector<double>> &V, SlabFunction &f)
{
  const unsigned int n = V[0].size(), n_points = kernel.n_points();
  f.val.resize(n_points);
  f.dt.resize(n_points);
  for (unsigned int m = 0; m < n_points; ++m)
  {
    Vector<double> &v = f.val[m], &d = f.dt[m];
    v.reinit(n);
    d.reinit(n);
    for (unsigned int k = 0; k < V.size(); ++k)
    {
      v.add(kernel.values_at(m)[k], V[k]);
      d.add(kernel.derivatives_at(m)[k] / tau, V[k]);
    }
  }
  f.plus.reinit(n);
  for (unsigned int k = 0; k < V.size(); ++k)
    f.plus.add(basis.left_trace()[k], V[k]);
}

void transform(const FullMatrix<double> &R, SlabFunction &f)
{
  auto one = [&](Vector<double> &v)
  {
    if (!v.size())
      return;
    thread_local Vector<double> t;
    t.reinit(v.size(), true);
    R.vmult(t, v);
    v = t;
  };
  for (auto &v : f.val)
    one(v);
  for (auto &v : f.dt)
    one(v);
  one(f.plus);
  one(f.minus);
}

/// d = a - b (d's vectors are reused).
void difference(const SlabFunction &a, const SlabFunction &b, SlabFunction &d)
{
  d = a;
  for (unsigned int m = 0; m < d.val.size(); ++m)
  {
    d.val[m] -= b.val[m];
    if (d.dt.size())
      d.dt[m] -= b.dt[m];
  }
  d.plus -= b.plus;
  if (d.minus.size())
    d.minus -= b.minus;
}

template <int dim>
unsigned int weight_degree(const Space<dim> &primal, const Space<dim> &other)
{
  return std::max(other.degree(), 2 * primal.degree());
}
} // namespace

template <int dim>
Indicators<dim>
estimate(const Space<dim> &primal, const Space<dim> &adjoint, const TimeMesh &mesh,
         const TemporalBasis &basis, const std::vector<Vector<double>> &U,
         const std::vector<Vector<double>> &Z, const std::vector<GoalSpec> &goals,
         const TimeIndicator time_indicator, const HigherOrderPrimal *hi)
{
  if ((time_indicator == TimeIndicator::higher_order) != (hi != nullptr))
    throw std::invalid_argument(
        "estimate: the higher_order time indicator needs the dG(r+1) primal (and only it)");
  if (hi && (hi->basis.n_dofs() != basis.n_dofs() + 1 || hi->U.size() != mesh.n_slabs()))
    throw std::invalid_argument("estimate: the higher-order primal must be dG(r+1) on the "
                                "same slabs");
  const auto &tria = primal.dof_handler().get_triangulation();
  const SpatialOperators<dim> ops(primal.dof_handler(), weight_degree(primal, adjoint));
  const auto &fe_w = ops.weight_element();
  const FullMatrix<double> P = ops.interpolation_from(primal.finite_element()),
                           Q = ops.interpolation_from(adjoint.finite_element());
  CellKernel<dim> kernel(primal, fe_w, basis);
  const TemporalReconstruction recon(basis);
  const LocalGoal<dim> goal_t(primal.mapping(), fe_w, tria, goals, true),
      goal_T(primal.mapping(), fe_w, tria, goals, false);
  const unsigned int N = mesh.n_slabs(), m1 = basis.n_dofs(), nw = fe_w.n_dofs_per_cell();

  // z(T^+) = M^{-1} j_T (the end-time goal's representer in the adjoint space) and
  // the interpolant of u_0 (E_tau u at t_0).
  Vector<double> zT, u0(primal.n_dofs());
  if (!goal_T.empty())
  {
    GoalVectors gv = assemble_goal_vectors(adjoint, goals);
    SparseMatrix<double> M(adjoint.sparsity());
    MatrixCreator::create_mass_matrix(
        adjoint.mapping(), adjoint.dof_handler(), QGauss<dim>(adjoint.degree() + 1), M,
        (const Function<dim> *)nullptr, adjoint.constraints());
    adjoint.constraints().condense(gv.at_end);
    for (unsigned int i = 0; i < M.m(); ++i)
      if (adjoint.constraints().is_constrained(i))
        M.set(i, i, 1.);
    SparseDirectUMFPACK lu;
    lu.initialize(M);
    zT = gv.at_end;
    lu.solve(zT);
    adjoint.constraints().distribute(zT);
  }
  {
    const ScalarFunctionFromFunctionObject<dim> f0(
        [&](const Point<dim> &x) { return primal.scene.initial_value(x); });
    VectorTools::interpolate(primal.mapping(), primal.dof_handler(), f0, u0);
  }

  Indicators<dim> ind;
  ind.eta_h_cell.assign(tria.n_active_cells(), std::array<double, dim>{});
  ind.eta_tau_cell.assign(tria.n_active_cells(), 0.);
  ind.eta_tau_slab.assign(N, 0.);

  // E_tau at the temporal Gauss points (values [0] and derivatives [1]): the same
  // combinations for every cell and slab
  std::vector<std::array<TimeCombination, 2>> E_z(kernel.n_points()),
      E_u(kernel.n_points());
  for (unsigned int m = 0; m < kernel.n_points(); ++m)
    for (unsigned int d = 0; d < 2; ++d)
    {
      E_z[m][d] = recon.adjoint(kernel.point(m), d == 1);
      E_u[m][d] = recon.primal(kernel.point(m), d == 1);
    }

  // the dG(r+1) basis at the temporal Gauss points (values, derivatives per unit s)
  const unsigned int m2 = hi ? hi->basis.n_dofs() : 0;
  std::vector<std::vector<double>> hi_val, hi_der;
  if (hi)
    for (unsigned int m = 0; m < kernel.n_points(); ++m)
    {
      hi_val.push_back(hi->basis.values(kernel.point(m)));
      std::vector<double> d(m2);
      for (unsigned int k = 0; k < m2; ++k)
        d[k] = hi->basis.derivative(k, kernel.point(m));
      hi_der.push_back(d);
    }
  std::vector<Vector<double>> hk(m2);
  Vector<double> e_prev(nw);

  std::vector<types::global_dof_index> idx_q(adjoint.finite_element().n_dofs_per_cell());
  SlabFunctional rho, supg, A_rh, S_rh, A_z, Jf;
  // buffers reused over cells and slabs (the loop body allocates nothing once sized)
  std::vector<Vector<double>> zk(m1), uk(m1), vk(m1);
  Vector<double> z_next(nw), u_prev(nw), tmp(nw), vT(nw), vz(nw), vu(nw);
  SlabFunction z, u, Rhz, Riz, dz, v, ez, eu;
  std::vector<LocalMap> lift(dim);
  Vector<double> jt, jT;
  for (const auto &cell : primal.dof_handler().active_cell_iterators())
  {
    kernel.reinit(cell);
    const auto &idx = kernel.dof_indices();
    typename DoFHandler<dim>::active_cell_iterator cq(&tria, cell->level(), cell->index(),
                                                      &adjoint.dof_handler());
    cq->get_dof_indices(idx_q);
    for (unsigned int i = 0; i < dim; ++i)
      lift[i] = ops.directional_lift(cell, i);
    if (!goal_t.empty())
      goal_t.cell_vector(cell, jt);
    if (!goal_T.empty())
      goal_T.cell_vector(cell, jT);
    const auto c = cell->active_cell_index();
    double supg_part = 0;                // S(u)(R_h z) on this cell
    std::array<double, dim> lift_size{}; // ||I_2h,i u - u||^2 over the slabs

    for (unsigned int n = 0; n < N; ++n)
    {
      const double t0 = mesh.start(n), tau = mesh.tau(n);
      kernel.primal_functionals(t0, tau, U[n], n ? &U[n - 1] : nullptr, rho, supg);

      // adjoint: z on the slab, z(t_n^+)
      for (unsigned int k = 0; k < m1; ++k)
      {
        gather(Z[n], idx_q, m1, k, Q, zk[k]);
        gather(U[n], idx, m1, k, P, uk[k]);
      }
      z_next = 0.;
      if (n + 1 < N)
        for (unsigned int k = 0; k < m1; ++k)
        {
          gather(Z[n + 1], idx_q, m1, k, Q, tmp);
          z_next.add(basis.left_trace()[k], tmp);
        }
      else if (zT.size())
        gather(zT, idx_q, 1, 0, Q, z_next);
      if (n > 0)
        gather(U[n - 1], idx, m1, m1 - 1, P, u_prev);
      else
        gather(u0, idx, 1, 0, P, u_prev);

      slab_function(kernel, basis, tau, zk, z);
      Rhz = z;
      transform(ops.restriction(dim), Rhz);
      kernel.adjoint_functional(t0, tau, Rhz, false, A_rh);
      kernel.adjoint_functional(t0, tau, Rhz, true, S_rh);
      kernel.adjoint_functional(t0, tau, z, false, A_z);
      kernel.goal_functional(tau, jt, Jf);
      const bool last = n + 1 == N;
      slab_function(kernel, basis, tau, uk, u);
      // S(u)(R_h z): with z_h = R_h z in the primal space, J(e) = rho(u)(z - z_h) +
      // S(u)(z_h) and J(e) = rho*(z_h)(u - u_h) + S(u)(z_h) hold exactly, so the
      // average of the two carries the full SUPG consistency term.
      supg_part += apply(supg, Rhz, false);

      // eta_h,i
      for (unsigned int i = 0; i < dim; ++i)
      {
        Riz = z;
        transform(ops.restriction(i), Riz);
        difference(z, Riz, dz);
        double eta = 0.5 * apply(rho, dz, false);
        if (lift[i].exists)
        {
          for (unsigned int k = 0; k < m1; ++k)
          {
            lift[i].apply(U[n], vk[k], m1, k);
            vk[k] -= uk[k];
          }
          slab_function(kernel, basis, tau, vk, v);
          for (const auto &vv : v.val)
            lift_size[i] += tau * vv.norm_sqr();
          if (n > 0)
          {
            lift[i].apply(U[n - 1], v.minus, m1, m1 - 1);
            v.minus -= u_prev;
          }
          else
            v.minus.reinit(0);
          double jv = apply(Jf, v, false); // J' over I
          if (last && jT.size())
          {
            vT = 0.;
            for (unsigned int k = 0; k < m1; ++k)
              vT.add(basis.right_trace()[k], vk[k]);
            jv += jT * vT;
          }
          eta += 0.5 * (jv - apply(A_rh, v, true)) + 0.5 * apply(S_rh, v, true);
        }
        ind.eta_h_cell[c][i] += eta;
        ind.eta_h[i] += eta;
      }

      // eta_tau: E z - z (outside value z(t_n^+)), E u - u (outside value u(t_{n-1}^-))
      ez.val.resize(kernel.n_points());
      ez.dt.resize(kernel.n_points());
      eu.val.resize(kernel.n_points());
      eu.dt.resize(kernel.n_points());
      for (unsigned int m = 0; m < kernel.n_points(); ++m)
      {
        for (bool deriv : {false, true})
        {
          const TimeCombination &a = E_z[m][deriv], &b = E_u[m][deriv];
          vz = 0.;
          vu = 0.;
          vz.add(a.outside, z_next);
          vu.add(b.outside, u_prev);
          for (unsigned int k = 0; k < m1; ++k)
          {
            vz.add(a.slab[k], zk[k]);
            vu.add(b.slab[k], uk[k]);
          }
          if (deriv)
          {
            vz /= tau;
            vu /= tau;
            vz -= z.dt[m];
            vu -= u.dt[m];
            ez.dt[m] = vz;
            eu.dt[m] = vu;
          }
          else
          {
            vz -= z.val[m];
            vu -= u.val[m];
            ez.val[m] = vz;
            eu.val[m] = vu;
          }
        }
      }
      ez.plus.reinit(nw); // E z(t_{n-1}) = z(t_{n-1}^+)
      eu.plus = u_prev;   // E u(t_{n-1}) - u(t_{n-1}^+)
      eu.plus -= u.plus;
      // J_T(E u - u) at T: 0 for the Radau reconstruction (E u - u vanishes at t_n)
      double end_part = 0;
      if (hi)
      {
        // E u := u_r+1: values and derivatives at the Gauss points, the jump of
        // e = u_r+1 - u at t_{n-1} (e(t_0^-) = 0: both start from u_0), and J_T(e(T))
        for (unsigned int k = 0; k < m2; ++k)
          gather(hi->U[n], idx, m2, k, P, hk[k]);
        for (unsigned int m = 0; m < kernel.n_points(); ++m)
        {
          vu = 0.;
          tmp = 0.;
          for (unsigned int k = 0; k < m2; ++k)
          {
            vu.add(hi_val[m][k], hk[k]);
            tmp.add(hi_der[m][k] / tau, hk[k]);
          }
          vu -= u.val[m];
          tmp -= u.dt[m];
          eu.val[m] = vu;
          eu.dt[m] = tmp;
        }
        eu.plus = 0.;
        for (unsigned int k = 0; k < m2; ++k)
          eu.plus.add(hi->basis.left_trace()[k], hk[k]);
        eu.plus -= u.plus;
        if (n > 0)
        {
          e_prev = 0.;
          for (unsigned int k = 0; k < m2; ++k)
          {
            gather(hi->U[n - 1], idx, m2, k, P, tmp);
            e_prev.add(hi->basis.right_trace()[k], tmp);
          }
          e_prev -= u_prev; // u(t_{n-1}^-)
          eu.plus -= e_prev;
        }
        if (last && jT.size())
        {
          vT = 0.;
          for (unsigned int k = 0; k < m2; ++k)
            vT.add(hi->basis.right_trace()[k], hk[k]);
          for (unsigned int k = 0; k < m1; ++k)
            vT.add(-basis.right_trace()[k], uk[k]);
          end_part = jT * vT;
        }
      }
      const double jv = apply(Jf, eu, false) + end_part; // J'(E u - u) over I and at T
      const double half_rho = 0.5 * apply(rho, ez, false),
                   half_rhostar = 0.5 * (jv - apply(A_z, eu, true));
      const double eta_tau = time_indicator == TimeIndicator::average
                                 ? half_rho + half_rhostar
                                 : 2 * half_rhostar;
      ind.eta_tau_rho += half_rho;
      ind.eta_tau_rhostar += half_rhostar;
      ind.eta_tau_cell[c] += eta_tau;
      ind.eta_tau_slab[n] += eta_tau;
      ind.eta_tau += eta_tau;
    }
    // The SUPG consistency term is not directional (the seed formula's 1/2 S(u)(R_i z)
    // is nearly the same for every i: R_i z does not measure direction i). Its cell
    // total S(u)(R_h z) is split over the directions in proportion to the size of the
    // directional primal error ||I_2h,i u - u||^2 (summed over the slabs).
    double total = 0;
    for (double l : lift_size)
      total += l;
    for (unsigned int i = 0; i < dim; ++i)
    {
      const double share = (total > 0 ? lift_size[i] / total : 1. / dim) * supg_part;
      ind.eta_h_cell[c][i] += share;
      ind.eta_h[i] += share;
    }
  }
  return ind;
}

namespace
{
/// Runs `body(kernel, cell, to_w, other_dofs)` on every cell.
template <int dim, typename Body>
void for_cells(const Space<dim> &primal, const Space<dim> &other,
               const TemporalBasis &basis, Body body)
{
  const SpatialOperators<dim> ops(primal.dof_handler(), weight_degree(primal, other));
  const FullMatrix<double> to_w = ops.interpolation_from(other.finite_element());
  CellKernel<dim> kernel(primal, ops.weight_element(), basis);
  std::vector<types::global_dof_index> idx(other.finite_element().n_dofs_per_cell());
  for (const auto &cell : primal.dof_handler().active_cell_iterators())
  {
    kernel.reinit(cell);
    typename DoFHandler<dim>::active_cell_iterator co(
        &primal.dof_handler().get_triangulation(), cell->level(), cell->index(),
        &other.dof_handler());
    co->get_dof_indices(idx);
    body(kernel, to_w, idx);
  }
}

template <int dim>
SlabFunction other_function(const CellKernel<dim> &kernel, const TemporalBasis &basis,
                            double tau, const Vector<double> &V,
                            const std::vector<types::global_dof_index> &idx,
                            const FullMatrix<double> &to_w)
{
  std::vector<Vector<double>> vk(basis.n_dofs());
  for (unsigned int k = 0; k < basis.n_dofs(); ++k)
    gather(V, idx, basis.n_dofs(), k, to_w, vk[k]);
  SlabFunction f;
  slab_function(kernel, basis, tau, vk, f);
  return f;
}
} // namespace

namespace
{
/// sum over cells of rho(u)(w) (supg == false) or S(u)(w), one value per slab.
template <int dim>
std::vector<double> primal_form(const Space<dim> &primal, const Space<dim> &other,
                                const TimeMesh &mesh, const TemporalBasis &basis,
                                const std::vector<Vector<double>> &U,
                                const std::vector<Vector<double>> &W, bool supg)
{
  std::vector<double> out(mesh.n_slabs(), 0.);
  for_cells(primal, other, basis,
            [&](const CellKernel<dim> &k, const FullMatrix<double> &to_w,
                const std::vector<types::global_dof_index> &idx)
            {
              SlabFunctional rho, S;
              for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
              {
                k.primal_functionals(mesh.start(n), mesh.tau(n), U[n],
                                     n ? &U[n - 1] : nullptr, rho, S);
                out[n] +=
                    apply(supg ? S : rho,
                          other_function(k, basis, mesh.tau(n), W[n], idx, to_w), false);
              }
            });
  return out;
}
} // namespace

template <int dim>
std::vector<double>
LocalizedForms<dim>::primal_residual(const Space<dim> &primal, const Space<dim> &other,
                                     const TimeMesh &mesh, const TemporalBasis &basis,
                                     const std::vector<Vector<double>> &U,
                                     const std::vector<Vector<double>> &W)
{
  return primal_form(primal, other, mesh, basis, U, W, false);
}

template <int dim>
std::vector<double>
LocalizedForms<dim>::supg(const Space<dim> &primal, const Space<dim> &other,
                          const TimeMesh &mesh, const TemporalBasis &basis,
                          const std::vector<Vector<double>> &U,
                          const std::vector<Vector<double>> &Y)
{
  return primal_form(primal, other, mesh, basis, U, Y, true);
}

template <int dim>
std::vector<double> LocalizedForms<dim>::adjoint_form(
    const Space<dim> &primal, const Space<dim> &other, const TimeMesh &mesh,
    const TemporalBasis &basis, const std::vector<Vector<double>> &V,
    const std::vector<Vector<double>> &Zt, bool supg_derivative)
{
  std::vector<double> out(mesh.n_slabs(), 0.);
  const unsigned int m1 = basis.n_dofs();
  for_cells(primal, other, basis,
            [&](const CellKernel<dim> &k, const FullMatrix<double> &to_w,
                const std::vector<types::global_dof_index> &idx)
            {
              SlabFunctional A;
              for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
              {
                const double tau = mesh.tau(n);
                k.adjoint_functional(mesh.start(n), tau,
                                     other_function(k, basis, tau, Zt[n], idx, to_w),
                                     supg_derivative, A);
                SlabFunction v = other_function(k, basis, tau, V[n], idx, to_w);
                if (n > 0)
                  gather(V[n - 1], idx, m1, m1 - 1, to_w, v.minus);
                out[n] += apply(A, v, true);
              }
            });
  return out;
}

template Indicators<2> estimate<2>(const Space<2> &, const Space<2> &, const TimeMesh &,
                                   const TemporalBasis &,
                                   const std::vector<Vector<double>> &,
                                   const std::vector<Vector<double>> &,
                                   const std::vector<GoalSpec> &, TimeIndicator,
                                   const HigherOrderPrimal *);
template struct LocalizedForms<2>;
} // namespace anisodwr
