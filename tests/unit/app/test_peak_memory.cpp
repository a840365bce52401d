// src/app/peak_memory.cpp: the peak resident memory grows by what the process touches, and the sum
// over ranks is each rank's peak added up.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstring>
#include <memory>

#include "app/peak_memory.hpp"

namespace {

TEST(PeakMemory, GrowsByTheMemoryTouched) {
  const double before = granflow::peak_resident_bytes();
  EXPECT_GT(before, 1e6) << "a process running the test holds more than a megabyte";
  // 256 MB above anything the tests before held: written, so that it becomes resident.
  const double touched = 256.0 * (1 << 20);
  const double block_bytes = before + touched;  // resident alone, it lifts the peak by at least `touched`
  auto block = std::make_unique<char[]>(size_t(block_bytes));
  std::memset(block.get(), 1, size_t(block_bytes));
  const double after = granflow::peak_resident_bytes();
  EXPECT_GE(after - before, touched) << "peak " << before << " -> " << after << " bytes";
  EXPECT_LT(after - before, block_bytes + 64.0 * (1 << 20));
  EXPECT_EQ(block[size_t(block_bytes) - 1], 1);
}

TEST(PeakMemory, SumsTheRanks) {
  int ranks = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const double mine = granflow::peak_resident_bytes();
  const double sum = granflow::peak_resident_bytes_summed(MPI_COMM_WORLD);
  // Each rank's peak lies between its own at the two readings; on one rank the sum is its peak.
  EXPECT_GE(sum, mine);
  if (ranks == 1) EXPECT_LE(sum, granflow::peak_resident_bytes());
}

}  // namespace
