#pragma once
// A failure that one rank meets alone (a file only rank 0 reads or writes) must stop every rank, or
// the others wait forever in the next collective call.
#include <mpi.h>

#include <string>

namespace granflow {

// Collective. Each rank passes what went wrong on it ("" if nothing); every rank gets back the
// message of the lowest rank that failed, or "" if none did.
inline std::string first_failure(MPI_Comm comm, const std::string& mine) {
  int failed = mine.empty() ? 0 : 1, any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, comm);
  if (!any) return {};
  int rank;
  MPI_Comm_rank(comm, &rank);
  int who = failed ? rank : 1 << 30, first = 0;
  MPI_Allreduce(&who, &first, 1, MPI_INT, MPI_MIN, comm);
  int length = rank == first ? int(mine.size()) : 0;
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  std::string text = rank == first ? mine : std::string(size_t(length), ' ');
  MPI_Bcast(text.data(), length, MPI_CHAR, first, comm);
  return text;
}

}  // namespace granflow
