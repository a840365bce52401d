// The C library's clock(), for the libraries granflow runs: read in user space, not by a system call.
//
// MUMPS orders each new matrix pattern with PORD (Debian's MUMPS has no METIS), and PORD times its
// own phases with clock(), some 17 000 calls per analysis of the Bui et al. collapse at 300 x 100.
// glibc's clock() reads the process's CPU time, which has no user-space (vDSO) path: each call is a
// system call, and together they were three quarters of an analysis: 73 ms an analysis with glibc's
// clock, 19 ms with this one (docs/benchmarks.md). Nothing in granflow reads those timings. This definition, exported by the executable (CMakeLists.txt), takes the place of glibc's
// for every library loaded with it; it counts microseconds of the coarse monotonic clock, which the
// kernel maps into user space, since the first call. It is wall time, not CPU time: the timings the
// libraries keep for themselves include the time a rank waits. Results do not change (one rank:
// the same history to the bit).
#include <time.h>

extern "C" clock_t clock() noexcept {
  static const timespec start = [] {
    timespec t;
    clock_gettime(CLOCK_MONOTONIC_COARSE, &t);
    return t;
  }();
  timespec now;
  clock_gettime(CLOCK_MONOTONIC_COARSE, &now);
  // CLOCKS_PER_SEC is 1 000 000 (POSIX).
  return clock_t(now.tv_sec - start.tv_sec) * 1000000 + clock_t(now.tv_nsec - start.tv_nsec) / 1000;
}
