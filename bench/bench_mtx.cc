// One slab matrix from a file, any PETSc solver: the benchmark of the slab solvers on
// the systems a DWR run actually solves (matrices written by output.dump_slab_loop).
//
//   anisodwr_bench_mtx FILE.mtx LABEL [--transpose] [--solves N] [--air R [--air-relax T]]
//                      [--own-umfpack] [PETSc options]
//
// Reads a Matrix Market "coordinate real general" file, optionally transposes it (the
// adjoint solves with K_n^T), sets up the KSP/PC chosen by the PETSc options (e.g.
// -ksp_type gmres -pc_type hypre -pc_hypre_type boomeramg, AIR through
// -pc_hypre_boomeramg_restriction_type 1, ILU(k) through -pc_type ilu
// -pc_factor_levels k, a direct solver through -ksp_type preonly -pc_type lu
// -pc_factor_mat_solver_type umfpack|mumps) once and solves N right-hand sides with it
// (b = K x for N fixed pseudo-random x), as a march reuses one preconditioner or
// factorization over its slabs. Prints one CSV line (the header with LABEL = --header):
// label, unknowns, nonzeros, setup s, solve s per right-hand side, mean iterations,
// KSP converged (1/0), max true relative residual ||b - K x_h|| / ||b||, max relative
// error ||x - x_h|| / ||x||, peak RSS MB (the matrix as read is part of it), and with
// --own-umfpack UMFPACK's own figures (empty otherwise).
//
// `--air R` replaces the PETSc solver by hypre directly: GMRES(30) preconditioned by
// one BoomerAMG V-cycle with approximate ideal restriction (AIR-R, R = 1 or 2), the
// settings PETSc's options cannot reach (one-point interpolation, F-F-C post-relaxation
// only, Jacobi) on Falgout coarsening; same tolerance and output. `--air-relax T` sets
// hypre's relaxation type (0 Jacobi, 3 hybrid Gauss-Seidel).
//
// `--own-umfpack` solves with anisodwr's own UMFPACK wrapper (solver/direct_solver.h,
// no iterative refinement, as the slab solves run) instead of PETSc's, and adds
// UMFPACK's figures: the peak memory its symbolic analysis predicts, the actual peak of
// the numeric factorization and the size of the factors (MB; doc/results.md,
// "UMFPACK's memory and the `auto` rule").
#include "io/table.h"
#include "solver/direct_solver.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <petscksp.h>

#ifdef ANISODWR_HAVE_HYPRE
#  include <HYPRE.h>
#  include <HYPRE_parcsr_ls.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace dealii;

