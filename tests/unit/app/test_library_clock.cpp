// src/app/library_clock.cpp: the executable's clock() is the one the libraries it loads call, and it
// reads elapsed time (glibc's reads CPU time, which does not advance while the process sleeps).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <thread>

namespace {

TEST(LibraryClock, IsTheClockEveryLibraryCalls) {
  // What a shared library's call of clock() is bound to: the first definition in the global scope.
  void* bound = dlsym(RTLD_DEFAULT, "clock");
  EXPECT_EQ(bound, reinterpret_cast<void*>(&clock)) << "the executable does not export its clock()";
  void* libc = dlopen("libc.so.6", RTLD_LAZY | RTLD_NOLOAD);
  ASSERT_NE(libc, nullptr);
  EXPECT_NE(bound, dlsym(libc, "clock")) << "the libraries call glibc's clock()";
  dlclose(libc);
}

TEST(LibraryClock, CountsMicrosecondsOfElapsedTime) {
  const clock_t before = clock();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const clock_t after = clock();
  // The coarse clock ticks every 1-10 ms; a CPU-time clock would have advanced by about nothing.
  EXPECT_GE(after - before, 35000) << "clock() did not advance while the process slept";
  EXPECT_LT(after - before, 5000000);
  EXPECT_GE(clock(), after);
}

}  // namespace
