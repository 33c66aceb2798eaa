// Belos + Ifpack2 on Tpetra for slab systems; see iterative_solver.h.
#include "solver/iterative_solver.h"

#include <deal.II/lac/trilinos_precondition.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
#include <mpi.h>

#include <BelosBiCGStabSolMgr.hpp>
#include <BelosBlockGmresSolMgr.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosStatusTest.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Ifpack2_Factory.hpp>
#include <Kokkos_Core.hpp>
#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_BlockCrsMatrix_Helpers.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

extern "C" void dgees_(const char *jobvs, const char *sort,
                       int (*select)(double *, double *), const int *n, double *a,
                       const int *lda, int *sdim, double *wr, double *wi, double *vs,
                       const int *ldvs, double *work, const int *lwork, int *bwork,
                       int *info);

namespace anisodwr
{
namespace
{
using Map = Tpetra::Map<>;
using LO = Map::local_ordinal_type;
using GO = Map::global_ordinal_type;
using Node = Map::node_type;
using Matrix = Tpetra::CrsMatrix<double, LO, GO, Node>;
using RowMatrix = Tpetra::RowMatrix<double, LO, GO, Node>;
using MV = Tpetra::MultiVector<double, LO, GO, Node>;
using Vec = Tpetra::Vector<double, LO, GO, Node>;
using OP = Tpetra::Operator<double, LO, GO, Node>;
using Prec = Ifpack2::Preconditioner<double, LO, GO, Node>;
using Teuchos::RCP;
using Teuchos::rcp;

void ensure_kokkos()
{
  // Never finalized: Tpetra keeps static Kokkos buffers that are freed at exit.
  static const bool done = []
  {
    if (!Kokkos::is_initialized())
      Kokkos::initialize();
    return true;
  }();
  (void)done;
}

RCP<const Teuchos::Comm<int>> serial_comm()
{
  static const RCP<const Teuchos::Comm<int>> comm = rcp(new Teuchos::SerialComm<int>());
  return comm;
}

/// CSR of a*A + b*B (B on A's pattern, may be null), optionally transposed; sorted rows.
RCP<Matrix> to_tpetra(const RCP<const Map> &map, const dealii::SparseMatrix<double> &A,
                      double a, const dealii::SparseMatrix<double> *B, double b,
                      bool transpose)
{
  const std::size_t n = A.m();
  if (B && &B->get_sparsity_pattern() != &A.get_sparsity_pattern() &&
      B->n_nonzero_elements() != A.n_nonzero_elements())
    throw std::logic_error("to_tpetra: the two matrices do not share a pattern");
  Teuchos::ArrayRCP<std::size_t> ptr(n + 1, 0);
  const std::size_t nnz = A.n_nonzero_elements();
  Teuchos::ArrayRCP<LO> col(nnz);
  Teuchos::ArrayRCP<double> val(nnz);
  // Pass 1: row lengths of the result.
  for (std::size_t i = 0; i < n; ++i)
    for (auto it = A.begin(i); it != A.end(i); ++it)
      ++ptr[(transpose ? it->column() : i) + 1];
  std::partial_sum(ptr.begin(), ptr.end(), ptr.begin());
  std::vector<std::size_t> fill(ptr.begin(), ptr.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    auto itb = B ? B->begin(i) : A.begin(i);
    for (auto it = A.begin(i); it != A.end(i); ++it, ++itb)
    {
      const std::size_t j = it->column();
      const double v = a * it->value() + (B ? b * itb->value() : 0.);
      const std::size_t row = transpose ? j : i;
      col[fill[row]] = static_cast<LO>(transpose ? i : j);
      val[fill[row]++] = v;
    }
  }
  // Sort each row by column (deal.II stores the diagonal first).
  std::vector<std::pair<LO, double>> tmp;
  for (std::size_t i = 0; i < n; ++i)
  {
    tmp.clear();
    for (std::size_t q = ptr[i]; q < ptr[i + 1]; ++q)
      tmp.emplace_back(col[q], val[q]);
    std::sort(tmp.begin(), tmp.end(),
              [](const auto &x, const auto &y) { return x.first < y.first; });
    for (std::size_t q = ptr[i]; q < ptr[i + 1]; ++q)
    {
      col[q] = tmp[q - ptr[i]].first;
      val[q] = tmp[q - ptr[i]].second;
    }
  }
  auto M = rcp(new Matrix(map, map, ptr, col, val));
  M->fillComplete();
  return M;
}

/// Tb (x) S1 + I (x) S2 in the interleaved ordering (block size Tb.m()), or its transpose
/// built from S1^T, S2^T if `transpose` (Tb is used as given).
RCP<Matrix> kron_block_tpetra(const RCP<const Map> &map,
                              const dealii::FullMatrix<double> &Tb,
                              const dealii::SparseMatrix<double> &S1,
                              const dealii::SparseMatrix<double> &S2, bool transpose)
{
  const unsigned int nb = Tb.m();
  if (nb == 1)
    return to_tpetra(map, S1, Tb(0, 0), &S2, 1., transpose);
  // Spatial CSR of S1 and S2 (transposed if asked), then expand each entry to a block.
  const RCP<const Map> smap =
      rcp(new Map(static_cast<Tpetra::global_size_t>(S1.m()), 0, serial_comm()));
  const auto A1 = to_tpetra(smap, S1, 1., nullptr, 0., transpose);
  const auto A2 = to_tpetra(smap, S2, 1., nullptr, 0., transpose);
  const std::size_t n = S1.m(), nnz = A1->getNodeNumEntries();
  const SlabLayout block{nb};
  Teuchos::ArrayRCP<std::size_t> ptr(n * nb + 1, 0);
  Teuchos::ArrayRCP<LO> col(nnz * nb * nb);
  Teuchos::ArrayRCP<double> val(nnz * nb * nb);
  std::size_t q = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    typename Matrix::local_inds_host_view_type c1, c2;
    typename Matrix::values_host_view_type v1, v2;
    A1->getLocalRowView(static_cast<LO>(i), c1, v1);
    A2->getLocalRowView(static_cast<LO>(i), c2, v2);
    for (unsigned int s = 0; s < nb; ++s)
    {
      for (std::size_t e = 0; e < c1.extent(0); ++e)
        for (unsigned int t = 0; t < nb; ++t)
        {
          col[q] = static_cast<LO>(block.index(c1(e), t));
          val[q++] = Tb(s, t) * v1(e) + (s == t ? v2(e) : 0.);
        }
      ptr[block.index(i, s) + 1] = q;
    }
  }
  auto M = rcp(new Matrix(map, map, ptr, col, val));
  M->fillComplete();
  return M;
}

/// deal.II's PreconditionBase holds an Epetra_MpiComm, and ML asks MPI for its rank:
/// MPI must be initialized before the first AMG. Done on first use (only the amg path
/// needs it) and finalized at exit if we initialized it.
void ensure_mpi()
{
  static const bool done = []
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized)
    {
      MPI_Init(nullptr, nullptr);
      std::atexit(
          []
          {
            int finalized = 0;
            MPI_Finalized(&finalized);
            if (!finalized)
              MPI_Finalize();
          });
    }
    return true;
  }();
  (void)done;
}