namespace
{
const char *header = "label,unknowns,nonzeros,setup_s,solve_s,iterations,converged,"
                     "residual,error,peak_mb,umf_bound_mb,umf_peak_mb,umf_factors_mb";

void check(PetscErrorCode ierr, const char *what)
{
  if (ierr)
    throw std::runtime_error(std::string("PETSc error in ") + what);
}

struct Triplets
{
  PetscInt n = 0;
  std::vector<PetscInt> row_start, cols;
  std::vector<PetscScalar> vals;
};

/// The matrix of a Matrix Market file in compressed rows (transposed on request).
Triplets read_matrix_market(const std::string &path, bool transpose)
{
  std::ifstream f(path);
  if (!f)
    throw std::runtime_error(path + ": cannot open the matrix file");
  std::string line;
  std::getline(f, line);
  if (line.rfind("%%MatrixMarket matrix coordinate real general", 0) != 0)
    throw std::runtime_error(path + ": expected a Matrix Market 'coordinate real general' "
                                    "header, found '" + line + "'");
  while (std::getline(f, line) && !line.empty() && line[0] == '%')
  {
  }
  long m = 0, n = 0, nnz = 0;
  std::istringstream(line) >> m >> n >> nnz;
  if (m <= 0 || m != n || nnz <= 0)
    throw std::runtime_error(path + ": expected a square matrix, size line '" + line + "'");
  std::vector<PetscInt> I(nnz), J(nnz);
  std::vector<PetscScalar> V(nnz);
  for (long k = 0; k < nnz; ++k)
  {
    long i, j;
    double v;
    if (!(f >> i >> j >> v) || i < 1 || i > m || j < 1 || j > n)
      throw std::runtime_error(path + ": bad entry " + std::to_string(k + 1));
    I[k] = PetscInt(transpose ? j - 1 : i - 1);
    J[k] = PetscInt(transpose ? i - 1 : j - 1);
    V[k] = v;
  }
  Triplets t;
  t.n = PetscInt(m);
  t.row_start.assign(m + 1, 0);
  for (long k = 0; k < nnz; ++k)
    ++t.row_start[I[k] + 1];
  for (long i = 0; i < m; ++i)
    t.row_start[i + 1] += t.row_start[i];
  t.cols.resize(nnz);
  t.vals.resize(nnz);
  std::vector<PetscInt> next(t.row_start.begin(), t.row_start.end() - 1);
  for (long k = 0; k < nnz; ++k)
  {
    t.cols[next[I[k]]] = J[k];
    t.vals[next[I[k]]++] = V[k];
  }
  // PETSc's AIJ format (and UMFPACK behind it) needs ascending columns in every row;
  // deal.II writes the diagonal first
  std::vector<std::pair<PetscInt, PetscScalar>> row;
  for (long i = 0; i < m; ++i)
  {
    row.clear();
    for (PetscInt k = t.row_start[i]; k < t.row_start[i + 1]; ++k)
      row.emplace_back(t.cols[k], t.vals[k]);
    std::sort(row.begin(), row.end());
    for (std::size_t k = 0; k < row.size(); ++k)
      t.cols[t.row_start[i] + k] = row[k].first, t.vals[t.row_start[i] + k] = row[k].second;
  }
  return t;
}

struct SolveFigures
{
  double setup = 0, solve = 0, iterations = 0, residual = 0, error = 0;
  bool converged = true;
  /// --own-umfpack: UMFPACK's predicted peak, actual peak and factor size (MB)
  std::string umfpack_figures = ",,";
};

/// The fixed pseudo-random solution of right-hand side s.
double exact_entry(PetscInt i, int s)
{
  return std::sin(0.7 * double(i) + 1.3 * s) + 0.1 * (s + 1);
}

/// b = K x for the exact solution x of right-hand side s.
std::vector<double> right_hand_side(const Triplets &t, int s)
{
  std::vector<double> b(t.n, 0.);
  for (PetscInt i = 0; i < t.n; ++i)
    for (PetscInt k = t.row_start[i]; k < t.row_start[i + 1]; ++k)
      b[i] += t.vals[k] * exact_entry(t.cols[k], s);
  return b;
}

/// Residual ||b - K x_h|| / ||b|| and error of x_h for right-hand side s (b from
/// right_hand_side), with the matrix in compressed rows.
void add_accuracy(const Triplets &t, int s, const std::vector<double> &b,
                  const std::vector<double> &xh, SolveFigures &f)
{
  double r2 = 0, b2 = 0, e2 = 0, x2 = 0;
  for (PetscInt i = 0; i < t.n; ++i)
  {
    double kx = 0;
    for (PetscInt k = t.row_start[i]; k < t.row_start[i + 1]; ++k)
      kx += t.vals[k] * xh[t.cols[k]];
    const double x = exact_entry(i, s);
    r2 += (b[i] - kx) * (b[i] - kx);
    b2 += b[i] * b[i];
    e2 += (xh[i] - x) * (xh[i] - x);
    x2 += x * x;
  }
  f.residual = std::max(f.residual, std::sqrt(r2 / b2));
  f.error = std::max(f.error, std::sqrt(e2 / x2));
}

#ifdef ANISODWR_HAVE_HYPRE
/// The matrix of t as a hypre IJ matrix (ParCSR object in parA).
HYPRE_IJMatrix hypre_matrix(const Triplets &t, HYPRE_ParCSRMatrix &parA)
{
  const HYPRE_BigInt last = t.n - 1;
  HYPRE_IJMatrix A;
  HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, last, 0, last, &A);
  HYPRE_IJMatrixSetObjectType(A, HYPRE_PARCSR);
  std::vector<HYPRE_Int> sizes(t.n);
  for (PetscInt i = 0; i < t.n; ++i)
    sizes[i] = HYPRE_Int(t.row_start[i + 1] - t.row_start[i]);
  HYPRE_IJMatrixSetRowSizes(A, sizes.data());
  HYPRE_IJMatrixInitialize(A);
  for (PetscInt i = 0; i < t.n; ++i)
  {
    HYPRE_Int nc = sizes[i];
    HYPRE_BigInt row = i;
    std::vector<HYPRE_BigInt> cols(t.cols.begin() + t.row_start[i],
                                   t.cols.begin() + t.row_start[i + 1]);
    HYPRE_IJMatrixSetValues(A, 1, &nc, &row, cols.data(), t.vals.data() + t.row_start[i]);
  }
  HYPRE_IJMatrixAssemble(A);
  HYPRE_IJMatrixGetObject(A, reinterpret_cast<void **>(&parA));
  return A;
}

