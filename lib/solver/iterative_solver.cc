// The Belos driver of the slab solvers: Krylov method, stagnation watch and the
// preconditioner choice; GMRES preconditioned by a frozen operator's modes runs on
// deal.II's GMRES instead (no Trilinos); see iterative_solver.h.
#include "solver/iterative_solver.h"

#include "base/errors.h"
#include "solver/ifpack2_factory.h"
#include "solver/kronecker_operator.h"
#include "solver/inner_gmres.h"
#include "solver/kronecker_preconditioner.h"
#include "solver/mode_solver.h"
#include "solver/tpetra_bridge.h"

#include <BelosBiCGStabSolMgr.hpp>
#include <BelosBlockGmresSolMgr.hpp>
#include <BelosLinearProblem.hpp>
#include <BelosStatusTest.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Tpetra_BlockCrsMatrix.hpp>
#include <Tpetra_BlockCrsMatrix_Helpers.hpp>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace anisodwr
{
using namespace tpetra;

namespace
{
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

/// The stagnation rule of both Krylov drivers: the residual norms by iteration, and
/// stagnation where the residual has fallen by less than `factor` over the last `window`
/// iterations.
class ResidualHistory
{
public:
  ResidualHistory(unsigned int window, double factor) : window(window), factor(factor) {}

  /// Records iteration k's residual; the fall over the last window (residual then /
  /// now, 0 for a zero residual now) if that is stagnation, else a negative number.
  double stagnation(std::size_t k, double residual)
  {
    if (history.size() <= k)
      history.resize(k + 1, std::numeric_limits<double>::quiet_NaN());
    history[k] = residual;
    if (k <= window)
      return -1.;
    const double before = history[k - window];
    // A NaN before (iteration not recorded) never triggers.
    if (before > 0. && !(residual * factor < before))
      return residual > 0. ? before / residual : 0.;
    return -1.;
  }
  void clear() { history.clear(); }

private:
  unsigned int window;
  double factor;
  std::vector<double> history;
};

std::string stagnation_text(double ratio, double factor, unsigned int window)
{
  std::ostringstream m;
  m << "stagnated: the residual fell by " << ratio << " < " << factor << " over the last "
    << window << " iterations";
  return m.str();
}

/// Restarts of GMRES from its iterate where the implicit (recurrence) residual met the
/// tolerance and the true one is not accepted: the recurrence lost the last digits to
/// round-off, and a restart starts from the true residual (one or two iterations then
/// reach the accuracy of the coupled direct solve).
constexpr unsigned int accuracy_restarts = 2;

/// Whether a Krylov solve's result is accepted: no breakdown or stagnation, and the true
/// relative residual meets the tolerance, or is within 10x of it where the implicit
/// (recurrence) one met it (round-off: loss of accuracy).
bool accepted(const KrylovStats &stats, double tolerance, bool implicit_met,
              const std::string &stagnation, const std::string &breakdown)
{
  return breakdown.empty() && stagnation.empty() && std::isfinite(stats.residual) &&
         (stats.residual <= tolerance || (implicit_met && stats.residual <= 10. * tolerance));
}

/// The failure of solver `name`: iterations, residual, stagnation or breakdown.
KrylovFailure failure(const std::string &name, const KrylovStats &stats,
                      const IterativeOptions &o, const std::string &stagnation,
                      const std::string &breakdown)
{
  std::ostringstream msg;
  msg << "iterative solver " << name << " did not converge: " << stats.iterations
      << " iterations (max " << o.max_iterations << "), relative residual " << stats.residual
      << " > tolerance " << o.tolerance;
  if (!stagnation.empty())
    msg << " (" << stagnation << ")";
  if (!breakdown.empty())
    msg << " (breakdown: " << breakdown << ")";
  return KrylovFailure(msg.str());
}

/// Stagnation detection for (F)GMRES, added to Belos' status tests as the "debug" test
/// (an OR member that never passes): records the implicit residual norm of each
/// iteration and throws Stagnation when it has fallen by less than `factor` over the
/// last `window` iterations. Belos' own tests and iterates are unaffected otherwise.
class StagnationTest : public Belos::StatusTest<double, MV, OP>
{
public:
  StagnationTest(unsigned int window, double factor)
      : window(window), factor(factor), history(window, factor)
  {
  }

  Belos::StatusType checkStatus(Belos::Iteration<double, MV, OP> *it) override
  {
    const int k = it->getNumIters();
    if (k < 0)
      return Belos::Failed;
    std::vector<double> norms(1, 0.);
    it->getNativeResiduals(&norms);
    last = static_cast<unsigned int>(k);
    const double ratio = history.stagnation(static_cast<std::size_t>(k), norms[0]);
    if (ratio >= 0.)
      throw Stagnation(last, ratio);
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
  ResidualHistory history; // implicit residual norm by iteration
  unsigned int last = 0;
};
/// The stopping rule of the GMRES without Trilinos: deal.II's SolverControl on the
/// implicit residual ||b - K x_k|| (right preconditioning), failing on stagnation by
/// ResidualHistory's rule where solver.stagnation_* ask for it (as the Belos path).
class WatchedControl : public dealii::SolverControl
{
public:
  WatchedControl(const IterativeOptions &o, double bnorm)
      : dealii::SolverControl(o.max_iterations, o.tolerance * bnorm, false, false),
        watch(o.stagnation_window > 0 && o.stagnation_factor > 1.),
        window(o.stagnation_window), factor(o.stagnation_factor), history(window, factor)
  {
  }

  State check(const unsigned int step, const double value) override
  {
    const double ratio = history.stagnation(step, value);
    const State state = dealii::SolverControl::check(step, value);
    if (state == iterate && watch && ratio >= 0.)
    {
      stagnation = stagnation_text(ratio, factor, window);
      return failure;
    }
    return state;
  }

  std::string stagnation;

private:
  bool watch;
  unsigned int window;
  double factor;
  ResidualHistory history;
};
} // namespace

struct IterativeSlabSolver::Impl
{
  IterativeOptions o;
  /// preconditioner = modes with GMRES (runs_without_trilinos): deal.II's GMRES on
  /// deal.II vectors, K from `blocks` (or `assembled`), the preconditioner `modes`;
  /// nothing of Trilinos, so two marches may solve in two threads
  bool native = false;
  bool transpose = false;
  KronBlocks blocks;
  const dealii::SparseMatrix<double> *assembled = nullptr;
  const ModeDirectSolver *modes = nullptr;

  /// dst = K src (K^T with transpose)
  void vmult(dealii::Vector<double> &dst, const dealii::Vector<double> &src) const
  {
    if (assembled)
      transpose ? assembled->Tvmult(dst, src) : assembled->vmult(dst, src);
    else
      transpose ? blocks.Tvmult(dst.data(), src.data()) : blocks.vmult(dst.data(), src.data());
  }
  KrylovStats solve_native(const dealii::Vector<double> &b, dealii::Vector<double> &x,
                           double bnorm, const std::string &name) const;

  RCP<const Map> map;
  RCP<Matrix> K; // assembled K (null if matrix-free)
  RCP<OP> op;    // K or the Kronecker operator
  RCP<OP> prec;
  RCP<KroneckerPreconditioner> kronecker; // prec, if a kronecker* one
  RCP<RowMatrix> block_matrix; // block_ilu: K as BlockCrsMatrix
};

IterativeSlabSolver::IterativeSlabSolver(const IterativeOptions &options) : impl(new Impl)
{
  impl->o = options;
  if (options.inner_iterations > 0 && options.krylov == Krylov::bicgstab)
    throw InputError("solver.inner_iterations = " +
                     std::to_string(options.inner_iterations) +
                     " makes the preconditioner change between applications; it needs "
                     "solver.krylov = gmres or fgmres (run as flexible GMRES), not "
                     "bicgstab");
  if (!runs_without_trilinos(options))
    ensure_kokkos();
}

bool IterativeSlabSolver::runs_without_trilinos(const IterativeOptions &o)
{
  return o.preconditioner == Preconditioner::modes && o.krylov == Krylov::gmres;
}

IterativeSlabSolver::~IterativeSlabSolver() = default;

std::string IterativeSlabSolver::name() const
{
  const auto &o = impl->o;
  std::string n = anisodwr::name(o.krylov) + "+" + anisodwr::name(o.preconditioner);
  if (o.spatial_preconditioner == SpatialPreconditioner::amg && is_kronecker(o.preconditioner))
    n += "(amg-" + anisodwr::name(o.amg_smoother) + ")";
  if (o.inner_iterations > 0 && is_kronecker(o.preconditioner))
    n += "[inner gmres " + std::to_string(o.inner_iterations) + "]";
  return n;
}

bool IterativeSlabSolver::needs_assembled_matrix(const IterativeOptions &o)
{
  return !is_kronecker(o.preconditioner) && o.preconditioner != Preconditioner::none &&
         o.preconditioner != Preconditioner::modes;
}

void IterativeSlabSolver::setup(const SlabMatrix &K, bool transpose)
{
  auto &d = *impl;
  if (runs_without_trilinos(d.o))
  {
    if (!K.modes || !K.modes->factorized())
      throw std::logic_error("preconditioner modes needs the factorized frozen mode solver");
    d.native = true;
    d.transpose = transpose;
    d.modes = K.modes;
    d.assembled = K.assembled;
    if (!K.assembled)
      d.blocks.reinit(*K.terms);
    return;
  }
  d.prec = Teuchos::null;
  d.kronecker = Teuchos::null;
  d.block_matrix = Teuchos::null;
  d.K = Teuchos::null;
  d.op = Teuchos::null;
  const unsigned int m = K.m;
  const std::size_t N = K.assembled ? K.assembled->m() : K.terms->at(0).S->m() * m;
  d.map = serial_map(N);
  if (K.assembled)
  {
    d.K = to_tpetra(d.map, *K.assembled, 1., nullptr, 0., transpose);
    d.op = d.K;
  }
  else if (K.terms && !needs_assembled_matrix(d.o))
    d.op = rcp(new KroneckerOperator(d.map, *K.terms, transpose));
  else
    throw std::logic_error("IterativeSlabSolver: preconditioner " + anisodwr::name(d.o.preconditioner) +
                           " needs the assembled slab matrix");
  const Preconditioner p = d.o.preconditioner;
  const LO n_blocks = static_cast<LO>(N / m);
  if (p == Preconditioner::none)
    return;
  if (p == Preconditioner::modes)
  {
    if (!K.modes || !K.modes->factorized())
      throw std::logic_error("preconditioner modes needs the factorized frozen mode solver");
    auto work = std::make_shared<dealii::Vector<double>>(N);
    d.prec = rcp(new FunctionOperator(
        d.map,
        [modes = K.modes, work, transpose](const tpetra::Vec &in, tpetra::Vec &out)
        {
          auto x = in.getData();
          for (std::size_t i = 0; i < work->size(); ++i)
            (*work)[i] = x[i];
          modes->solve(*work, transpose);
          auto y = out.getDataNonConst();
          for (std::size_t i = 0; i < work->size(); ++i)
            y[i] = (*work)[i];
        }));
    return;
  }
  if (is_kronecker(p))
  {
    if (!K.split)
      throw std::logic_error("kronecker preconditioner needs the Kronecker split of K");
    d.kronecker = rcp(new KroneckerPreconditioner(d.map, *K.split, transpose, d.o));
    d.prec = d.kronecker;
  }
  else if (p == Preconditioner::block_ilu)
  {
    auto B = Tpetra::convertToBlockCrsMatrix(*d.K, static_cast<LO>(m));
    d.block_matrix = B;
    d.prec = make_ifpack2(p, Teuchos::rcp_implicit_cast<const RowMatrix>(d.block_matrix),
                          d.o, n_blocks);
  }
  else
    d.prec = make_ifpack2(p, d.K, d.o, n_blocks);
}

namespace
{
/// One Belos solve of the set-up system: the solver managers, the stopping rules and
/// the true residual of the iterate.
struct BelosRun
{
  BelosRun(const IterativeOptions &o, const RCP<OP> &op, const RCP<OP> &prec,
           const RCP<const Map> &map, double bnorm)
      : o(o), op(op), prec(prec), X(rcp(new MV(map, 1))), B(rcp(new MV(map, 1))),
        bnorm(bnorm)
  {
  }

  const IterativeOptions &o;
  const RCP<OP> &op, &prec;
  RCP<MV> X, B;
  double bnorm;
  /// Belos prints caught exceptions (our Stagnation among them) at verbosity Errors;
  /// they end up in the failure message instead.
  RCP<std::ostringstream> belos_out = rcp(new std::ostringstream);
  bool watch = o.stagnation_window > 0 && o.stagnation_factor > 1.;

  Belos::ReturnType ret = Belos::Unconverged;
  /// GMRES stopped because its implicit residual met the tolerance while the true one
  /// did not (Belos' loss-of-accuracy detection)
  bool lost_accuracy = false;
  std::string breakdown, stagnation;

  RCP<Belos::SolverManager<double, MV, OP>> make_solver(int max_iterations) const
  {
    auto problem = rcp(new Belos::LinearProblem<double, MV, OP>(op, X, B));
    if (!prec.is_null())
      problem->setRightPrec(prec);
    problem->setProblem();
    auto pl = rcp(new Teuchos::ParameterList);
    pl->set("Convergence Tolerance", o.tolerance);
    pl->set("Maximum Iterations", max_iterations);
    pl->set("Verbosity", static_cast<int>(Belos::Errors));
    pl->set("Output Stream", Teuchos::rcp_implicit_cast<std::ostream>(belos_out));
    pl->set("Implicit Residual Scaling", "Norm of RHS");
    RCP<Belos::SolverManager<double, MV, OP>> solver;
    if (o.krylov == Krylov::gmres || o.krylov == Krylov::fgmres)
    {
      pl->set("Num Blocks", static_cast<int>(o.restart));
      pl->set("Maximum Restarts", static_cast<int>(o.max_iterations / o.restart + 1));
      pl->set("Explicit Residual Scaling", "Norm of RHS");
      if (o.krylov == Krylov::fgmres || o.inner_iterations > 0)
        pl->set("Flexible Gmres", true);
      solver = rcp(new Belos::BlockGmresSolMgr<double, MV, OP>(problem, pl));
      if (watch)
        solver->setDebugStatusTest(
            rcp(new StagnationTest(o.stagnation_window, o.stagnation_factor)));
    }
    else
      solver = rcp(new Belos::BiCGStabSolMgr<double, MV, OP>(problem, pl));
    return solver;
  }

  double true_residual() const
  {
    MV R(X->getMap(), 1);
    op->apply(*X, R);
    R.update(1., *B, -1.);
    Teuchos::Array<double> rn(1);
    R.norm2(rn());
    return rn[0] / bnorm;
  }

  /// BiCGStab has no per-iteration hook: chunks of `window` iterations, each a fresh
  /// BiCGStab from the current iterate, compared by the true residual. A solve that
  /// converges within the first chunk is the unchunked solve.
  void solve_in_chunks(KrylovStats &stats)
  {
    double before = true_residual();
    while (stats.iterations < o.max_iterations)
    {
      const unsigned int chunk =
          std::min(o.stagnation_window, o.max_iterations - stats.iterations);
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
      if (!(now * o.stagnation_factor < before) && stats.iterations < o.max_iterations)
      {
        stagnation = stagnation_text(now > 0. ? before / now : 0., o.stagnation_factor, chunk);
        break;
      }
      before = now;
      if (solver->getNumIters() == 0)
        break; // no progress possible
    }
  }

  /// One solve of at most max_iterations (GMRES watched by StagnationTest), restarted
  /// from its iterate (at most accuracy_restarts times) where the implicit residual met
  /// the tolerance and the true one is not accepted.
  void solve_once(KrylovStats &stats)
  {
    for (unsigned int restart = 0;; ++restart)
    {
      solve_for(o.max_iterations - stats.iterations, stats);
      stats.residual = true_residual();
      if (!stagnation.empty() || !breakdown.empty() || restart >= accuracy_restarts ||
          stats.iterations >= o.max_iterations || converged(stats) ||
          !(ret == Belos::Converged || lost_accuracy))
        return;
    }
  }

  /// One Belos solve of at most max_iterations more iterations.
  void solve_for(unsigned int max_iterations, KrylovStats &stats)
  {
    auto solver = make_solver(static_cast<int>(max_iterations));
    try
    {
      ret = solver->solve();
      stats.iterations += static_cast<unsigned int>(solver->getNumIters());
      lost_accuracy = solver->isLOADetected();
    }
    catch (const Stagnation &e)
    {
      stagnation = stagnation_text(e.ratio, o.stagnation_factor, o.stagnation_window);
      stats.iterations += e.iterations;
    }
    catch (const std::exception &e)
    {
      breakdown = e.what();
      stats.iterations += static_cast<unsigned int>(solver->getNumIters());
    }
  }

  /// The implicit (recurrence) residual may converge while the true one stagnates at
  /// round-off (loss of accuracy: Belos then reports Unconverged); either counts as the
  /// implicit residual's convergence for `accepted`.
  bool converged(const KrylovStats &stats) const
  {
    return accepted(stats, o.tolerance, ret == Belos::Converged || lost_accuracy,
                    stagnation, breakdown);
  }
};
} // namespace

KrylovStats IterativeSlabSolver::Impl::solve_native(const dealii::Vector<double> &b,
                                                    dealii::Vector<double> &x, double bnorm,
                                                    const std::string &name) const
{
  struct Operator
  {
    const Impl &d;
    void vmult(dealii::Vector<double> &dst, const dealii::Vector<double> &src) const
    {
      d.vmult(dst, src);
    }
  } op{*this};
  struct ModeSolve
  {
    const Impl &d;
    void vmult(dealii::Vector<double> &dst, const dealii::Vector<double> &src) const
    {
      dst = src;
      d.modes->solve(dst, d.transpose);
    }
  } prec{*this};
  KrylovStats stats;
  for (unsigned int restart = 0;; ++restart)
  {
    IterativeOptions left = o;
    left.max_iterations = o.max_iterations - stats.iterations;
    WatchedControl control(left, bnorm);
    // restart + 2 vectors: deal.II's count of GMRES's temporary vectors
    dealii::SolverGMRES<dealii::Vector<double>> gmres(
        control,
        dealii::SolverGMRES<dealii::Vector<double>>::AdditionalData(o.restart + 2, true));
    bool converged = true;
    std::string breakdown;
    try
    {
      gmres.solve(op, x, b, prec);
    }
    catch (const dealii::SolverControl::NoConvergence &)
    {
      converged = false;
    }
    catch (const std::exception &e)
    {
      converged = false;
      breakdown = e.what();
    }
    stats.iterations += control.last_step();
    dealii::Vector<double> r(b.size());
    vmult(r, x);
    r.sadd(-1., 1., b);
    stats.residual = r.l2_norm() / bnorm;
    if (accepted(stats, o.tolerance, converged, control.stagnation, breakdown))
      return stats;
    if (!(converged && restart < accuracy_restarts && stats.iterations < o.max_iterations))
      throw failure(name, stats, o, control.stagnation, breakdown);
  }
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
  if (d.native)
    return d.solve_native(b, x, bnorm, name());
  BelosRun run(d.o, d.op, d.prec, d.map, bnorm);
  const unsigned long inner_before = d.kronecker.is_null() ? 0 : d.kronecker->inner_iterations();
  {
    auto bd = run.B->getDataNonConst(0);
    auto xd = run.X->getDataNonConst(0);
    for (std::size_t i = 0; i < b.size(); ++i)
    {
      bd[i] = b[i];
      xd[i] = x[i];
    }
  }
  if (d.o.krylov == Krylov::bicgstab && run.watch)
    run.solve_in_chunks(stats);
  else
    run.solve_once(stats);
  // True residual of the returned iterate.
  stats.residual = run.true_residual();
  if (!d.kronecker.is_null())
    stats.inner_iterations = d.kronecker->inner_iterations() - inner_before;
  {
    auto xd = run.X->getData(0);
    for (std::size_t i = 0; i < x.size(); ++i)
      x[i] = xd[i];
  }
  if (!run.converged(stats))
    throw failure(name(), stats, d.o, run.stagnation, run.breakdown);
  return stats;
}
} // namespace anisodwr
