// Distributed direct solve of one slab matrix: MUMPS (PETSc) on 1 or more MPI ranks,
// against UMFPACK on one process, on the same matrix (a measurement for distributed
// runs; the solver itself runs as one process).
//
//   mpirun -np N anisodwr_bench_mumps P R EPS REFINEMENTS [mumps|umfpack]
//
// Moving hump, uniform mesh (REFINEMENTS global refinements), Q_P, dG(R), SUPG delta0
// = 1, tau = 0.05: the slab matrix K = sum_t T_t (x) S_t of the unconstrained spatial
// matrices (the Dirichlet rows not eliminated: same size and pattern as the solved
// system up to the boundary rows), built on every rank (the mesh is replicated); each
// rank copies its contiguous block of nodes (rows i (r+1) + k) into a PETSc MPI AIJ
// matrix. MUMPS factorizes once and solves 3 right-hand sides (the factorization is
// reused); `umfpack` (one process) has UMFPACK (deal.II SparseDirectUMFPACK) do the
// same on the same matrix instead. Prints one CSV line (header with --header): wall
// times in s, peak RSS in MB (max over ranks and sum; each run in its own process),
// relative residual of the last solve.
#include "config/parameters.h"
#include "io/table.h"
#include "scene/scene.h"
#include "slab/slab_operator.h"
#include "study/options.h"
#include "time/kronecker.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>

#include <iostream>
#include <string>
#include <vector>

using namespace anisodwr;
using namespace dealii;