/// BoomerAMG as AIR: the restriction and relaxation types given, one-point
/// interpolation, no pre-relaxation, post-relaxation F, F, C, one V-cycle.
HYPRE_Solver air_preconditioner(int restriction, int relax)
{
  HYPRE_Solver amg;
  HYPRE_BoomerAMGCreate(&amg);
  HYPRE_BoomerAMGSetRestriction(amg, restriction);
  HYPRE_BoomerAMGSetInterpType(amg, 100); // one-point interpolation
  HYPRE_BoomerAMGSetCoarsenType(amg, 6);
  HYPRE_BoomerAMGSetStrongThreshold(amg, 0.25);
  HYPRE_BoomerAMGSetStrongThresholdR(amg, 0.25);
  HYPRE_BoomerAMGSetFilterThresholdR(amg, 0.);
  HYPRE_BoomerAMGSetRelaxType(amg, relax);
  HYPRE_BoomerAMGSetMaxIter(amg, 1);
  HYPRE_BoomerAMGSetTol(amg, 0.);
  // no pre-relaxation; post-relaxation F, F, C; one sweep on the coarsest level
  // (hypre owns and frees these arrays)
  auto *sweeps = static_cast<HYPRE_Int *>(calloc(4, sizeof(HYPRE_Int)));
  auto **points = static_cast<HYPRE_Int **>(calloc(4, sizeof(HYPRE_Int *)));
  sweeps[0] = 0, sweeps[1] = 0, sweeps[2] = 3, sweeps[3] = 1;
  for (int k = 1; k < 4; ++k)
    points[k] = static_cast<HYPRE_Int *>(calloc(3, sizeof(HYPRE_Int)));
  points[2][0] = -1, points[2][1] = -1, points[2][2] = 1;
  HYPRE_BoomerAMGSetNumGridSweeps(amg, sweeps);
  HYPRE_BoomerAMGSetGridRelaxPoints(amg, points);
  return amg;
}

