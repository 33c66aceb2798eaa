// anisodwr command-line program: parse, run, report.
#include "base/blas_threads.h"
#include "base/errors.h"
#include "base/mpi.h"
#include "config/parameters.h"
#include "io/table.h"
#include "dwr/dwr.h"
#include "study/study.h"

#include <deal.II/base/multithread_info.h>


#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <streambuf>
#include <thread>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <string>
#include <vector>

namespace
{
const char *usage = R"(anisodwr - space-time cG(p)-dG(r) SUPG solver for convection-diffusion-reaction

Usage:
  anisodwr run CONFIG.json [--output DIR] [--set section.key=value ...]
  anisodwr defaults        print the complete default config (documented JSON; "#key" = doc)
  anisodwr --help

Exit codes: 0 success, 2 bad input (file, JSON, key, value, output directory in use) or
a run / DWR loop not started because its memory estimate exceeds adaptivity.max_memory_mb
(0: the physical memory), 3 numerical failure or out of memory, 4 an output file cannot
be written (disk full, I/O error), 130/143 interrupted (SIGINT/SIGTERM).
Outputs (in output.directory): summary.json, convergence.csv (study.mode = convergence),
solution.pvd + solution-NNNN.vtu (study.mode = single).
)";
/// The number of processes an MPI launcher started (OpenMPI, PMIx, MPICH/Hydra); 1
/// without a launcher. Read from the launcher's environment, so that a serial run does
/// not pay for MPI_Init.
long launcher_ranks()
{
  for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"})
    if (const char *size = std::getenv(name))
      return std::atol(size);
  return 1;
}

/// Under mpirun with more than one process: MPI up, the cores shared out between the
/// ranks of this machine (deal.II's threads in the estimator, OpenBLAS's under the
/// direct solver), and only rank 0 prints.
void start_mpi()
{
  if (launcher_ranks() <= 1)
    return;
  anisodwr::ensure_mpi();
  const unsigned int cores = std::max(1u, std::thread::hardware_concurrency()),
                     per_rank = std::max(1u, cores / anisodwr::mpi_ranks_on_this_machine());
  dealii::MultithreadInfo::set_thread_limit(per_rank);
  // OpenBLAS (if it is the BLAS in use) reads its thread count at load time
  anisodwr::set_blas_threads(int(per_rank));
  if (anisodwr::mpi_rank() != 0)
  {
    struct Discard : std::streambuf
    {
      int overflow(int c) override { return c == EOF ? 0 : c; }
    };
    static Discard discard;
    std::cout.rdbuf(&discard);
    std::cerr.rdbuf(&discard);
  }
}
} // namespace

namespace
{
using namespace anisodwr;

/// The run command: `run CONFIG.json [--output DIR] [--set section.key=value ...]` read
/// into the parameters (InputError naming the option on bad input).
Parameters read_run_command(const std::vector<std::string> &args)
{
  if (args.size() < 2)
    throw InputError("run: missing CONFIG.json");
  std::vector<std::string> overrides;
  std::string output;
  for (std::size_t i = 2; i < args.size(); ++i)
  {
    if ((args[i] == "--set" || args[i] == "--output") && i + 1 >= args.size())
      throw InputError(args[i] + ": missing value");
    if (args[i] == "--set")
      overrides.push_back(args[++i]);
    else if (args[i] == "--output")
    {
      output = args[++i];
      if (output.empty())
        throw InputError("--output: invalid value ''; expected the path of a directory "
                         "(not empty)");
    }
    else
      throw InputError("unknown option '" + args[i] + "'; expected --output DIR or --set "
                       "section.key=value");
  }
  if (!output.empty())
    overrides.push_back("output.directory=" + output);
  Parameters prm = Parameters::read(args[1], overrides);
  // several ranks: MUMPS unless solver.direct was chosen (UMFPACK would factorize the
  // same matrix on every rank)
  if (mpi_ranks() > 1 && prm.source("solver.direct") == "default")
    prm.solver.direct_solver = DirectEngine::mumps;
  return prm;
}

/// The command line's work; its exceptions become exit codes in main.
int run_command(const std::vector<std::string> &args)
{
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help")
  {
    std::cout << usage;
    return args.empty() ? exit_input_error : exit_ok;
  }
  if (args[0] == "defaults")
  {
    Parameters::print_defaults(std::cout);
    return exit_ok;
  }
  if (args[0] != "run")
    throw InputError("unknown command '" + args[0] + "'; expected run, defaults or --help");
  const Parameters prm = read_run_command(args);
  lock_output_directory(prm.output.directory);
  if (prm.study.mode == StudyMode::dwr)
    run_dwr(prm);
  else
    run_study(prm);
  std::cout << "results: " << prm.output.directory << "/ (summary.json";
  std::cout << (prm.study.mode == StudyMode::convergence ? ", convergence.csv"
                : prm.study.mode == StudyMode::dwr ? ", loops.csv, loops.tex, loops.pvd"
                                                   : ", solution.pvd")
            << ")\n";
  return exit_ok;
}
} // namespace

int main(int argc, char **argv)
{
#ifdef __GLIBC__
  // The estimator's inner loop allocates many small aligned deal.II vectors; with
  // glibc's fastbins every aligned allocation triggers malloc_consolidate, which
  // took half of the estimator's time (perf). Without fastbins the estimator runs
  // 1.7x faster (moving_hump_paper loop 10: 6.3 s -> 3.7 s).
  mallopt(M_MXFAST, 0);
#endif
  using namespace anisodwr;
  start_mpi();
  try
  {
    return run_command(std::vector<std::string>(argv + 1, argv + argc));
  }
  catch (const ResourceLimitError &e)
  {
    std::cerr << "anisodwr: stopped: " << e.what() << std::endl;
    return exit_input_error;
  }
  catch (const InputError &e)
  {
    std::cerr << "anisodwr: input error: " << e.what() << std::endl;
    return exit_input_error;
  }
  catch (const OutputError &e)
  {
    std::cerr << "anisodwr: output error: " << e.what() << std::endl;
    return exit_output_error;
  }
  catch (const NumericalError &e)
  {
    std::cerr << "anisodwr: numerical failure: " << e.what() << std::endl;
    return exit_numerical_error;
  }
  catch (const std::bad_alloc &)
  {
    std::cerr << "anisodwr: numerical failure: out of memory (std::bad_alloc); reduce the "
                 "problem size (discretization.initial_refinements, adaptivity.max_dofs, "
                 "adaptivity.max_memory_mb)"
              << std::endl;
    return exit_numerical_error;
  }
  catch (const std::exception &e)
  {
    std::cerr << "anisodwr: internal error: " << e.what() << std::endl;
    return 1;
  }
}
