#pragma once
// The Kronecker (Schur-form) preconditioners kronecker and kronecker_presb of the slab
// matrix K = T1 (x) S1 + T2 (x) S2 (internal to lib/solver/).
#include "solver/iterative_solver.h"
#include "solver/tpetra_bridge.h"

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
/// Each inner solve is one application of an Ifpack2 ILU(k) (solver.ilu_fill).
class KroneckerPreconditioner : public OP
{
public:
  KroneckerPreconditioner(const RCP<const Map> &slab_map, const KronSplit &k,
                          bool transpose, const IterativeOptions &o);

  RCP<const Map> getDomainMap() const override { return slab_map; }
  RCP<const Map> getRangeMap() const override { return slab_map; }

  void apply(const MV &X, MV &Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1., double beta = 0.) const override;

private:
  /// One diagonal block of T: 1x1 (shift t) or 2x2 (alpha +- i beta), with its inner
  /// solver (ILU or AMG) and, for 2x2 blocks without PRESB, the 2n map and vectors.
  struct Block
  {
    unsigned int first = 0, size = 1;
    double shift = 0, alpha = 0, beta = 0, sigma = 0, rho = 0;
    RCP<Matrix> matrix;
    RCP<Prec> prec;                // ilu
    std::shared_ptr<AmgBlock> amg; // amg
    RCP<const Map> map; // 2x2 blocks without PRESB: the 2n map and work vectors
    RCP<Vec> in, out;
  };
  static void inner(const Block &b, const Vec &in, Vec &out);

  /// m, T, Q and P = Q^T T2^{-1} from G = T2^{-1} T1 = Q T Q^T (of the transposed
  /// factors if `transpose`).
  void schur_form(const KronSplit &k, bool transpose);
  /// The diagonal block of T starting at index j with its inner solver.
  Block make_block(unsigned int j, const dealii::SparseMatrix<double> &S1,
                   const dealii::SparseMatrix<double> &S2, bool transpose,
                   const IterativeOptions &o) const;
  /// y_k = sum_l P(k, l) x_l: the right-hand side in the Schur basis.
  void to_schur_basis(const MV &X, std::size_t column) const;
  /// Block back substitution over the temporal index (last block first), in place in y.
  void back_substitute() const;
  /// y_j for one block from the transformed right-hand side in y_j.
  void solve_block(const Block &b) const;
  /// Y = beta Y + alpha (Q (x) I) y.
  void from_schur_basis(MV &Y, std::size_t column, double alpha, double beta) const;

  bool presb = false;
  unsigned int m = 1;
  RCP<const Map> slab_map, space_map;
  dealii::FullMatrix<double> T, Q, P;
  RCP<Matrix> S1_t;
  std::vector<Block> blocks;
  std::vector<RCP<Vec>> y, z;
  RCP<Vec> w1, w2, h;
};
} // namespace anisodwr::tpetra