/// GMRES(30) + BoomerAMG with AIR through hypre's own interface.
SolveFigures solve_with_air(const Triplets &t, int restriction, int relax, int n_solves)
{
  const HYPRE_BigInt last = t.n - 1;
  HYPRE_ParCSRMatrix parA;
  HYPRE_IJMatrix A = hypre_matrix(t, parA);

  auto make_vector = [&](HYPRE_IJVector &v, HYPRE_ParVector &par)
  {
    HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, last, &v);
    HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(v);
    HYPRE_IJVectorAssemble(v);
    HYPRE_IJVectorGetObject(v, reinterpret_cast<void **>(&par));
  };
  HYPRE_IJVector b, x;
  HYPRE_ParVector parb, parx;
  make_vector(b, parb);
  make_vector(x, parx);
  std::vector<HYPRE_BigInt> idx(t.n);
  for (PetscInt i = 0; i < t.n; ++i)
    idx[i] = i;

  HYPRE_Solver gmres, amg = air_preconditioner(restriction, relax);
  HYPRE_ParCSRGMRESCreate(MPI_COMM_SELF, &gmres);
  HYPRE_GMRESSetKDim(gmres, 30);
  HYPRE_GMRESSetMaxIter(gmres, 500);
  HYPRE_GMRESSetTol(gmres, 1e-10);
  HYPRE_GMRESSetPrecond(gmres, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                        reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
  SolveFigures f;
  Timer timer;
  HYPRE_ParCSRGMRESSetup(gmres, parA, parb, parx);
  f.setup = timer.wall_time();
  std::vector<double> xh(t.n, 0.);
  for (int s = 0; s < n_solves; ++s)
  {
    std::vector<double> rhs = right_hand_side(t, s);
    std::fill(xh.begin(), xh.end(), 0.);
    HYPRE_IJVectorSetValues(b, t.n, idx.data(), rhs.data());
    HYPRE_IJVectorSetValues(x, t.n, idx.data(), xh.data());
    timer.restart();
    const HYPRE_Int status = HYPRE_ParCSRGMRESSolve(gmres, parA, parb, parx);
    f.solve += timer.wall_time() / n_solves;
    HYPRE_Int its;
    HYPRE_GMRESGetNumIterations(gmres, &its);
    f.iterations += double(its) / n_solves;
    HYPRE_ClearAllErrors();
    HYPRE_IJVectorGetValues(x, t.n, idx.data(), xh.data());
    add_accuracy(t, s, rhs, xh, f);
    f.converged = f.converged && status == 0 && its < 500 && f.residual <= 1e-8;
  }
  HYPRE_ParCSRGMRESDestroy(gmres);
  HYPRE_BoomerAMGDestroy(amg);
  HYPRE_IJVectorDestroy(b);
  HYPRE_IJVectorDestroy(x);
  HYPRE_IJMatrixDestroy(A);
  return f;
}
#else
SolveFigures solve_with_air(const Triplets &, int, int, int)
{
  throw std::runtime_error("--air: built without hypre (install libhypre-dev)");
}
#endif

/// The KSP/PC of the PETSc options database, set up once, n_solves right-hand sides.
SolveFigures solve_with_petsc(const Triplets &t, int n_solves)
{
  Mat K;
  check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, t.n, t.n,
                                  const_cast<PetscInt *>(t.row_start.data()),
                                  const_cast<PetscInt *>(t.cols.data()),
                                  const_cast<PetscScalar *>(t.vals.data()), &K),
        "MatCreateSeqAIJWithArrays");
  Vec b, xh;
  check(MatCreateVecs(K, &xh, &b), "MatCreateVecs");
  KSP ksp;
  check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  check(KSPSetOperators(ksp, K, K), "KSPSetOperators");
  check(KSPSetTolerances(ksp, 1e-10, 1e-50, 1e10, 500), "KSPSetTolerances");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  SolveFigures f;
  Timer timer;
  check(KSPSetUp(ksp), "KSPSetUp"); // builds the preconditioner / factorization
  f.setup = timer.wall_time();
  std::vector<double> xv(t.n);
  for (int s = 0; s < n_solves; ++s)
  {
    const std::vector<double> rhs = right_hand_side(t, s);
    PetscScalar *p;
    check(VecGetArray(b, &p), "VecGetArray");
    std::copy(rhs.begin(), rhs.end(), p);
    check(VecRestoreArray(b, &p), "VecRestoreArray");
    check(VecSet(xh, 0.), "VecSet");
    timer.restart();
    check(KSPSolve(ksp, b, xh), "KSPSolve");
    f.solve += timer.wall_time() / n_solves;
    PetscInt its;
    KSPConvergedReason reason;
    check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
    check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
    f.iterations += double(its) / n_solves;
    check(VecGetArray(xh, &p), "VecGetArray");
    std::copy(p, p + t.n, xv.begin());
    check(VecRestoreArray(xh, &p), "VecRestoreArray");
    add_accuracy(t, s, rhs, xv, f);
    // converged in the solver's norm and in the true residual
    f.converged = f.converged && reason > 0 && f.residual <= 1e-8;
  }
  KSPDestroy(&ksp);
  VecDestroy(&b);
  VecDestroy(&xh);
  MatDestroy(&K);
  return f;
}