/// One ML AMG hierarchy (deal.II TrilinosWrappers::PreconditionAMG, Epetra) for a serial
/// spatial block given as a Tpetra matrix; applied to Tpetra vectors through Epetra
/// views of their host data (no copies). block_size 2 (the real 2n x 2n form of a complex
/// shift, interleaved) aggregates the two unknowns of a node together ("PDE equations").
class AmgBlock
{
public:
  AmgBlock(const Matrix &A, unsigned int block_size, const IterativeOptions &o)
  {
    ensure_mpi();
    comm = std::make_unique<Epetra_MpiComm>(MPI_COMM_SELF);
    const int n = static_cast<int>(A.getNodeNumRows());
    map = std::make_unique<Epetra_Map>(n, 0, *comm);
    std::vector<int> lengths(n);
    for (int i = 0; i < n; ++i)
      lengths[i] = static_cast<int>(A.getNumEntriesInLocalRow(i));
    matrix = std::make_unique<Epetra_CrsMatrix>(Copy, *map, lengths.data(), true);
    std::vector<int> cols;
    for (int i = 0; i < n; ++i)
    {
      typename Matrix::local_inds_host_view_type c;
      typename Matrix::values_host_view_type v;
      A.getLocalRowView(i, c, v);
      cols.assign(c.data(), c.data() + c.extent(0));
      matrix->InsertGlobalValues(i, static_cast<int>(cols.size()), v.data(), cols.data());
    }
    matrix->FillComplete();

    dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic = false; // ML "NSSA": nonsymmetric smoothed aggregation
    data.higher_order_elements = false;
    data.n_cycles = 1;
    data.w_cycle = false;
    data.aggregation_threshold = 1e-4;
    data.smoother_sweeps = 1;
    data.smoother_overlap = 0;
    data.smoother_type = o.amg_smoother == "gauss_seidel" ? "Gauss-Seidel"
                         : o.amg_smoother == "chebyshev"  ? "Chebyshev"
                                                          : "ILU";
    data.coarse_type = "Amesos-KLU";
    if (block_size > 1)
    {
      data.constant_modes.assign(block_size, std::vector<bool>(n, false));
      for (int i = 0; i < n; ++i)
        data.constant_modes[i % block_size][i] = true;
    }
    Teuchos::ParameterList pl;
    data.set_parameters(pl, modes, *matrix);
    if (block_size > 1)
      pl.set("PDE equations", static_cast<int>(block_size));
    // Constructed only now: its Epetra_MpiComm needs MPI.
    amg = std::make_unique<dealii::TrilinosWrappers::PreconditionAMG>();
    amg->initialize(*matrix, pl);
  }

