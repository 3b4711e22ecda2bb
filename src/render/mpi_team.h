#pragma once
// An MPI job as a RenderTeam (issue 27): the ranks of `mpirun -n N snell render ...` render one
// frame. Rank 0 hands out tiles one at a time as ranks ask for them (the caustic's tiles cost
// many times the rest, so fixed blocks would leave ranks idle), decides alone when a time
// budget or Ctrl-C stops the render, and receives the films, reduced exactly. Built only where
// MPI is found (SNELL_HAVE_MPI); elsewhere mpi_team() is always null.
#include "render/render_team.h"

namespace snell {

/// Starts MPI when this process was launched by an MPI launcher (mpirun, srun); a process
/// started alone keeps to a LocalTeam. Call once, at the top of main(). Returns the exit status
/// to end with when MPI could not start (else 0).
int start_mpi_if_launched(int& argc, char**& argv);
/// Ends MPI (once, at the end of main()); nothing when it was not started.
void finish_mpi();
/// The job's team when MPI was started, else null.
RenderTeam* mpi_team();
/// Whether this build can run under MPI.
bool built_with_mpi();

}  // namespace snell
