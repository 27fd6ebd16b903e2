// RankComm over MPI (Open MPI): the process-wide MPI session. Linked only into the
// pinmask executable (target pinmask_mpi); libraries see optimize/search/rank_comm.hpp.
//
// MPI starts only when this process was started by an MPI launcher (mpirun, mpiexec, srun with
// PMI/PMIx: OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK or PMI_SIZE in the environment) and only
// when a command asks for it (search, sweep, decode --batch): a plain `pinmask ...` never pays
// MPI's start-up and runs as rank 0 of 1 (LocalComm semantics, no MPI call at all).
// MPI_Init_thread(FUNNELED) once; MPI_Finalize at process exit (static destruction).
#pragma once

#include <memory>

#include "optimize/search/rank_comm.hpp"

namespace pinmask {

// True when an MPI launcher started this process (see above).
bool launched_by_mpi();

// The world communicator: MPI when launched_by_mpi() (initialised on first call), else a
// LocalComm. The same object for the life of the process.
RankComm& world_comm();

// True when world_comm() runs over MPI (even with one rank).
bool mpi_active();

// Ends every rank of the job with `code` (MPI_Abort) when MPI is active with more than one rank,
// so an error on one rank cannot leave the others waiting in a collective; otherwise returns.
void abort_job_if_distributed(int code);

}  // namespace pinmask
