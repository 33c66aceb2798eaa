// The memory estimate of a run / DWR loop (study/memory_estimate.h): exact byte counts
// of the stored slab solutions, ordering properties of the model (more DoFs, slabs,
// temporal degree or stored adjoints -> more memory; UMFPACK > Krylov for the same
// system), and the stop message.
#include "base/errors.h"
#include "study/memory_estimate.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

using namespace anisodwr;

namespace
{
constexpr double MB = 1024. * 1024.;

/// A Q1 primal with n DoFs (9 couplings per row) and its Q2 adjoint (4n DoFs, 16 per row).
MemoryModel loop_model(double n, unsigned int r, unsigned int slabs, bool iterative)
{
  MemoryModel m;
  m.primal = {n, 9 * n, iterative};
  m.adjoint = {4 * n, 64 * n, iterative};
  m.r = r;
  m.n_slabs = slabs;
  m.base_mb = 100;
  return m;
}
} // namespace

TEST(MemoryEstimate, StoredSolutionsAreExact)
{
  // primal and adjoint solutions of all slabs at the end of the marches
  const auto m = loop_model(1e5, 1, 36, false);
  const auto e = estimate_memory(m);
  EXPECT_DOUBLE_EQ(e.stored_solutions_mb, 8. * 2 * (1e5 + 4e5) * 36 / MB);
  EXPECT_LE(e.solutions_mb, e.stored_solutions_mb);
  // the total is the base, a fixed start-up growth and the parts
  const double startup = e.total_mb - m.base_mb - e.solutions_mb - e.matrices_mb - e.solver_mb;
  EXPECT_GE(startup, 0);
  const auto e4 = estimate_memory(loop_model(4e5, 2, 7, true));
  EXPECT_NEAR(e4.total_mb - m.base_mb - e4.solutions_mb - e4.matrices_mb - e4.solver_mb,
              startup, 1e-9);
  // a second stored adjoint (per-goal estimates) adds exactly one set
  auto m2 = m;
  m2.adjoints_stored = 2;
  EXPECT_DOUBLE_EQ(estimate_memory(m2).stored_solutions_mb - e.stored_solutions_mb,
                   8. * 2 * 4e5 * 36 / MB);
  // the dG(r+1) primal's solutions (time_indicator = higher_order)
  auto m4 = m;
  m4.higher_order = true;
  m4.higher_order_slabs = 54; // 36 slabs of dG(2) in dG(1) slab solutions
  EXPECT_DOUBLE_EQ(estimate_memory(m4).stored_solutions_mb - e.stored_solutions_mb,
                   8. * 2 * 1e5 * 54 / MB);
  // the base is added as it is
  auto m3 = m;
  m3.base_mb = 1000;
  EXPECT_NEAR(estimate_memory(m3).total_mb - e.total_mb, 900, 1e-9);
}

TEST(MemoryEstimate, ConcurrentMarchesHoldBothOperators)
{
  // adaptivity.concurrent_marches: phases with the primal's and the adjoint's operator
  // at once, at least the one-after-the-other peak, and no fewer stored solutions
  for (const bool iterative : {false, true})
    for (const bool higher_order : {false, true})
    {
      auto m = loop_model(1e5, 1, 36, iterative);
      m.extra_primal_slabs = 40;
      m.higher_order = higher_order;
      m.higher_order_slabs = higher_order ? 54 : 0;
      const auto sequential = estimate_memory(m);
      m.concurrent = true;
      const auto concurrent = estimate_memory(m);
      EXPECT_DOUBLE_EQ(concurrent.stored_solutions_mb,
                       8. * 2 * (1e5 * (36 + 40 + m.higher_order_slabs) + 4e5 * 36) / MB);
      EXPECT_DOUBLE_EQ(concurrent.stored_solutions_mb, sequential.stored_solutions_mb);
      EXPECT_GT(concurrent.total_mb, sequential.total_mb);
      // the end of the concurrent marches holds both operators and every solution: more
      // than the solutions and the larger operator alone
      EXPECT_GT(concurrent.total_mb, m.base_mb + concurrent.stored_solutions_mb);
    }
}

