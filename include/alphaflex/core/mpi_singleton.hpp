#pragma once
// Start-up of a process that no launcher started (docs/performance.md, start-up).

namespace alphaflex {

/// Call before MPI_Init (PetscInitialize/SlepcInitialize). A process started without mpirun is
/// an MPI singleton, and Open MPI 4.1 then forks and execs an `orted` daemon for it (so that it
/// could MPI_Comm_spawn, which alphaflex never does): 0.3-0.5 s of wall time of every single-rank
/// run. Sets OMPI_MCA_ess_singleton_isolated=1, which makes the singleton run alone, only when no
/// launcher started this process (mpirun, srun/PMIx set OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK
/// or PMI_SIZE) and the user has not set it (an explicit setting wins). Other MPI implementations
/// ignore the variable.
void avoid_singleton_daemon();

}  // namespace alphaflex