  void apply(const Vec &in, Vec &out) const
  {
    auto x = in.getData();
    auto y = out.getDataNonConst();
    const Epetra_Vector ex(View, *map, const_cast<double *>(x.getRawPtr()));
    Epetra_Vector ey(View, *map, y.getRawPtr());
    const int err = amg->trilinos_operator().ApplyInverse(ex, ey);
    if (err != 0)
      throw std::runtime_error("AMG (ML) application failed, error " +
                               std::to_string(err));
  }

private:
  std::unique_ptr<Epetra_MpiComm> comm;
  std::unique_ptr<Epetra_Map> map;
  std::unique_ptr<Epetra_CrsMatrix> matrix; // ML keeps a reference to it
  std::unique_ptr<Epetra_MultiVector> modes;
  std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
};

RCP<Prec> make_ifpack2(const std::string &type, const RCP<const RowMatrix> &A,
                       const IterativeOptions &o, LO n_blocks)
{
  Teuchos::ParameterList pl;
  std::string kind;
  if (type == "ilut")
  {
    kind = "ILUT";
    pl.set("fact: ilut level-of-fill", std::max(1., o.ilu_fill));
    pl.set("fact: drop tolerance", o.ilut_drop);
  }
  else if (type == "riluk" || type == "block_ilu")
  {
    kind = type == "riluk" ? "RILUK" : "RBILUK";
    pl.set("fact: iluk level-of-fill", static_cast<int>(std::lround(o.ilu_fill)));
  }
  else if (type == "block_jacobi" || type == "block_gauss_seidel")
  {
    kind = "BLOCK RELAXATION";
    pl.set("relaxation: type", type == "block_jacobi" ? "Jacobi" : "Gauss-Seidel");
    pl.set("relaxation: container", "Dense");
    pl.set("relaxation: sweeps", 1);
    pl.set("partitioner: type", "linear");
    pl.set("partitioner: local parts", n_blocks);
  }
  else
    throw std::invalid_argument("unknown preconditioner '" + type + "'");
  Ifpack2::Factory factory;
  RCP<Prec> p = factory.create<RowMatrix>(kind, A);
  p->setParameters(pl);
  p->initialize();
  p->compute();
  return p;
}

/// Thrown by StagnationTest out of Belos' iteration (Belos rethrows it unchanged).
class Stagnation : public std::runtime_error
{
public:
  Stagnation(unsigned int iterations, double ratio)
      : std::runtime_error("stagnation"), iterations(iterations), ratio(ratio)
  {
  }
  unsigned int iterations; ///< at detection
  double ratio;            ///< residual `window` iterations ago / residual now
};

/// Stagnation detection for (F)GMRES, added to Belos' status tests as the "debug" test
/// (an OR member that never passes): records the implicit residual norm of each
/// iteration and throws Stagnation when it has fallen by less than `factor` over the
/// last `window` iterations. Belos' own tests and iterates are unaffected otherwise.
class StagnationTest : public Belos::StatusTest<double, MV, OP>
{
public:
  StagnationTest(unsigned int window, double factor) : window(window), factor(factor) {}

  Belos::StatusType checkStatus(Belos::Iteration<double, MV, OP> *it) override
  {
    const int k = it->getNumIters();
    if (k < 0)
      return Belos::Failed;
    std::vector<double> norms(1, 0.);
    it->getNativeResiduals(&norms);
    const auto ku = static_cast<std::size_t>(k);
    if (history.size() <= ku)
      history.resize(ku + 1, std::numeric_limits<double>::quiet_NaN());
    history[ku] = norms[0];
    last = static_cast<unsigned int>(k);
    if (ku > window)
    {
      const double before = history[ku - window];
      // A NaN before (iteration not recorded) never triggers.
      if (before > 0. && !(norms[0] * factor < before))
        throw Stagnation(last, norms[0] > 0. ? before / norms[0] : 0.);
    }
    return Belos::Failed;
  }
  Belos::StatusType getStatus() const override { return Belos::Failed; }
  void reset() override
  {
    history.clear();
    last = 0;
  }
  void print(std::ostream &os, int indent = 0) const override
  {
    os << std::string(indent, ' ') << "stagnation test: residual falls by " << factor
       << " over " << window << " iterations\n";
  }

private:
  unsigned int window;
  double factor;
  std::vector<double> history; // implicit residual norm by iteration
  unsigned int last = 0;
};

