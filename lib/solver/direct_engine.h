#pragma once
// The sparse direct solver's choice (solver.direct), without the solvers' types.
#include "base/choice.h"

#include <vector>

namespace anisodwr
{
/// UMFPACK in this process, or MUMPS on the run's MPI ranks (lib/solver/mumps_solver.h).
enum class DirectEngine
{
  umfpack,
  mumps
};
inline const std::vector<Named<DirectEngine>> &names(DirectEngine)
{
  static const std::vector<Named<DirectEngine>> table{{DirectEngine::umfpack, "umfpack"},
                                                      {DirectEngine::mumps, "mumps"}};
  return table;
}
} // namespace anisodwr
