// One slab-solver benchmark configuration (run each in its own process: peak memory).
//
//   anisodwr_bench_solvers SYSTEM P R EPS REFINEMENTS SOLVER [SLABS]
//     SYSTEM  primal | adjoint (transposed slab systems of the adjoint space)
//     P       spatial degree of that system (primal Q1/Q2, adjoint Q2/Q4)
//     SOLVER  direct | mumps | KRYLOV+PRECONDITIONER[@amg[-gs|-cheb]] (e.g. gmres+kronecker,
//             gmres+kronecker_presb@amg: solver.spatial_preconditioner = amg with the
//             ILU / Gauss-Seidel / Chebyshev smoother)
//     SLABS   slabs marched (tau = 0.05 as in config/moving_hump.json), default 3
//
// Moving hump, uniform mesh (REFINEMENTS global refinements of the unit square), SUPG
// delta0 = 1, solver tolerance 1e-10, restart 30, max 500 iterations. Prints one CSV
// line (header with --header): setup = factorization or preconditioner (incl. the Tpetra
// copy of K), solve = per slab, peak = VmHWM of the process. Env BENCH_ILU_FILL sets
// solver.ilu_fill (default 1). Env BENCH_ANISO = k refines every cell k more times in y
// only (aspect ratio 2^k, column aspect_ratio). Env BENCH_NUMBERING = downstream
// numbers the DoFs along b (solver.dof_numbering; column numbering). Env BENCH_INNER = k
// sets solver.inner_iterations (BENCH_INNER_TOL solver.inner_tolerance); column
// inner_mean = inner GMRES iterations per slab solve.
#include "base/errors.h"
#include "goal/goal.h"
#include "io/table.h"
#include "scene/scene.h"
#include "slab/adjoint_march.h"
#include "slab/primal_march.h"
#include "study/options.h"

#include <deal.II/grid/tria.h>

#include <mpi.h>

#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <unistd.h>

using namespace anisodwr;
using namespace dealii;

namespace
{
const char *header =
    "system,p,r,eps,refinements,N_space,N_slab,solver,preconditioner,status,"
    "setup_s,solve_s_per_slab,iters_mean,iters_max,peak_mb,base_mb,load1,"
    "message,aspect_ratio,numbering,inner_iterations,inner_mean";

double current_rss_mb()
{
  long pages = 0, rss = 0;
  std::FILE *f = std::fopen("/proc/self/statm", "r");
  if (f)
  {
    if (std::fscanf(f, "%ld %ld", &pages, &rss) != 2)
      rss = 0;
    std::fclose(f);
  }
  return rss * double(sysconf(_SC_PAGESIZE)) / (1024. * 1024.);
}

double load1()
{
  double l[3] = {0, 0, 0};
  return getloadavg(l, 3) > 0 ? l[0] : -1;
}
} // namespace

namespace
{
/// The slab solver options of the SOLVER argument (direct | mumps |
/// KRYLOV+PRECONDITIONER[@amg[-gs|-cheb]]) and the BENCH_* environment; krylov and prec
/// get the names for the CSV line ("-" for a direct solver).
SlabSolverOptions solver_options(const std::string &solver, std::string &krylov,
                                 std::string &prec)
{
  SlabSolverOptions o;
  krylov = "-";
  prec = "-";
  if (solver == "direct" || solver == "mumps")
  {
    o.type = SolverType::direct;
    if (solver == "mumps")
      o.direct_solver = DirectEngine::mumps;
    return o;
  }
  const auto plus = solver.find('+');
  krylov = solver.substr(0, plus);
  prec = solver.substr(plus + 1);
  const auto at = prec.find('@');
  if (at != std::string::npos)
  {
    const std::string spatial = prec.substr(at + 1);
    o.iterative.spatial_preconditioner = SpatialPreconditioner::amg;
    o.iterative.amg_smoother = spatial == "amg-gs"     ? AmgSmoother::gauss_seidel
                               : spatial == "amg-cheb" ? AmgSmoother::chebyshev
                                                       : AmgSmoother::ilu;
    prec = prec.substr(0, at);
  }
  o.type = SolverType::iterative;
  o.iterative.krylov = choice_named<Krylov>(krylov);
  o.iterative.preconditioner = choice_named<Preconditioner>(prec);
  o.iterative.tolerance = 1e-10;
  o.iterative.restart = 30;
  o.iterative.max_iterations = 500;
  if (const char *fill = std::getenv("BENCH_ILU_FILL"))
    o.iterative.ilu_fill = std::stod(fill);
  if (const char *inner = std::getenv("BENCH_INNER"))
    o.iterative.inner_iterations = std::stoi(inner);
  if (const char *tol = std::getenv("BENCH_INNER_TOL"))
    o.iterative.inner_tolerance = std::stod(tol);
  return o;
}

/// The scene's coarse mesh refined `refs` times, then every cell cut `aniso` more times
/// in y (BENCH_ANISO).
void make_mesh(const Scene<2> &scene, unsigned int refs, unsigned int aniso,
               Triangulation<2> &tria)
{
  scene.make_coarse_grid(tria);
  tria.refine_global(refs);
  for (unsigned int k = 0; k < aniso; ++k)
  {
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_refine_flag(RefinementCase<2>::cut_y);
    tria.execute_coarsening_and_refinement();
  }
}
/// Marches the primal or the adjoint (its goal vectors from the scene's default goals)
/// over the slabs: "ok", or "failed" with the exception's message (CSV-safe).
std::string march(bool adjoint, const Space<2> &space, const Scene<2> &scene,
                  const TimeMesh &mesh, const TemporalBasis &basis, SlabOperator<2> &op,
                  std::string &message)
{
  try
  {
    MarchOptions mo;
    mo.label = adjoint ? "adjoint" : "primal";
    if (adjoint)
    {
      const GoalVectors j = assemble_goal_vectors(space, scene.default_goals(0.01));
      march_adjoint(space, mesh, basis, op, j, mo);
    }
    else
      march_primal(space, mesh, basis, op, mo);
    return "ok";
  }
  catch (const std::exception &e)
  {
    message = e.what();
    for (auto &c : message)
      if (c == '"' || c == ',' || c == '\n')
        c = ';';
    return "failed";
  }
}
} // namespace