/// Preconditioner from the Kronecker form K = T1 (x) S1 + T2 (x) S2.
///
/// With G = T2^{-1} T1 = Q T Q^T (real Schur form, T quasi upper triangular with
/// standardized 2x2 blocks), K x = b becomes (T (x) S1 + I (x) S2) y = (Q^T T2^{-1} (x)
/// I) b, x = (Q (x) I) y, solved by block back substitution over the temporal index:
///  - 1x1 block t: one spatial solve with t S1 + S2;
///  - 2x2 block Tb = [[a, b], [c, a]] (eigenvalues a +- i beta, beta^2 = -bc), either
///    (kronecker) one ILU(k) of the real 2n x 2n matrix Tb (x) S1 + I (x) S2
///    (interleaved, i.e. the real form of the complex shifted matrix (a + i beta) S1 +
///    S2), or (kronecker_presb) scaled to [[B, -beta S1], [beta S1, B]], B = a S1 + S2,
///    and preconditioned by PRESB (Axelsson-Neytcheva): two solves with B + beta S1 = (a
///    + beta) S1 + S2, half the memory; for exact inner solves the preconditioned
///    spectrum lies in [1/2, 1] when S1, S2 are symmetric positive (semi)definite, so
///    GMRES needs ~14 iterations to 1e-10 even then.
/// Each inner solve is one application of an Ifpack2 ILU(k) (solver.ilu_fill).
class KroneckerPreconditioner : public OP
{
public:
  KroneckerPreconditioner(const RCP<const Map> &slab_map, const KronSplit &k,
                          bool transpose, const IterativeOptions &o)
      : presb(o.preconditioner == "kronecker_presb"), slab_map(slab_map)
  {
    if (o.spatial_preconditioner != "ilu" && o.spatial_preconditioner != "amg")
      throw std::invalid_argument("unknown spatial preconditioner '" +
                                  o.spatial_preconditioner + "' (ilu or amg)");
    if (o.amg_smoother != "ilu" && o.amg_smoother != "gauss_seidel" &&
        o.amg_smoother != "chebyshev")
      throw std::invalid_argument("unknown AMG smoother '" + o.amg_smoother +
                                  "' (ilu, gauss_seidel or chebyshev)");
    m = k.T1.m();
    const int mi = static_cast<int>(m);
    dealii::FullMatrix<double> T1(m, m), T2(m, m), T2inv(m, m), G(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
      {
        T1(i, j) = transpose ? k.T1(j, i) : k.T1(i, j);
        T2(i, j) = transpose ? k.T2(j, i) : k.T2(i, j);
      }
    T2inv.invert(T2);
    T2inv.mmult(G, T1);
    // Real Schur form (LAPACK, column major).
    std::vector<double> a(m * m), vs(m * m), wr(m), wi(m), work(8 * m + 16);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        a[i + j * m] = G(i, j);
    int sdim = 0, info = 0, lwork = static_cast<int>(work.size());
    std::vector<int> bwork(m);
    dgees_("V", "N", nullptr, &mi, a.data(), &mi, &sdim, wr.data(), wi.data(), vs.data(),
           &mi, work.data(), &lwork, bwork.data(), &info);
    if (info != 0)
      throw std::runtime_error("kronecker preconditioner: dgees failed, info = " +
                               std::to_string(info));
    T.reinit(m, m);
    Q.reinit(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
      {
        T(i, j) = a[i + j * m];
        Q(i, j) = vs[i + j * m];
      }
    P.reinit(m, m);
    Q.Tmmult(P, T2inv); // P = Q^T T2^{-1}

    const auto &S1 = *k.S1;
    const auto &S2 = *k.S2;
    space_map =
        rcp(new Map(static_cast<Tpetra::global_size_t>(S1.m()), 0, serial_comm()));
    S1_t = to_tpetra(space_map, S1, 1., nullptr, 0., transpose);
    for (unsigned int j = 0; j < m;)
    {
      Block blk;
      blk.first = j;
      if (j + 1 < m && T(j + 1, j) != 0.)
      {
        blk.size = 2;
        blk.alpha = 0.5 * (T(j, j) + T(j + 1, j + 1));
        const double b = T(j, j + 1), c = T(j + 1, j);
        blk.beta = std::sqrt(std::max(0., -b * c));
        blk.sigma = -blk.beta / b;
        blk.rho = blk.beta / c;
        blk.shift = blk.alpha + blk.beta;
      }
      else
      {
        blk.size = 1;
        blk.shift = T(j, j);
      }
      if (blk.size == 2 && !presb)
      {
        dealii::FullMatrix<double> Tb(2, 2);
        for (unsigned int s = 0; s < 2; ++s)
          for (unsigned int t = 0; t < 2; ++t)
            Tb(s, t) = T(j + s, j + t);
        blk.map = rcp(
            new Map(static_cast<Tpetra::global_size_t>(2 * S1.m()), 0, serial_comm()));
        blk.matrix = kron_block_tpetra(blk.map, Tb, S1, S2, transpose);
        blk.in = rcp(new Vec(blk.map));
        blk.out = rcp(new Vec(blk.map));
      }
      else
        blk.matrix = to_tpetra(space_map, S1, blk.shift, &S2, 1., transpose);
      if (o.spatial_preconditioner == "amg")
      {
        blk.amg = std::make_shared<AmgBlock>(*blk.matrix, blk.map.is_null() ? 1 : 2, o);
        blk.matrix = Teuchos::null; // ML works on its Epetra copy
      }
      else
      {
        IterativeOptions io = o;
        io.ilu_fill = std::max(0., std::round(o.ilu_fill));
        blk.prec = make_ifpack2("riluk", blk.matrix, io, 1);
      }
      blocks.push_back(blk);
      j += blk.size;
    }
    for (unsigned int k2 = 0; k2 < m; ++k2)
    {
      y.push_back(rcp(new Vec(space_map)));
      z.push_back(rcp(new Vec(space_map)));
    }
    w1 = rcp(new Vec(space_map));
    w2 = rcp(new Vec(space_map));
    h = rcp(new Vec(space_map));
  }

  RCP<const Map> getDomainMap() const override { return slab_map; }
  RCP<const Map> getRangeMap() const override { return slab_map; }

  void apply(const MV &X, MV &Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1., double beta = 0.) const override
  {
    if (mode != Teuchos::NO_TRANS)
      throw std::logic_error(
          "kronecker preconditioner: transposed apply not implemented");
    const std::size_t n = space_map->getNodeNumElements();
    const SlabLayout slab{m};
    for (std::size_t c = 0; c < X.getNumVectors(); ++c)
    {
      {
        auto x = X.getData(c);
        std::vector<Teuchos::ArrayRCP<double>> g(m);
        for (unsigned int k = 0; k < m; ++k)
          g[k] = y[k]->getDataNonConst();
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int k = 0; k < m; ++k)
          {
            double s = 0;
            for (unsigned int l = 0; l < m; ++l)
              s += P(k, l) * x[slab.index(i, l)];
            g[k][i] = s;
          }
      }
      // y holds the transformed right-hand side; overwritten block by block (last first).
      for (auto b = blocks.rbegin(); b != blocks.rend(); ++b)
      {
        const unsigned int j0 = b->first, j1 = b->first + b->size;
        for (unsigned int j = j0; j < j1; ++j)
          for (unsigned int l = j1; l < m; ++l)
            if (T(j, l) != 0.)
              y[j]->update(-T(j, l), *z[l], 1.);
        if (b->size == 1)
        {
          w1->assign(*y[j0]);
          inner(*b, *w1, *y[j0]);
        }
        else if (!presb)
        {
          {
            auto in = b->in->getDataNonConst();
            auto r1 = y[j0]->getData();
            auto r2 = y[j0 + 1]->getData();
            for (std::size_t i = 0; i < n; ++i)
            {
              in[2 * i] = r1[i];
              in[2 * i + 1] = r2[i];
            }
          }
          inner(*b, *b->in, *b->out);
          auto out = b->out->getData();
          auto y1 = y[j0]->getDataNonConst();
          auto y2 = y[j0 + 1]->getDataNonConst();
          for (std::size_t i = 0; i < n; ++i)
          {
            y1[i] = out[2 * i];
            y2[i] = out[2 * i + 1];
          }
        }
        else
        {
          // [[B, -beta S1], [beta S1, B]] [y1; zz] = [f1; f2], f2 = rho r2, y2 = sigma
          // zz.
          Vec &f1 = *y[j0];
          Vec &r2 = *y[j0 + 1];
          w1->update(1., f1, b->rho, r2, 0.); // f1 + f2
          inner(*b, *w1, *h);                 // h = y1 + zz
          S1_t->apply(*h, *w2);
          w2->update(1., f1, b->beta); // beta S1 h + f1
          inner(*b, *w2, *w1);         // y1 = (B + beta S1)^{-1}(beta S1 h + f1)
          y[j0]->assign(*w1);
          h->update(-1., *w1, 1.); // zz = h - y1
          y[j0 + 1]->update(b->sigma, *h, 0.);
        }
        if (j0 > 0)
          for (unsigned int j = j0; j < j1; ++j)
            S1_t->apply(*y[j], *z[j]);
      }
      auto out = Y.getDataNonConst(c);
      std::vector<Teuchos::ArrayRCP<const double>> yy(m);
      for (unsigned int k = 0; k < m; ++k)
        yy[k] = y[k]->getData();
      for (std::size_t i = 0; i < n; ++i)
        for (unsigned int k = 0; k < m; ++k)
        {
          double s = 0;
          for (unsigned int l = 0; l < m; ++l)
            s += Q(k, l) * yy[l][i];
          out[slab.index(i, k)] =
              (beta == 0. ? 0. : beta * out[slab.index(i, k)]) + alpha * s;
        }
    }
  }

private:
  struct Block
  {
    unsigned int first = 0, size = 1;
    double shift = 0, alpha = 0, beta = 0, sigma = 0, rho = 0;
    RCP<Matrix> matrix;
    RCP<Prec> prec;                 // ilu
    std::shared_ptr<AmgBlock> amg; // amg
    RCP<const Map> map; // 2x2 blocks without PRESB: the 2n map and work vectors
    RCP<Vec> in, out;
  };
  static void inner(const Block &b, const Vec &in, Vec &out)
  {
    if (b.amg)
      b.amg->apply(in, out);
    else
      b.prec->apply(in, out);
  }
  bool presb = false;
  unsigned int m = 1;
  RCP<const Map> slab_map, space_map;
  dealii::FullMatrix<double> T, Q, P;
  RCP<Matrix> S1_t;
  std::vector<Block> blocks;
  std::vector<RCP<Vec>> y, z;
  RCP<Vec> w1, w2, h;
};
/// Matrix-free K = sum_t T_t (x) S_t (or K^T): m spatial products per term.
class KroneckerOperator : public OP
{
public:
  KroneckerOperator(const RCP<const Map> &slab_map, const std::vector<KronTerm> &terms,
                    bool transpose)
      : slab_map(slab_map)
  {
    m = terms.at(0).T.m();
    space_map = rcp(
        new Map(static_cast<Tpetra::global_size_t>(terms[0].S->m()), 0, serial_comm()));
    std::map<const dealii::SparseMatrix<double> *, RCP<Matrix>> converted;
    for (const auto &t : terms)
    {
      Term term;
      term.T.reinit(m, m);
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < m; ++j)
          term.T(i, j) = transpose ? t.T(j, i) : t.T(i, j);
      auto &S = converted[t.S];
      if (S.is_null())
        S = to_tpetra(space_map, *t.S, 1., nullptr, 0., transpose);
      term.S = S;
      this->terms.push_back(term);
    }
    for (unsigned int k = 0; k < m; ++k)
    {
      xs.push_back(rcp(new Vec(space_map)));
      ys.push_back(rcp(new Vec(space_map)));
      sx.push_back(rcp(new Vec(space_map)));
    }
  }

