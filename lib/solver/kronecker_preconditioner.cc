#include "solver/kronecker_preconditioner.h"

#include "solver/amg_block.h"
#include "solver/ifpack2_factory.h"
#include "solver/inner_gmres.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace anisodwr::tpetra
{
KroneckerPreconditioner::KroneckerPreconditioner(const RCP<const Map> &slab_map,
                                                 const KronSplit &k, bool transpose,
                                                 const IterativeOptions &o)
    : presb(o.preconditioner == Preconditioner::kronecker_presb),
      inner_its(o.inner_iterations), inner_tol(o.inner_tolerance), slab_map(slab_map)
{
  schur = TemporalSchur(k.T1, k.T2, transpose);
  m = schur.m;

  const auto &S1 = *k.S1;
  const auto &S2 = *k.S2;
  space_map = serial_map(S1.m());
  S1_t = to_tpetra(space_map, S1, 1., nullptr, 0., transpose);
  w1 = rcp(new Vec(space_map));
  w2 = rcp(new Vec(space_map));
  h = rcp(new Vec(space_map));
  for (const ModeBlock &mode : schur.blocks)
    blocks.push_back(make_block(mode, S1, S2, transpose, o));
  for (unsigned int k2 = 0; k2 < m; ++k2)
  {
    y.push_back(rcp(new Vec(space_map)));
    z.push_back(rcp(new Vec(space_map)));
  }
}

KroneckerPreconditioner::Block
KroneckerPreconditioner::make_block(const ModeBlock &mode,
                                    const dealii::SparseMatrix<double> &S1,
                                    const dealii::SparseMatrix<double> &S2,
                                    bool transpose, const IterativeOptions &o) const
{
  Block blk;
  static_cast<ModeBlock &>(blk) = mode;
  const unsigned int j = mode.first;
  const auto &T = schur.T;
  if (blk.size == 2 && !presb)
  {
    dealii::FullMatrix<double> Tb(2, 2);
    for (unsigned int s = 0; s < 2; ++s)
      for (unsigned int t = 0; t < 2; ++t)
        Tb(s, t) = T(j + s, j + t);
    blk.map = serial_map(2 * S1.m());
    blk.matrix = kron_block_tpetra(blk.map, Tb, S1, S2, transpose);
    blk.in = rcp(new Vec(blk.map));
    blk.out = rcp(new Vec(blk.map));
  }
  else
    blk.matrix = to_tpetra(space_map, S1, blk.shift, &S2, 1., transpose);
  make_spatial(blk, o);
  if (blk.size == 2 && presb)
    blk.presb = presb_of(blk);
  if (inner_its > 0)
    make_inner_operators(blk);
  else if (o.spatial_preconditioner == SpatialPreconditioner::amg)
    blk.matrix = Teuchos::null; // ML works on its Epetra copy
  return blk;
}

void KroneckerPreconditioner::make_spatial(Block &blk, const IterativeOptions &o)
{
  if (o.spatial_preconditioner == SpatialPreconditioner::amg)
  {
    auto amg = std::make_shared<AmgBlock>(*blk.matrix, blk.map.is_null() ? 1 : 2, o);
    blk.spatial = [amg](const Vec &in, Vec &out) { amg->apply(in, out); };
  }
  else
  {
    IterativeOptions io = o;
    io.ilu_fill = std::max(0., std::round(o.ilu_fill));
    RCP<Prec> prec = make_ifpack2(Preconditioner::riluk, blk.matrix, io, 1);
    blk.spatial = [prec](const Vec &in, Vec &out) { prec->apply(in, out); };
  }
}

void KroneckerPreconditioner::make_inner_operators(Block &blk) const
{
  if (blk.size == 1 || !presb)
  {
    blk.op = blk.matrix;
    blk.op_prec = rcp(new FunctionOperator(blk.map.is_null() ? space_map : blk.map,
                                           blk.spatial));
    return;
  }
  // The scaled block [[B, -beta S1], [beta S1, B]] on [y1; zz], B = M - beta S1 with
  // M = blk.matrix = B + beta S1, and PRESB as its preconditioner.
  const std::size_t n = space_map->getNodeNumElements();
  blk.map = serial_map(2 * n);
  blk.in = rcp(new Vec(blk.map));
  blk.out = rcp(new Vec(blk.map));
  const auto sm = space_map;
  const RCP<Matrix> M = blk.matrix, S1 = S1_t;
  const double beta = blk.beta;
  const RCP<Vec> s = rcp(new Vec(sm)), t = rcp(new Vec(sm));
  blk.op = rcp(new FunctionOperator(
      blk.map,
      [=](const Vec &x, Vec &y)
      {
        const auto x1 = x.offsetView(sm, 0), x2 = x.offsetView(sm, n);
        auto y1 = y.offsetViewNonConst(sm, 0), y2 = y.offsetViewNonConst(sm, n);
        M->apply(*x1, *y1);
        M->apply(*x2, *y2);
        s->update(1., *x1, 1., *x2, 0.);
        S1->apply(*s, *t);
        y1->update(-beta, *t, 1.); // M x1 - beta S1 (x1 + x2)
        s->update(1., *x1, -1., *x2, 0.);
        S1->apply(*s, *t);
        y2->update(beta, *t, 1.); // M x2 + beta S1 (x1 - x2)
      }));
  const Presb pr = blk.presb;
  blk.op_prec = rcp(new FunctionOperator(
      blk.map,
      [=](const Vec &f, Vec &y)
      {
        pr(*f.offsetView(sm, 0), *f.offsetView(sm, n), *y.offsetViewNonConst(sm, 0),
           *y.offsetViewNonConst(sm, n));
      }));
}

KroneckerPreconditioner::Presb KroneckerPreconditioner::presb_of(const Block &b) const
{
  Presb p;
  p.spatial = b.spatial;
  p.S1 = S1_t;
  p.beta = b.beta;
  p.w1 = w1;
  p.w2 = w2;
  p.h = h;
  return p;
}

void KroneckerPreconditioner::Presb::operator()(const Vec &f1, const Vec &f2, Vec &y1,
                                                Vec &zz) const
{
  w1->update(1., f1, 1., f2, 0.); // f1 + f2
  spatial(*w1, *h);               // h = y1 + zz
  S1->apply(*h, *w2);
  w2->update(1., f1, beta); // beta S1 h + f1
  spatial(*w2, y1);         // y1 = (B + beta S1)^{-1}(beta S1 h + f1)
  zz.update(1., *h, -1., y1, 0.);
}

void KroneckerPreconditioner::apply(const MV &X, MV &Y, Teuchos::ETransp mode,
                                    double alpha, double beta) const
{
  if (mode != Teuchos::NO_TRANS)
    throw std::logic_error("kronecker preconditioner: transposed apply not implemented");
  for (std::size_t c = 0; c < X.getNumVectors(); ++c)
  {
    to_schur_basis(X, c);
    back_substitute();
    from_schur_basis(Y, c, alpha, beta);
  }
}

void KroneckerPreconditioner::to_schur_basis(const MV &X, std::size_t column) const
{
  const std::size_t n = space_map->getNodeNumElements();
  auto x = X.getData(column);
  std::vector<Teuchos::ArrayRCP<double>> g(m);
  std::vector<double *> modes(m);
  for (unsigned int k = 0; k < m; ++k)
  {
    g[k] = y[k]->getDataNonConst();
    modes[k] = g[k].getRawPtr();
  }
  gather_modes(schur.P, x.getRawPtr(), n, modes);
}

void KroneckerPreconditioner::back_substitute() const
{
  // y holds the transformed right-hand side; overwritten block by block (last first).
  for (auto b = blocks.rbegin(); b != blocks.rend(); ++b)
  {
    const unsigned int j0 = b->first, j1 = b->first + b->size;
    for (unsigned int j = j0; j < j1; ++j)
      for (unsigned int l = j1; l < m; ++l)
        if (schur.T(j, l) != 0.)
          y[j]->update(-schur.T(j, l), *z[l], 1.);
    solve_block(*b);
    if (j0 > 0)
      for (unsigned int j = j0; j < j1; ++j)
        S1_t->apply(*y[j], *z[j]);
  }
}

void KroneckerPreconditioner::solve_block(const Block &b) const
{
  const unsigned int j0 = b.first;
  if (b.size == 1)
  {
    w1->assign(*y[j0]);
    solve_on_block(b, *w1, *y[j0]);
    return;
  }
  Vec &y1 = *y[j0], &y2 = *y[j0 + 1];
  if (!presb)
  {
    interleave(y1, y2, *b.in);
    solve_on_block(b, *b.in, *b.out);
    deinterleave(*b.out, y1, y2);
    return;
  }
  // [[B, -beta S1], [beta S1, B]] [y1; zz] = [f1; f2], f1 = r1, f2 = rho r2,
  // y2 = sigma zz.
  y2.scale(b.rho);
  if (inner_its > 0)
  {
    const std::size_t n = space_map->getNodeNumElements();
    b.in->offsetViewNonConst(space_map, 0)->assign(y1);
    b.in->offsetViewNonConst(space_map, n)->assign(y2);
    solve_on_block(b, *b.in, *b.out);
    y1.assign(*b.out->offsetView(space_map, 0));
    y2.assign(*b.out->offsetView(space_map, n));
  }
  else
    b.presb(y1, y2, y1, y2);
  y2.scale(b.sigma);
}

void KroneckerPreconditioner::solve_on_block(const Block &b, const Vec &in, Vec &out) const
{
  if (inner_its > 0)
    inner_count += inner_gmres(b.op, b.op_prec, in, out, inner_its, inner_tol);
  else
    b.spatial(in, out);
}

void KroneckerPreconditioner::interleave(const Vec &a, const Vec &b, Vec &ab)
{
  auto out = ab.getDataNonConst();
  auto r1 = a.getData();
  auto r2 = b.getData();
  for (Teuchos_Ordinal i = 0; i < r1.size(); ++i)
  {
    out[2 * i] = r1[i];
    out[2 * i + 1] = r2[i];
  }
}

void KroneckerPreconditioner::deinterleave(const Vec &ab, Vec &a, Vec &b)
{
  auto in = ab.getData();
  auto y1 = a.getDataNonConst();
  auto y2 = b.getDataNonConst();
  for (Teuchos_Ordinal i = 0; i < y1.size(); ++i)
  {
    y1[i] = in[2 * i];
    y2[i] = in[2 * i + 1];
  }
}

void KroneckerPreconditioner::from_schur_basis(MV &Y, std::size_t column, double alpha,
                                               double beta) const
{
  const std::size_t n = space_map->getNodeNumElements();
  auto out = Y.getDataNonConst(column);
  std::vector<Teuchos::ArrayRCP<const double>> yy(m);
  std::vector<const double *> modes(m);
  for (unsigned int k = 0; k < m; ++k)
  {
    yy[k] = y[k]->getData();
    modes[k] = yy[k].getRawPtr();
  }
  scatter_modes(schur.Q, modes, n, out.getRawPtr(), alpha, beta);
}
} // namespace anisodwr::tpetra