int main(int argc, char **argv)
{
  if (argc == 2 && std::string(argv[1]) == "--header")
  {
    std::cout << header << "\n";
    return 0;
  }
  if (argc < 7)
  {
    std::cerr
        << "usage: anisodwr_bench_solvers SYSTEM P R EPS REFINEMENTS SOLVER [SLABS]\n";
    return 2;
  }
  const std::string system = argv[1], solver = argv[6];
  const unsigned int p = std::stoi(argv[2]), r = std::stoi(argv[3]),
                     refs = std::stoi(argv[5]), slabs = argc > 7 ? std::stoi(argv[7]) : 3;
  const std::string eps = argv[4];
  const bool adjoint = system == "adjoint";

  std::string krylov, prec;
  const SlabSolverOptions o = solver_options(solver, krylov, prec);
  const bool direct = o.type == SolverType::direct;
  // AMG needs MPI (the library initializes it on first use); initialized here, outside
  // the timed setup, since it is a once-per-process cost (about 1 s for a singleton).
  const bool amg = o.iterative.spatial_preconditioner == SpatialPreconditioner::amg;
  if (amg)
  {
    MPI_Init(nullptr, nullptr);
    std::atexit([] { MPI_Finalize(); }); // after the slab operator is gone
  }
  const auto scene = create_scene<2>(
      Parameters::from_overrides({"scene.name=moving_hump", "scene.epsilon=" + eps}));
  const unsigned int aniso =
      std::getenv("BENCH_ANISO") ? std::stoi(std::getenv("BENCH_ANISO")) : 0;
  Triangulation<2> tria;
  make_mesh(*scene, refs, aniso, tria);
  Space<2> space(*scene, tria, p, Stabilization{1.0, SupgLength::volume, 0.});
  const char *numbering_env = std::getenv("BENCH_NUMBERING");
  const std::string numbering = numbering_env ? numbering_env : "native";
  space.set_downstream_numbering(numbering == "downstream");
  space.setup();
  const TemporalBasis basis(r);
  const double tau = 0.05;
  const TimeMesh mesh = TimeMesh::uniform(slabs * tau, slabs);
  SlabOperator<2> op(space, basis, o);
  const double base = current_rss_mb();
  std::string message;
  std::string status = march(adjoint, space, *scene, mesh, basis, op, message);
  const auto &t = op.timings();
  // With the default solver.fallback = direct a failed Krylov solve is redone by UMFPACK:
  // that is not an iterative success.
  if (status == "ok" && t.n_fallbacks > 0)
  {
    status = "fallback";
    message = std::to_string(t.n_fallbacks) + " of " + std::to_string(t.n_solves) +
              " solves fell back to UMFPACK";
  }
  const double setup = direct ? t.factorize : t.precondition;
  const unsigned int solves = std::max(1u, t.n_solves);
  std::cout << system << "," << p << "," << r << "," << eps << "," << refs << ","
            << space.n_dofs() << "," << op.n_slab_dofs() << "," << krylov << ","
            << (direct ? prec : solver.substr(solver.find('+') + 1))
            << "," << status << "," << setup << "," << t.solve / solves << ","
            << (t.n_krylov_solves ? double(t.krylov_iterations) / t.n_krylov_solves : 0.)
            << "," << t.max_krylov_iterations << "," << peak_memory_mb() << "," << base
            << "," << load1() << ",\"" << message << "\"," << (1u << aniso) << ","
            << numbering << "," << o.iterative.inner_iterations << ","
            << (t.n_krylov_solves ? double(t.inner_iterations) / t.n_krylov_solves : 0.)
            << std::endl;
  return 0;
}