  RCP<const Map> getDomainMap() const override { return slab_map; }
  RCP<const Map> getRangeMap() const override { return slab_map; }

  void apply(const MV &X, MV &Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1., double beta = 0.) const override
  {
    if (mode != Teuchos::NO_TRANS)
      throw std::logic_error("Kronecker operator: transposed apply not implemented");
    const std::size_t n = space_map->getNodeNumElements();
    const SlabLayout slab{m};
    for (std::size_t c = 0; c < X.getNumVectors(); ++c)
    {
      {
        auto x = X.getData(c);
        for (unsigned int k = 0; k < m; ++k)
        {
          auto xk = xs[k]->getDataNonConst();
          for (std::size_t i = 0; i < n; ++i)
            xk[i] = x[slab.index(i, k)];
        }
      }
      for (unsigned int k = 0; k < m; ++k)
        ys[k]->putScalar(0.);
      for (const auto &t : terms)
        for (unsigned int l = 0; l < m; ++l)
        {
          bool used = false;
          for (unsigned int k = 0; k < m; ++k)
            used = used || t.T(k, l) != 0.;
          if (!used)
            continue;
          t.S->apply(*xs[l], *sx[l]);
          for (unsigned int k = 0; k < m; ++k)
            if (t.T(k, l) != 0.)
              ys[k]->update(t.T(k, l), *sx[l], 1.);
        }
      auto y = Y.getDataNonConst(c);
      for (unsigned int k = 0; k < m; ++k)
      {
        auto yk = ys[k]->getData();
        for (std::size_t i = 0; i < n; ++i)
          y[slab.index(i, k)] =
              (beta == 0. ? 0. : beta * y[slab.index(i, k)]) + alpha * yk[i];
      }
    }
  }

private:
  struct Term
  {
    dealii::FullMatrix<double> T;
    RCP<Matrix> S;
  };
  unsigned int m = 1;
  RCP<const Map> slab_map, space_map;
  std::vector<Term> terms;
  std::vector<RCP<Vec>> xs, ys, sx;
};
} // namespace

