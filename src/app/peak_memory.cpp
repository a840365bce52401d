#include "app/peak_memory.hpp"

#include <sys/resource.h>

namespace granflow {

double peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return double(usage.ru_maxrss) * 1024.0;  // Linux counts ru_maxrss in kilobytes
}

double peak_resident_bytes_summed(MPI_Comm comm) {
  const double mine = peak_resident_bytes();
  double sum = 0.0;
  MPI_Allreduce(&mine, &sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  return sum;
}

}  // namespace granflow