/// anisodwr's UMFPACK wrapper: analysis and factorization once, n_solves solves.
SolveFigures solve_with_own_umfpack(const Triplets &t, int n_solves)
{
  std::vector<unsigned int> lengths(t.n);
  for (PetscInt i = 0; i < t.n; ++i)
    lengths[i] = unsigned(t.row_start[i + 1] - t.row_start[i]);
  SparsityPattern pattern(t.n, t.n, lengths);
  for (PetscInt i = 0; i < t.n; ++i)
    for (PetscInt k = t.row_start[i]; k < t.row_start[i + 1]; ++k)
      pattern.add(i, t.cols[k]);
  pattern.compress();
  SparseMatrix<double> K(pattern);
  for (PetscInt i = 0; i < t.n; ++i)
    for (PetscInt k = t.row_start[i]; k < t.row_start[i + 1]; ++k)
      K.set(i, t.cols[k], t.vals[k]);
  anisodwr::DirectSolver lu(0);
  SolveFigures f;
  Timer timer;
  lu.factorize(K);
  f.setup = timer.wall_time();
  Vector<double> x(t.n);
  std::vector<double> xv(t.n);
  for (int s = 0; s < n_solves; ++s)
  {
    const std::vector<double> rhs = right_hand_side(t, s);
    std::copy(rhs.begin(), rhs.end(), x.begin());
    timer.restart();
    lu.solve(x);
    f.solve += timer.wall_time() / n_solves;
    std::copy(x.begin(), x.end(), xv.begin());
    add_accuracy(t, s, rhs, xv, f);
  }
  f.converged = f.residual <= 1e-8;
  const anisodwr::DirectSolverInfo &info = lu.info();
  std::ostringstream figures;
  figures << info.predicted_peak_mb << "," << info.peak_mb << "," << info.factor_mb;
  f.umfpack_figures = figures.str();
  return f;
}

int run(int argc, char **argv)
{
  if (argc >= 2 && std::strcmp(argv[1], "--header") == 0)
  {
    std::cout << header << "\n";
    return 0;
  }
  if (argc < 3)
  {
    std::cerr << "usage: anisodwr_bench_mtx FILE.mtx LABEL [--transpose] [--solves N] "
                 "[--air R [--air-relax T]] [--own-umfpack] [PETSc options] | --header\n";
    return 2;
  }
  const std::string path = argv[1], label = argv[2];
  bool transpose = false, own_umfpack = false;
  int n_solves = 3, air = 0, air_relax = 0;
  for (int a = 3; a < argc; ++a)
    if (std::strcmp(argv[a], "--transpose") == 0)
      transpose = true;
    else if (std::strcmp(argv[a], "--solves") == 0 && a + 1 < argc)
      n_solves = std::max(1, std::atoi(argv[++a]));
    else if (std::strcmp(argv[a], "--air") == 0 && a + 1 < argc)
      air = std::atoi(argv[++a]);
    else if (std::strcmp(argv[a], "--air-relax") == 0 && a + 1 < argc)
      air_relax = std::atoi(argv[++a]);
    else if (std::strcmp(argv[a], "--own-umfpack") == 0)
      own_umfpack = true;
  const Triplets t = read_matrix_market(path, transpose);
  const SolveFigures f = own_umfpack ? solve_with_own_umfpack(t, n_solves)
                         : air > 0   ? solve_with_air(t, air, air_relax, n_solves)
                                     : solve_with_petsc(t, n_solves);
  std::cout << label << "," << t.n << "," << t.cols.size() << "," << f.setup << ","
            << f.solve << "," << f.iterations << "," << int(f.converged) << ","
            << f.residual << "," << f.error << "," << anisodwr::peak_memory_mb() << ","
            << f.umfpack_figures << std::endl;
  return 0;
}
} // namespace

int main(int argc, char **argv)
{
  // deal.II's MPI_InitFinalize initializes PETSc with argv: the PETSc options of the
  // command line reach KSPSetFromOptions.
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
  {
    return run(argc, argv);
  }
  catch (const std::exception &e)
  {
    std::cerr << "anisodwr_bench_mtx: " << e.what() << "\n";
    return 2;
  }
}