const char *preconditioner_names()
{
  return "none|ilut|riluk|block_jacobi|block_gauss_seidel|block_ilu|kronecker|kronecker_"
         "presb";
}

const char *spatial_preconditioner_names() { return "ilu|amg"; }

struct IterativeSlabSolver::Impl
{
  IterativeOptions o;
  RCP<const Map> map;
  RCP<Matrix> K; // assembled K (null if matrix-free)
  RCP<OP> op;    // K or the Kronecker operator
  RCP<OP> prec;
  RCP<RowMatrix> block_matrix; // block_ilu: K as BlockCrsMatrix
};

IterativeSlabSolver::IterativeSlabSolver(const IterativeOptions &options) : impl(new Impl)
{
  impl->o = options;
  ensure_kokkos();
}

IterativeSlabSolver::~IterativeSlabSolver() = default;

std::string IterativeSlabSolver::name() const
{
  const auto &o = impl->o;
  std::string n = o.krylov + "+" + o.preconditioner;
  if (o.spatial_preconditioner == "amg" &&
      (o.preconditioner == "kronecker" || o.preconditioner == "kronecker_presb"))
    n += "(amg-" + o.amg_smoother + ")";
  return n;
}

bool IterativeSlabSolver::needs_assembled_matrix(const IterativeOptions &o)
{
  return o.preconditioner != "kronecker" && o.preconditioner != "kronecker_presb" &&
         o.preconditioner != "none";
}

