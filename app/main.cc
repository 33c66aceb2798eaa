// anisodwr command-line program: parse, run, report.
#include "base/errors.h"
#include "config/parameters.h"
#include "io/table.h"
#include "study/dwr.h"
#include "study/study.h"

#include <cstdlib>
#include <iostream>
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
(0: the physical memory), 3 numerical failure or out of memory, 130/143 interrupted
(SIGINT/SIGTERM).
Outputs (in output.directory): summary.json, convergence.csv (study.mode = convergence),
solution.pvd + solution-NNNN.vtu (study.mode = single).
)";
/// The number of processes an MPI launcher started (OpenMPI, PMIx, MPICH/Hydra), and
/// this one's rank; 1 and 0 without a launcher. Read from the launcher's environment, so
/// that a serial run does not pay for MPI_Init.
std::pair<long, long> launcher_ranks()
{
  const char *names[][2] = {{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"},
                            {"PMIX_SIZE", "PMIX_RANK"},
                            {"PMI_SIZE", "PMI_RANK"}};
  for (const auto &n : names)
    if (const char *size = std::getenv(n[0]))
    {
      const char *rank = std::getenv(n[1]);
      return {std::atol(size), rank ? std::atol(rank) : 0};
    }
  return {1, 0};
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
  const std::vector<std::string> args(argv + 1, argv + argc);
  try
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
    if (args.size() < 2)
      throw InputError("run: missing CONFIG.json");
    // Every rank would compute the same and write the same files: refuse, once.
    if (const auto [ranks, rank] = launcher_ranks(); ranks > 1)
    {
      if (rank != 0)
        return exit_input_error;
      throw InputError("started by an MPI launcher with " + std::to_string(ranks) +
                       " processes; anisodwr runs as one process (its slab solvers and "
                       "the estimator use the machine's cores through threads): run it "
                       "without mpirun, or with -np 1");
    }
    std::vector<std::string> overrides;
    std::string output;
    for (std::size_t i = 2; i < args.size(); ++i)
    {
      if ((args[i] == "--set" || args[i] == "--output") && i + 1 >= args.size())
        throw InputError(args[i] + ": missing value");
      if (args[i] == "--set")
        overrides.push_back(args[++i]);
      else if (args[i] == "--output")
        output = args[++i];
      else
        throw InputError("unknown option '" + args[i] + "'; expected --output DIR or --set "
                         "section.key=value");
    }
    if (!output.empty())
      overrides.push_back("output.directory=" + output);
    const Parameters prm = Parameters::read(args[1], overrides);
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
