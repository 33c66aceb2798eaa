#include "study/study.h"

#include "base/errors.h"
#include "base/mpi.h"
#include "adaptivity/refinement.h"
#include "io/table.h"
#include "io/vtu.h"
#include "scene/scene.h"
#include "slab/primal_march.h"
#include "study/error_norms.h"
#include "study/memory_estimate.h"
#include "study/options.h"

#include <deal.II/base/timer.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace anisodwr
{
using namespace dealii;

namespace
{
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct LevelResult
{
  unsigned int level = 0;
  double h = 0, tau = 0;
  types::global_dof_index n_space = 0, n_tot = 0;
  unsigned int n_t = 0;
  ErrorNorms err;
  bool has_exact = false;
  double t_total = 0;
  double memory_estimate_mb = 0;
  SlabTimings slab;
  std::vector<std::string> vtu_files;
};

std::string fmt(double v)
{
  return json_number(v, 10);
}

std::string level_json(const LevelResult &r)
{
  std::ostringstream s;
  s << "{\"level\": " << r.level << ", \"h\": " << fmt(r.h) << ", \"tau\": " << fmt(r.tau)
    << ", \"N_space\": " << r.n_space << ", \"N_t\": " << r.n_t
    << ", \"N_tot\": " << r.n_tot;
  if (r.has_exact)
    s << ", \"err_L2_T\": " << fmt(r.err.L2_T) << ", \"err_nodal\": " << fmt(r.err.nodal)
      << ", \"err_L2L2\": " << fmt(r.err.L2L2);
  s << ", \"memory_estimate_mb\": " << fmt(r.memory_estimate_mb)
    << ", \"wall_time\": {\"total\": " << fmt(r.t_total)
    << ", \"assemble_spatial\": " << fmt(r.slab.assemble_spatial)
    << ", \"assemble_slab\": " << fmt(r.slab.assemble_slab)
    << ", \"factorize\": " << fmt(r.slab.factorize)
    << ", \"solve\": " << fmt(r.slab.solve)
    << "}, \"factorizations\": " << r.slab.n_factorizations << "}";
  return s.str();
}

/// Solves the primal problem on the scene's mesh refined `refinements` times with
/// `n_slabs` equal slabs. Not started (ResourceLimitError) if its memory estimate, with
/// the process's resident memory base_mb before the first level, exceeds `limit`.
LevelResult solve_level(const Parameters &prm, const Scene<2> &scene, unsigned int level,
                        unsigned int refinements, unsigned int n_slabs,
                        bool write_vtu_files, double base_mb, const MemoryLimit &limit)
{
  Timer timer;
  LevelResult res;
  res.level = level;
  Triangulation<2> tria;
  scene.make_coarse_grid(tria);
  tria.refine_global(refinements);
  if (prm.study.mode == StudyMode::single && prm.discretization.wall_layer > 0.)
    std::cout << wall_layer_text(refine_wall_layer(tria, scene, prm.discretization.wall_layer))
              << "\n";
  const auto space_ptr = make_space(prm, scene, tria, prm.discretization.p);
  const Space<2> &space = *space_ptr;
  const MemoryModel model = memory_model(prm, space, nullptr, n_slabs, base_mb);
  res.memory_estimate_mb = estimate_memory(model).total_mb;
  check_memory(prm.study.mode == StudyMode::convergence ? "level " + std::to_string(level)
                                                        : "run",
               res.memory_estimate_mb, limit, model);
  const TemporalBasis basis(prm.discretization.r);
  const TimeMesh mesh = TimeMesh::uniform(scene.end_time, n_slabs);
  SlabOperator<2> op(space, basis, slab_solver_options(prm));
  MarchOptions opt;
  opt.label =
      prm.study.mode == StudyMode::convergence ? "level " + std::to_string(level) : "run";
  opt.progress = prm.output.progress;
  opt.growth_limit = prm.discretization.growth_limit;
  const auto U = march_primal(space, mesh, basis, op, opt);
  res.t_total = timer.wall_time();
  res.slab = op.timings();
  res.h = GridTools::maximal_cell_diameter(tria);
  res.tau = mesh.max_tau();
  res.n_space = space.n_dofs();
  res.n_t = mesh.n_slabs();
  res.n_tot = res.n_space * res.n_t * basis.n_dofs();
  res.has_exact = scene.exact() != nullptr;
  if (res.has_exact)
    res.err = compute_errors(space, mesh, basis, U);
  if (write_vtu_files && prm.output.vtu_every > 0)
  {
    std::vector<std::pair<double, std::string>> records;
    Vector<double> u;
    for (unsigned int n = 0; n < mesh.n_slabs(); ++n)
      if ((n + 1) % prm.output.vtu_every == 0 || n + 1 == mesh.n_slabs())
      {
        combine_blocks(U[n], basis.right_trace(), u);
        records.emplace_back(
            mesh.t[n + 1],
            write_vtu(space, u, mesh.t[n + 1], prm.output.directory, "solution", n + 1));
        res.vtu_files.push_back(records.back().second);
      }
    write_pvd(prm.output.directory, "solution", records);
  }
  return res;
}

double order(double e_coarse, double e_fine, double ratio)
{
  if (!(e_coarse > 0 && e_fine > 0) || ratio <= 1.)
    return nan;
  return std::log(e_coarse / e_fine) / std::log(ratio);
}

std::string summary_text(const Parameters &prm, const std::vector<LevelResult> &levels,
                         const std::string &status, double wall,
                         const std::string &details = "",
                         const std::string &stop_reason = "")
{
  std::ostringstream f;
  f << "{\n  \"status\": \"" << json_escape(status) << "\",\n  \"mpi_ranks\": "
    << mpi_ranks() << ",\n";
  if (!stop_reason.empty())
    f << "  \"stop_reason\": \"" << json_escape(stop_reason) << "\",\n";
  if (!details.empty())
    f << "  \"details\": \"" << json_escape(details) << "\",\n";
  f << "  \"config\": " << prm.to_json(2) << ",\n  \"levels\": [";
  for (std::size_t i = 0; i < levels.size(); ++i)
    f << (i ? ",\n    " : "\n    ") << level_json(levels[i]);
  f << "\n  ],\n  \"wall_time\": " << fmt(wall)
    << ",\n  \"peak_memory_mb\": " << fmt(peak_memory_mb()) << ",\n  "
    << solver_totals_json() << "\n}\n";
  return f.str();
}

void write_summary(const Parameters &prm, const std::vector<LevelResult> &levels,
                   const std::string &status, double wall,
                   const std::string &details = "", const std::string &stop_reason = "")
{
  const std::string path = prm.output.directory + "/summary.json";
  write_file_atomically(path,
                        summary_text(prm, levels, status, wall, details, stop_reason));
  // what a SIGINT/SIGTERM from now on leaves behind
  set_interrupt_summary(path, summary_text(prm, levels, "interrupted", wall));
}
} // namespace

void run_study(const Parameters &prm)
{
  make_directory(prm.output.directory);
  const auto scene = create_scene<2>(prm);
  Timer timer;
  const double base_mb = mpi_max(resident_memory_mb());
  const MemoryLimit limit = memory_limit(prm);
  std::vector<LevelResult> levels;
  write_summary(prm, levels, "running", 0.);
  if (prm.study.mode == StudyMode::convergence && prm.discretization.wall_layer > 0.)
    std::cerr << "anisodwr: warning: discretization.wall_layer is ignored by study.mode = "
                 "convergence (its levels are uniform refinements)\n";
  try
  {
    if (prm.study.mode == StudyMode::single)
    {
      levels.push_back(solve_level(prm, *scene, 0, prm.discretization.initial_refinements,
                                   prm.discretization.n_slabs, true, base_mb, limit));
      const auto &r = levels.back();
      std::cout << "N_space = " << r.n_space << ", N_t = " << r.n_t
                << ", N_tot = " << r.n_tot << ", wall time " << r.t_total << " s\n";
      if (r.has_exact)
        std::cout << "err_L2_T = " << r.err.L2_T << ", err_nodal = " << r.err.nodal
                  << ", err_L2L2 = " << r.err.L2L2 << "\n";
    }
    else
    {
      const bool space = prm.study.refine != StudyRefine::time,
                 time = prm.study.refine != StudyRefine::space;
      CsvTable table(prm.output.directory + "/convergence.csv",
                     {"level", "h", "tau", "N_space", "N_t", "N_tot", "err_L2_T",
                      "err_nodal", "err_L2L2", "order_L2_T", "order_nodal", "order_L2L2",
                      "wall_time"});
      for (unsigned int l = 0; l < prm.study.levels; ++l)
      {
        levels.push_back(solve_level(
            prm, *scene, l, prm.discretization.initial_refinements + (space ? l : 0),
            prm.discretization.n_slabs << (time ? l : 0), false, base_mb, limit));
        write_summary(prm, levels, "running", timer.wall_time());
        const auto &r = levels.back();
        std::array<double, 3> o{{nan, nan, nan}};
        if (l > 0)
        {
          const auto &c = levels[l - 1];
          const double ratio = space ? c.h / r.h : c.tau / r.tau;
          o = {{order(c.err.L2_T, r.err.L2_T, ratio),
                order(c.err.nodal, r.err.nodal, ratio),
                order(c.err.L2L2, r.err.L2L2, ratio)}};
        }
        const double e = r.has_exact ? 1. : nan;
        table.add_row({double(l), r.h, r.tau, double(r.n_space), double(r.n_t),
                       double(r.n_tot), e * r.err.L2_T, e * r.err.nodal, e * r.err.L2L2,
                       o[0], o[1], o[2], r.t_total});
        std::cout << "level " << l << ": N_space = " << r.n_space << ", N_t = " << r.n_t;
        if (r.has_exact) // like the CSV: no error columns without an exact solution
          std::cout << ", err_L2_T = " << r.err.L2_T << ", err_nodal = " << r.err.nodal
                    << ", err_L2L2 = " << r.err.L2L2 << ", orders " << o[0] << " " << o[1]
                    << " " << o[2];
        std::cout << std::endl;
      }
      std::cout << "table: " << table.path() << "\n";
    }
  }
  catch (const ResourceLimitError &e)
  {
    // not started: the finished levels stay, the reason is the message
    write_summary(prm, levels, "stopped", timer.wall_time(), "", e.what());
    throw;
  }
  catch (const std::exception &e)
  {
    write_summary(prm, levels, "failed: " + failure_message(e), timer.wall_time(),
                  failure_details(e));
    throw;
  }
  write_summary(prm, levels, "ok", timer.wall_time());
}
} // namespace anisodwr