void IterativeSlabSolver::setup(const SlabMatrix &K, bool transpose)
{
  auto &d = *impl;
  d.prec = Teuchos::null;
  d.block_matrix = Teuchos::null;
  d.K = Teuchos::null;
  d.op = Teuchos::null;
  const unsigned int m = K.m;
  const std::size_t N = K.assembled ? K.assembled->m() : K.terms->at(0).S->m() * m;
  d.map = rcp(new Map(static_cast<Tpetra::global_size_t>(N), 0, serial_comm()));
  if (K.assembled)
  {
    d.K = to_tpetra(d.map, *K.assembled, 1., nullptr, 0., transpose);
    d.op = d.K;
  }
  else if (K.terms && !needs_assembled_matrix(d.o))
    d.op = rcp(new KroneckerOperator(d.map, *K.terms, transpose));
  else
    throw std::logic_error("IterativeSlabSolver: preconditioner " + d.o.preconditioner +
                           " needs the assembled slab matrix");
  const std::string &p = d.o.preconditioner;
  const LO n_blocks = static_cast<LO>(N / m);
  if (p == "none")
    return;
  if (p == "kronecker" || p == "kronecker_presb")
  {
    if (!K.split)
      throw std::logic_error("kronecker preconditioner needs the Kronecker split of K");
    d.prec = rcp(new KroneckerPreconditioner(d.map, *K.split, transpose, d.o));
  }
  else if (p == "block_ilu")
  {
    auto B = Tpetra::convertToBlockCrsMatrix(*d.K, static_cast<LO>(m));
    d.block_matrix = B;
    d.prec = make_ifpack2(p, Teuchos::rcp_implicit_cast<const RowMatrix>(d.block_matrix),
                          d.o, n_blocks);
  }
  else
    d.prec = make_ifpack2(p, d.K, d.o, n_blocks);
}

