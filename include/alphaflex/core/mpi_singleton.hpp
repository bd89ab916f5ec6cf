#pragma once
// Start-up of an MPI process (docs/performance.md, "Start-up of a small run" and "Studies on
// several ranks").

namespace alphaflex {

/// Call before MPI_Init (PetscInitialize/SlepcInitialize). A process started without mpirun is
/// an MPI singleton, and Open MPI 4.1 then forks and execs an `orted` daemon for it (so that it
/// could MPI_Comm_spawn, which alphaflex never does): 0.3-0.5 s of wall time of every single-rank
/// run. Sets OMPI_MCA_ess_singleton_isolated=1, which makes the singleton run alone, only when no
/// launcher started this process (mpirun, srun/PMIx set OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK
/// or PMI_SIZE) and the user has not set it (an explicit setting wins). An isolated singleton
/// then also gets OMPI_MCA_orte_create_session_dirs=0 (unless the user set it): all isolated
/// singletons share one session directory, and concurrent runs (a scripted sweep, ctest -j)
/// raced on creating and removing it, one in a few hundred failing in MPI_Init. Other MPI
/// implementations ignore both variables.
void avoid_singleton_daemon();

/// Call before MPI_Init. When every rank of the job is on this node (a singleton, or mpirun's
/// OMPI_COMM_WORLD_LOCAL_SIZE equal to OMPI_COMM_WORLD_SIZE), the ranks talk through shared
/// memory (Open MPI's ob1 with its vader transport) whatever else is installed, but Open MPI 4.1
/// still opens every network layer (MTL) it was built with to choose among them; on Debian those
/// are psm, psm2 and ofi, and libpsm2 and libpsm_infinipath each calibrate a timer when loaded, in
/// a loop of 125 µs sleeps pinned to core 0: 0.2-0.3 s of wall time per process on this machine
/// whether or not the hardware exists. Sets OMPI_MCA_pml=ob1 then, so that no MTL is opened.
/// Nothing is set on several nodes, without Open MPI's variables under a launcher, or when the
/// user chose a PML or MTL (OMPI_MCA_pml or OMPI_MCA_mtl in the environment, which is also where
/// `mpirun --mca pml ...` puts it). Other MPI implementations ignore the variable.
void prefer_shared_memory_on_one_node();

/// Both of the above, before MPI_Init of every alphaflex executable.
void prepare_mpi_start();

}  // namespace alphaflex
