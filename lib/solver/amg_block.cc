#include "solver/amg_block.h"

#include <deal.II/lac/trilinos_precondition.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
#include <mpi.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace anisodwr::tpetra
{
namespace
{
/// deal.II's PreconditionBase holds an Epetra_MpiComm, and ML asks MPI for its rank:
/// MPI must be initialized before the first AMG. Done on first use (only the amg path
/// needs it) and finalized at exit if we initialized it.
void ensure_mpi()
{
  static const bool done = []
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized)
    {
      MPI_Init(nullptr, nullptr);
      std::atexit(
          []
          {
            int finalized = 0;
            MPI_Finalized(&finalized);
            if (!finalized)
              MPI_Finalize();
          });
    }
    return true;
  }();
  (void)done;
}
} // namespace

AmgBlock::AmgBlock(const Matrix &A, unsigned int block_size, const IterativeOptions &o)
{
  ensure_mpi();
  copy_to_epetra(A);
  build_hierarchy(block_size, o);
}

AmgBlock::~AmgBlock() = default;

void AmgBlock::copy_to_epetra(const Matrix &A)
{
  comm = std::make_unique<Epetra_MpiComm>(MPI_COMM_SELF);
  const int n = static_cast<int>(A.getNodeNumRows());
  map = std::make_unique<Epetra_Map>(n, 0, *comm);
  std::vector<int> lengths(n);
  for (int i = 0; i < n; ++i)
    lengths[i] = static_cast<int>(A.getNumEntriesInLocalRow(i));
  matrix = std::make_unique<Epetra_CrsMatrix>(Copy, *map, lengths.data(), true);
  std::vector<int> cols;
  for (int i = 0; i < n; ++i)
  {
    typename Matrix::local_inds_host_view_type c;
    typename Matrix::values_host_view_type v;
    A.getLocalRowView(i, c, v);
    cols.assign(c.data(), c.data() + c.extent(0));
    matrix->InsertGlobalValues(i, static_cast<int>(cols.size()), v.data(), cols.data());
  }
  matrix->FillComplete();
}

void AmgBlock::build_hierarchy(unsigned int block_size, const IterativeOptions &o)
{
  const int n = static_cast<int>(map->NumMyElements());
  dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
  data.elliptic = false; // ML "NSSA": nonsymmetric smoothed aggregation
  data.higher_order_elements = false;
  data.n_cycles = 1;
  data.w_cycle = false;
  data.aggregation_threshold = 1e-4;
  data.smoother_sweeps = 1;
  data.smoother_overlap = 0;
  data.smoother_type = o.amg_smoother == AmgSmoother::gauss_seidel ? "Gauss-Seidel"
                       : o.amg_smoother == AmgSmoother::chebyshev  ? "Chebyshev"
                                                                   : "ILU";
  data.coarse_type = "Amesos-KLU";
  if (block_size > 1)
  {
    data.constant_modes.assign(block_size, std::vector<bool>(n, false));
    for (int i = 0; i < n; ++i)
      data.constant_modes[i % block_size][i] = true;
  }
  Teuchos::ParameterList pl;
  data.set_parameters(pl, modes, *matrix);
  if (block_size > 1)
    pl.set("PDE equations", static_cast<int>(block_size));
  // Constructed only now: its Epetra_MpiComm needs MPI.
  amg = std::make_unique<dealii::TrilinosWrappers::PreconditionAMG>();
  amg->initialize(*matrix, pl);
}

void AmgBlock::apply(const Vec &in, Vec &out) const
{
  auto x = in.getData();
  auto y = out.getDataNonConst();
  const Epetra_Vector ex(View, *map, const_cast<double *>(x.getRawPtr()));
  Epetra_Vector ey(View, *map, y.getRawPtr());
  const int err = amg->trilinos_operator().ApplyInverse(ex, ey);
  if (err != 0)
    throw std::runtime_error("AMG (ML) application failed, error " + std::to_string(err));
}
} // namespace anisodwr::tpetra