TEST(MemoryEstimate, DegreeQPrimalOfTheGoalEstimates)
{
  // adaptivity.goal_estimate = enriched: one more operator of the adjoint's size and its
  // N slab solutions, after the adjoints (beside their solutions) or beside them
  // (concurrent); the stored solutions at the end of the marches are unchanged
  for (const bool iterative : {false, true})
  {
    std::map<bool, double> enriched_total;
    for (const bool concurrent : {false, true})
    {
      auto m = loop_model(1e5, 1, 36, iterative);
      m.concurrent = concurrent;
      const auto plain = estimate_memory(m);
      m.enriched = true;
      const auto e = estimate_memory(m);
      const double u_q = 8. * 2 * 4e5 * 36 / MB;
      EXPECT_DOUBLE_EQ(e.stored_solutions_mb, plain.stored_solutions_mb);
      EXPECT_GT(e.total_mb, plain.total_mb);
      // its march's end holds every stored solution and u_q
      EXPECT_GT(e.total_mb, m.base_mb + e.stored_solutions_mb + u_q);
      enriched_total[concurrent] = e.total_mb;
    }
    EXPECT_GT(enriched_total[true], enriched_total[false]);
    // goal_estimate = consistent: u_q's solutions beside the adjoints' operator, no
    // operator of its own: more than without, at most enriched's after the adjoints
    // (whose operator takes the adjoint's place) and less than enriched's beside them
    auto m = loop_model(1e5, 1, 36, iterative);
    const auto plain = estimate_memory(m);
    m.consistent = true;
    const auto c = estimate_memory(m);
    EXPECT_DOUBLE_EQ(c.stored_solutions_mb, plain.stored_solutions_mb);
    EXPECT_GE(c.total_mb, plain.total_mb);
    EXPECT_GT(c.total_mb, m.base_mb + c.stored_solutions_mb + 8. * 2 * 4e5 * 36 / MB);
    EXPECT_LE(c.total_mb, enriched_total[false]);
    EXPECT_LT(c.total_mb, enriched_total[true]);
    // goal_estimate = both: enriched's operator and u_q and consistent's u_q: at least
    // enriched's peak, with or without concurrent marches
    for (const bool concurrent : {false, true})
    {
      m.concurrent = concurrent;
      m.enriched = true;
      EXPECT_GE(estimate_memory(m).total_mb, enriched_total[concurrent]);
    }
  }
}

TEST(MemoryEstimate, PrimalOnlyRun)
{
  MemoryModel m;
  m.primal = {1e4, 9e4, false};
  m.r = 2;
  m.n_slabs = 7;
  const auto e = estimate_memory(m);
  EXPECT_DOUBLE_EQ(e.stored_solutions_mb, 8. * 3 * 1e4 * 7 / MB);
  EXPECT_GT(e.solver_mb, 0);
  // 4 N more primal slab solutions (measure_time_error)
  m.extra_primal_slabs = 28;
  EXPECT_DOUBLE_EQ(estimate_memory(m).stored_solutions_mb, 8. * 3 * 1e4 * 35 / MB);
}

TEST(MemoryEstimate, Monotone)
{
  for (const bool iterative : {false, true})
    for (const unsigned int r : {0u, 1u, 2u})
    {
      double last = 0;
      for (const double n : {1e3, 1e4, 1e5, 1e6})
      {
        const double e = estimate_memory(loop_model(n, r, 10, iterative)).total_mb;
        EXPECT_GT(e, last) << "n " << n << " r " << r << " iterative " << iterative;
        last = e;
        EXPECT_GT(estimate_memory(loop_model(n, r + 1, 10, iterative)).total_mb, e);
        EXPECT_GT(estimate_memory(loop_model(n, r, 20, iterative)).total_mb, e);
        auto t = loop_model(n, r, 10, iterative);
        t.time_dependent = true;
        EXPECT_GT(estimate_memory(t).total_mb, e);
      }
    }
  // with an adjoint more than without
  auto m = loop_model(1e5, 0, 10, false);
  const double with = estimate_memory(m).total_mb;
  m.adjoint = {};
  EXPECT_LT(estimate_memory(m).total_mb, with);
}

TEST(MemoryEstimate, DirectNeedsMoreThanIterative)
{
  for (const unsigned int r : {0u, 1u, 3u})
    for (const double n : {1e4, 1e5, 1e6})
    {
      const auto d = estimate_memory(loop_model(n, r, 10, false));
      const auto i = estimate_memory(loop_model(n, r, 10, true));
      EXPECT_GT(d.solver_mb, i.solver_mb) << "n " << n << " r " << r;
      EXPECT_GT(d.total_mb, i.total_mb) << "n " << n << " r " << r;
    }
}

TEST(MemoryEstimate, StopMessage)
{
  const auto m = loop_model(1e5, 0, 36, false);
  const MemoryLimit limit{10, "adaptivity.max_memory_mb = 10 MB"};
  EXPECT_NO_THROW(check_memory("loop 3", 9.5, limit, m));
  try
  {
    check_memory("loop 3", 1234.4, limit, m);
    FAIL() << "no exception";
  }
  catch (const ResourceLimitError &e)
  {
    const std::string s = e.what();
    EXPECT_EQ(s.find('\n'), std::string::npos) << s;
    for (const char *part : {"loop 3: memory estimate 1234 MB exceeds "
                             "adaptivity.max_memory_mb = 10 MB",
                             "N_space 100000", "adjoint 400000 DoFs", "36 slabs of dG(0)",
                             "UMFPACK", "not started"})
      EXPECT_NE(s.find(part), std::string::npos) << part << " not in: " << s;
  }
  EXPECT_GT(physical_memory_mb(), 1.);
  EXPECT_GT(resident_memory_mb(), 1.);
}
