#pragma once
// The run's peak memory, as the operating system counts it: the largest resident set of each rank's
// process (getrusage's ru_maxrss), summed over the ranks. It covers everything the process holds:
// fields, matrices, the factorisations of the direct solvers and the libraries' own buffers.
#include <mpi.h>

namespace granflow {

// This process's largest resident set so far, in bytes.
double peak_resident_bytes();

// peak_resident_bytes() summed over the ranks of comm. Collective.
double peak_resident_bytes_summed(MPI_Comm comm);

}  // namespace granflow