namespace
{
const char *header = "ranks,p,r,eps,refinements,N_space,N_slab,solver,build_s,"
                     "factorize_s,solve_s,residual,peak_mb_max,peak_mb_sum";

void for_each_next(std::vector<SparseMatrix<double>::const_iterator> &e)
{
  for (auto &it : e)
    ++it;
}

/// K's rows of the nodes [i0, i1) into the PETSc matrix (locally owned rows).
void copy_rows(const std::vector<KronTerm> &terms, unsigned int m, unsigned int i0,
               unsigned int i1, PETScWrappers::MPI::SparseMatrix &K)
{
  std::vector<types::global_dof_index> cols;
  std::vector<double> vals;
  for (unsigned int i = i0; i < i1; ++i)
    for (unsigned int k = 0; k < m; ++k)
    {
      cols.clear();
      vals.clear();
      // all S_t share one pattern: their row entries are visited in lockstep
      std::vector<SparseMatrix<double>::const_iterator> e;
      for (const auto &t : terms)
        e.push_back(t.S->begin(i));
      for (; e[0] != terms[0].S->end(i); for_each_next(e))
        for (unsigned int l = 0; l < m; ++l)
        {
          double v = 0;
          for (std::size_t q = 0; q < terms.size(); ++q)
            v += terms[q].T(k, l) * e[q]->value();
          cols.push_back(e[0]->column() * m + l);
          vals.push_back(v);
        }
      K.set(i * m + k, cols.size(), cols.data(), vals.data());
    }
}

/// The right-hand side, entry i.
double load(types::global_dof_index i)
{
  return 1. + double(i % 7);
}

/// The owned rows' sparsity of K (nodes [i0, i1)).
DynamicSparsityPattern kron_pattern(const SparseMatrix<double> &S, unsigned int m,
                                    unsigned int i0, unsigned int i1,
                                    const IndexSet &owned)
{
  DynamicSparsityPattern dsp(S.m() * m, S.m() * m, owned);
  for (unsigned int i = i0; i < i1; ++i)
    for (auto e = S.begin(i); e != S.end(i); ++e)
      for (unsigned int k = 0; k < m; ++k)
        for (unsigned int l = 0; l < m; ++l)
          dsp.add(i * m + k, e->column() * m + l);
  return dsp;
}
/// The figures of one configuration's CSV line.
struct Figures
{
  double build = 0, factorize = 0, solve = 0, residual = 0, peak_max = 0, peak_sum = 0;
};

/// UMFPACK on the assembled slab matrix (one process): assembly, factorization with the
/// first solve, the mean of three more solves, the relative residual, the peak.
Figures solve_umfpack(const std::vector<KronTerm> &terms, unsigned int m,
                      types::global_dof_index N)
{
  Figures f;
  Timer t;
  SparsityPattern pattern;
  make_kron_sparsity(terms[0].S->get_sparsity_pattern(), m, pattern);
  SparseMatrix<double> Kd;
  assemble_kron(terms, pattern, Kd);
  Vector<double> bd(N), xd(N), rd(N);
  for (types::global_dof_index i = 0; i < N; ++i)
    bd(i) = load(i);
  f.build = t.wall_time();
  t.restart();
  SparseDirectUMFPACK lu;
  lu.initialize(Kd);
  lu.vmult(xd, bd);
  f.factorize = t.wall_time();
  t.restart();
  for (unsigned int s = 0; s < 3; ++s)
    lu.vmult(xd, bd);
  f.solve = t.wall_time() / 3;
  Kd.vmult(rd, xd);
  rd -= bd;
  f.residual = rd.l2_norm() / bd.l2_norm();
  f.peak_max = f.peak_sum = peak_memory_mb();
  return f;
}

/// MUMPS (PETSc) on the slab matrix distributed by blocks of spatial rows over the ranks
/// of comm: the same figures, the peak as the maximum and the sum over the ranks.
Figures solve_mumps(const std::vector<KronTerm> &terms, unsigned int m, unsigned int n,
                    types::global_dof_index N, MPI_Comm comm)
{
  const unsigned int ranks = Utilities::MPI::n_mpi_processes(comm),
                     rank = Utilities::MPI::this_mpi_process(comm);
  Figures f;
  Timer t;
  const unsigned int i0 = std::size_t(n) * rank / ranks,
                     i1 = std::size_t(n) * (rank + 1) / ranks;
  IndexSet owned(N);
  owned.add_range(types::global_dof_index(i0) * m, types::global_dof_index(i1) * m);
  PETScWrappers::MPI::SparseMatrix K;
  K.reinit(owned, owned, kron_pattern(*terms[0].S, m, i0, i1, owned), comm);
  copy_rows(terms, m, i0, i1, K);
  K.compress(VectorOperation::insert);
  PETScWrappers::MPI::Vector b(owned, comm), x(owned, comm), res(owned, comm);
  for (const auto i : owned)
    b(i) = load(i);
  b.compress(VectorOperation::insert);
  f.build = t.wall_time();

  SolverControl control(1, 0);
  PETScWrappers::SparseDirectMUMPS mumps(control, comm);
  t.restart();
  mumps.solve(K, x, b); // factorization and the first solve
  f.factorize = t.wall_time();
  t.restart();
  for (unsigned int s = 0; s < 3; ++s)
    mumps.solve(K, x, b);
  f.solve = t.wall_time() / 3;
  K.vmult(res, x);
  res -= b;
  f.residual = res.l2_norm() / b.l2_norm();
  const double peak = peak_memory_mb();
  f.peak_max = Utilities::MPI::max(peak, comm);
  f.peak_sum = Utilities::MPI::sum(peak, comm);
  return f;
}
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm = MPI_COMM_WORLD;
  const unsigned int ranks = Utilities::MPI::n_mpi_processes(comm),
                     rank = Utilities::MPI::this_mpi_process(comm);
  if (argc == 2 && std::string(argv[1]) == "--header")
  {
    if (rank == 0)
      std::cout << header << "\n";
    return 0;
  }
  if (argc < 5)
  {
    if (rank == 0)
      std::cerr << "usage: mpirun -np N anisodwr_bench_mumps P R EPS REFINEMENTS "
                   "[mumps|umfpack]\n";
    return 2;
  }
  const unsigned int p = std::stoi(argv[1]), r = std::stoi(argv[2]),
                     refs = std::stoi(argv[4]);
  const std::string eps = argv[3];
  const bool umfpack = argc > 5 && std::string(argv[5]) == "umfpack";
  if (umfpack && ranks > 1)
  {
    if (rank == 0)
      std::cerr << "anisodwr_bench_mumps: umfpack runs on one process\n";
    return 2;
  }
  const auto scene = create_scene<2>(
      Parameters::from_overrides({"scene.name=moving_hump", "scene.epsilon=" + eps}));
  Triangulation<2> tria;
  scene->make_coarse_grid(tria);
  tria.refine_global(refs);
  Space<2> space(*scene, tria, p, Stabilization{1.0, SupgLength::volume, 0.});
  space.setup();
  const TemporalBasis basis(r);
  SlabSolverOptions o; // matrix-free Krylov options: prepare() only assembles the terms
  o.type = SolverType::iterative;
  SlabOperator<2> op(space, basis, o);
  op.prepare(0.1, 0.05);
  const auto &terms = op.full_terms();
  const unsigned int m = basis.n_dofs(), n = space.n_dofs();
  const types::global_dof_index N = types::global_dof_index(n) * m;
  const auto print_row = [&](const std::string &solver, const Figures &f)
  {
    std::cout << ranks << "," << p << "," << r << "," << eps << "," << refs << "," << n
              << "," << N << "," << solver << "," << f.build << "," << f.factorize << ","
              << f.solve << "," << f.residual << "," << f.peak_max << "," << f.peak_sum
              << std::endl;
  };
  if (umfpack)
  {
    print_row("umfpack", solve_umfpack(terms, m, N));
    return 0;
  }
  const Figures f = solve_mumps(terms, m, n, N, comm);
  if (rank == 0)
    print_row("mumps", f);
  return 0;
}
