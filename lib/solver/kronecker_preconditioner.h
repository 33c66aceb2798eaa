#pragma once
// The Kronecker (Schur-form) preconditioners kronecker and kronecker_presb of the slab
// matrix K = T1 (x) S1 + T2 (x) S2 (internal to lib/solver/).
#include "solver/iterative_solver.h"
#include "solver/temporal_schur.h"
#include "solver/tpetra_bridge.h"

#include <functional>
#include <memory>
#include <vector>

namespace anisodwr::tpetra
{
class AmgBlock;

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
/// Each inner solve is one application of an Ifpack2 ILU(k) (solver.ilu_fill) or of an
/// ML V-cycle, or (inner_iterations > 0) a right-preconditioned GMRES on the block: on
/// t S1 + S2, on the 2n x 2n real form, or on the scaled PRESB block with PRESB as its
/// preconditioner, to the relative residual inner_tolerance.
class KroneckerPreconditioner : public OP
{
public:
  KroneckerPreconditioner(const RCP<const Map> &slab_map, const KronSplit &k,
                          bool transpose, const IterativeOptions &o);

  RCP<const Map> getDomainMap() const override { return slab_map; }
  RCP<const Map> getRangeMap() const override { return slab_map; }

  void apply(const MV &X, MV &Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1., double beta = 0.) const override;

  /// Inner GMRES iterations over all applications so far (0 without inner iterations).
  unsigned long inner_iterations() const { return inner_count; }

private:
  using Spatial = std::function<void(const Vec &, Vec &)>;
  /// The PRESB approximation of [[B, -beta S1], [beta S1, B]]^{-1} (B + beta S1 inverted
  /// by `spatial`): [f1; f2] -> [y1; zz]; y1 may alias f1 and zz f2.
  struct Presb
  {
    Spatial spatial;
    RCP<Matrix> S1;
    double beta = 0;
    RCP<Vec> w1, w2, h;
    void operator()(const Vec &f1, const Vec &f2, Vec &y1, Vec &zz) const;
  };

  /// One diagonal block of T: 1x1 (shift t) or 2x2 (alpha +- i beta), with its inner
  /// solver (ILU or AMG) and, for 2x2 blocks without PRESB, the 2n map and vectors.
  struct Block : ModeBlock
  {
    RCP<Matrix> matrix;
    Spatial spatial; // one ILU or AMG application
    /// 2x2 blocks without PRESB, and every 2x2 block with inner iterations: the 2n map
    /// (interleaved, or [y1; zz] for PRESB) and work vectors.
    RCP<const Map> map;
    RCP<Vec> in, out;
    RCP<const OP> op, op_prec; // inner iterations: the block and its preconditioner
    Presb presb;               // 2x2 blocks with PRESB
  };

  /// The diagonal block `mode` of T with its inner solver.
  Block make_block(const ModeBlock &mode, const dealii::SparseMatrix<double> &S1,
                   const dealii::SparseMatrix<double> &S2, bool transpose,
                   const IterativeOptions &o) const;
  /// blk.spatial: one application of an Ifpack2 ILU(k) or an ML V-cycle of blk.matrix.
  static void make_spatial(Block &blk, const IterativeOptions &o);
  /// blk.op, blk.op_prec (and the 2n map for PRESB) for inner iterations.
  void make_inner_operators(Block &blk) const;
  Presb presb_of(const Block &b) const;
  /// y_k = sum_l P(k, l) x_l: the right-hand side in the Schur basis.
  void to_schur_basis(const MV &X, std::size_t column) const;
  /// Block back substitution over the temporal index (last block first), in place in y.
  void back_substitute() const;
  /// y_j for one block from the transformed right-hand side in y_j.
  void solve_block(const Block &b) const;
  /// out = the block's operator (1x1, or its 2n form) inverted: inner GMRES
  /// (inner_iterations > 0) or one application of its spatial preconditioner.
  void solve_on_block(const Block &b, const Vec &in, Vec &out) const;
  /// ab = (a_0, b_0, a_1, b_1, ...) and back.
  static void interleave(const Vec &a, const Vec &b, Vec &ab);
  static void deinterleave(const Vec &ab, Vec &a, Vec &b);
  /// Y = beta Y + alpha (Q (x) I) y.
  void from_schur_basis(MV &Y, std::size_t column, double alpha, double beta) const;

  bool presb = false;
  unsigned int inner_its = 0;
  double inner_tol = 0;
  mutable unsigned long inner_count = 0;
  unsigned int m = 1;
  RCP<const Map> slab_map, space_map;
  /// m, T, Q and P = Q^T T2^{-1} from G = T2^{-1} T1 = Q T Q^T (of the transposed
  /// factors if transposed)
  TemporalSchur schur;
  RCP<Matrix> S1_t;
  std::vector<Block> blocks;
  std::vector<RCP<Vec>> y, z;
  RCP<Vec> w1, w2, h;
};
} // namespace anisodwr::tpetra
