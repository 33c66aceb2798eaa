#include "solver/matrix_market.h"

#include "base/errors.h"
#include "base/mpi.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace anisodwr
{
using namespace dealii;

void write_matrix_market(const SparseMatrix<double> &A, const std::string &path)
{
  on_output_rank(
      [&]()
      {
        std::ofstream f(path);
        f << "%%MatrixMarket matrix coordinate real general\n"
          << "% anisodwr slab matrix K_n (Dirichlet and hanging-node rows condensed); the "
             "adjoint solves with its transpose\n"
          << A.m() << " " << A.n() << " " << A.n_nonzero_elements() << "\n";
        f.precision(17);
        for (types::global_dof_index i = 0; i < A.m(); ++i)
          for (auto e = A.begin(i); e != A.end(i); ++e)
            f << i + 1 << " " << e->column() + 1 << " " << e->value() << "\n";
        f.flush();
        if (!f)
        {
          const int err = errno;
          f.close();
          std::remove(path.c_str()); // absent rather than partial
          throw OutputError(path +
                            ": cannot write the slab matrix: " + std::strerror(err));
        }
      });
}
} // namespace anisodwr
