#pragma once
// The MPI processes of a run. Under mpirun every rank holds the whole mesh and runs the
// same computation; MUMPS distributes the factors of the slab systems over the ranks
// (lib/solver/mumps_solver.h), the estimator's cells are shared out and summed
// (allreduce_sum), and rank 0 alone writes files and prints. Without a launcher MPI is
// initialized only when MUMPS is first used.
#include <functional>
#include <vector>

namespace anisodwr
{
/// The number of MPI processes of this run and this one's rank (1 and 0 while MPI is
/// not initialized).
unsigned int mpi_ranks();
unsigned int mpi_rank();
/// The number of ranks on this machine (shared memory; 1 while MPI is not initialized).
unsigned int mpi_ranks_on_this_machine();
/// True on the rank that writes output (rank 0).
inline bool writes_output() { return mpi_rank() == 0; }
/// Initializes MPI (MPI_Init; MPI_Finalize at exit) unless it already is.
void ensure_mpi();
/// Runs `write` on the output rank only; every rank then throws what it threw (an
/// OutputError on the other ranks), so that all ranks stop together. Collective.
void on_output_rank(const std::function<void()> &write);
/// The largest x over all ranks (x on one rank). Collective: decisions taken from
/// measured times or memory must be the same on every rank.
double mpi_max(double x);
/// x := the element-wise sum of x over all ranks (nothing on one rank). Collective.
void allreduce_sum(std::vector<double> &x);
} // namespace anisodwr