KrylovStats IterativeSlabSolver::solve(const dealii::Vector<double> &b,
                                       dealii::Vector<double> &x) const
{
  const auto &d = *impl;
  KrylovStats stats;
  const double bnorm = b.l2_norm();
  if (x.size() != b.size())
    x.reinit(b.size());
  if (bnorm == 0.)
  {
    x = 0.;
    return stats;
  }
  auto B = rcp(new MV(d.map, 1));
  auto X = rcp(new MV(d.map, 1));
  {
    auto bd = B->getDataNonConst(0);
    auto xd = X->getDataNonConst(0);
    for (std::size_t i = 0; i < b.size(); ++i)
    {
      bd[i] = b[i];
      xd[i] = x[i];
    }
  }
  const bool watch = d.o.stagnation_window > 0 && d.o.stagnation_factor > 1.;
  // Belos prints caught exceptions (our Stagnation among them) at verbosity Errors; they
  // end up in the failure message instead.
  auto belos_out = rcp(new std::ostringstream);
  auto make_solver = [&](int max_iterations)
  {
    auto problem = rcp(new Belos::LinearProblem<double, MV, OP>(d.op, X, B));
    if (!d.prec.is_null())
      problem->setRightPrec(d.prec);
    problem->setProblem();
    auto pl = rcp(new Teuchos::ParameterList);
    pl->set("Convergence Tolerance", d.o.tolerance);
    pl->set("Maximum Iterations", max_iterations);
    pl->set("Verbosity", static_cast<int>(Belos::Errors));
    pl->set("Output Stream", Teuchos::rcp_implicit_cast<std::ostream>(belos_out));
    pl->set("Implicit Residual Scaling", "Norm of RHS");
    RCP<Belos::SolverManager<double, MV, OP>> solver;
    if (d.o.krylov == "gmres" || d.o.krylov == "fgmres")
    {
      pl->set("Num Blocks", static_cast<int>(d.o.restart));
      pl->set("Maximum Restarts", static_cast<int>(d.o.max_iterations / d.o.restart + 1));
      pl->set("Explicit Residual Scaling", "Norm of RHS");
      if (d.o.krylov == "fgmres")
        pl->set("Flexible Gmres", true);
      solver = rcp(new Belos::BlockGmresSolMgr<double, MV, OP>(problem, pl));
      if (watch)
        solver->setDebugStatusTest(
            rcp(new StagnationTest(d.o.stagnation_window, d.o.stagnation_factor)));
    }
    else if (d.o.krylov == "bicgstab")
      solver = rcp(new Belos::BiCGStabSolMgr<double, MV, OP>(problem, pl));
    else
      throw std::invalid_argument("unknown Krylov method '" + d.o.krylov + "'");
    return solver;
  };
  auto true_residual = [&]
  {
    MV R(d.map, 1);
    d.op->apply(*X, R);
    R.update(1., *B, -1.);
    Teuchos::Array<double> rn(1);
    R.norm2(rn());
    return rn[0] / bnorm;
  };
  Belos::ReturnType ret = Belos::Unconverged;
  std::string breakdown, stagnation;
  if (d.o.krylov == "bicgstab" && watch)
  {
    // BiCGStab has no per-iteration hook: chunks of `window` iterations, each a fresh
    // BiCGStab from the current iterate, compared by the true residual. A solve that
    // converges within the first chunk is the unchunked solve.
    double before = true_residual();
    while (stats.iterations < d.o.max_iterations)
    {
      const unsigned int chunk =
          std::min(d.o.stagnation_window, d.o.max_iterations - stats.iterations);
      auto solver = make_solver(static_cast<int>(chunk));
      try
      {
        ret = solver->solve();
      }
      catch (const std::exception &e)
      {
        breakdown = e.what();
      }
      stats.iterations += static_cast<unsigned int>(solver->getNumIters());
      if (ret == Belos::Converged || !breakdown.empty())
        break;
      const double now = true_residual();
      if (!(now * d.o.stagnation_factor < before) && stats.iterations < d.o.max_iterations)
      {
        std::ostringstream m;
        m << "stagnated: the residual fell by " << (now > 0. ? before / now : 0.)
          << " < " << d.o.stagnation_factor << " over the last " << chunk
          << " iterations";
        stagnation = m.str();
        break;
      }
      before = now;
      if (solver->getNumIters() == 0)
        break; // no progress possible
    }
  }
  else
  {
    auto solver = make_solver(static_cast<int>(d.o.max_iterations));
    try
    {
      ret = solver->solve();
      stats.iterations = static_cast<unsigned int>(solver->getNumIters());
    }
    catch (const Stagnation &e)
    {
      std::ostringstream m;
      m << "stagnated: the residual fell by " << e.ratio << " < " << d.o.stagnation_factor
        << " over the last " << d.o.stagnation_window << " iterations";
      stagnation = m.str();
      stats.iterations = e.iterations;
    }
    catch (const std::exception &e)
    {
      breakdown = e.what();
      stats.iterations = static_cast<unsigned int>(solver->getNumIters());
    }
  }
  // True residual of the returned iterate.
  stats.residual = true_residual();
  {
    auto xd = X->getData(0);
    for (std::size_t i = 0; i < x.size(); ++i)
      x[i] = xd[i];
  }
  // The implicit (recurrence) residual may converge while the true one stagnates
  // (loss of accuracy); accept a factor 10 of slack on the true residual.
  const bool ok = breakdown.empty() && stagnation.empty() &&
                  std::isfinite(stats.residual) &&
                  stats.residual <= 10. * d.o.tolerance &&
                  (ret == Belos::Converged || stats.residual <= d.o.tolerance);
  if (!ok)
  {
    std::ostringstream msg;
    msg << "iterative solver " << name() << " did not converge: " << stats.iterations
        << " iterations (max " << d.o.max_iterations << "), relative residual "
        << stats.residual << " > tolerance " << d.o.tolerance;
    if (!stagnation.empty())
      msg << " (" << stagnation << ")";
    if (!breakdown.empty())
      msg << " (breakdown: " << breakdown << ")";
    throw KrylovFailure(msg.str());
  }
  return stats;
}
} // namespace anisodwr
