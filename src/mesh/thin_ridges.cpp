#include "mesh/thin_ridges.hpp"

#include <algorithm>
#include <array>

namespace granflow {

std::vector<long> open_thin_ridges(int nx, int ny, int nz, bool periodic_x, std::vector<double>& mask,
                                   const std::function<bool(long)>& may_open) {
  auto index = [&](int i, int j, int k) { return (long(k) * ny + j) * nx + i; };
  auto cell_of = [&](long n) { return cell_of_index(n, nx, ny); };
  auto blocked = [&](long n) { return mask[size_t(n)] > 0.5; };
  auto open = [&](int i, int j, int k) {
    if (periodic_x) i = (i + nx) % nx;
    return i >= 0 && i < nx && k >= 0 && k < nz && !blocked(index(i, j, k));
  };
  auto thin = [&](int i, int j, int k) {
    return (open(i - 1, j, k) && open(i + 1, j, k)) || (open(i, j, k - 1) && open(i, j, k + 1));
  };
  // A pass looks at the cells next to those the last one opened (at first, at all of them): only
  // those can have become thin.
  std::vector<long> candidates, opened;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) candidates.push_back(index(i, j, k));
  while (!candidates.empty()) {
    std::vector<long> now;
    for (const long n : candidates) {
      const auto [i, j, k] = cell_of(n);
      if (blocked(n) && thin(i, j, k) && may_open(n)) now.push_back(n);
    }
    std::sort(now.begin(), now.end());
    now.erase(std::unique(now.begin(), now.end()), now.end());
    for (const long n : now) mask[size_t(n)] = 0.0;  // after the pass: a pass's result does not depend on its order
    candidates.clear();
    for (const long n : now) {
      const auto [i, j, k] = cell_of(n);
      for (const int di : {-1, 1}) {
        const int ni = periodic_x ? (i + di + nx) % nx : i + di;
        if (ni >= 0 && ni < nx) candidates.push_back(index(ni, j, k));
      }
      for (const int dk : {-1, 1})
        if (k + dk >= 0 && k + dk < nz) candidates.push_back(index(i, j, k + dk));
    }
    opened.insert(opened.end(), now.begin(), now.end());
  }
  std::sort(opened.begin(), opened.end());
  return opened;
}

}  // namespace granflow
