// A 2D cell array with `g` ghost layers, addressable as double** [j][i] with global indices
// i in [-g, mx+g), j in [-g, my+g) -- the same view PETSc's DMDAVecGetArray gives on a single
// rank, so kernels written for DMDA local arrays run unchanged on it.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace granflow::interface {

class GhostedArray2 {
 public:
  GhostedArray2() = default;
  GhostedArray2(int mx, int my, int g, double value = 0.0)
      : mx_(mx), my_(my), g_(g), stride_(mx + 2 * g),
        data_(static_cast<std::size_t>(mx + 2 * g) * static_cast<std::size_t>(my + 2 * g), value),
        rows_(static_cast<std::size_t>(my + 2 * g)) {
    // Row pointers offset by g so that rows_[k][-g] is the first element of storage row k;
    // every pointer formed stays inside the allocation.
    for (int k = 0; k < my + 2 * g; ++k) rows_[k] = data_.data() + k * stride_ + g;
  }
  // Row pointers refer into data_, so copies would alias; moves keep the heap buffers.
  GhostedArray2(const GhostedArray2&) = delete;
  GhostedArray2& operator=(const GhostedArray2&) = delete;
  GhostedArray2(GhostedArray2&&) noexcept = default;
  GhostedArray2& operator=(GhostedArray2&&) noexcept = default;

  double** rows() { return rows_.data() + g_; }
  const double* const* rows() const { return rows_.data() + g_; }
  double& operator()(int i, int j) { return rows_[j + g_][i]; }
  double operator()(int i, int j) const { return rows_[j + g_][i]; }

  int mx() const { return mx_; }
  int my() const { return my_; }
  int ghosts() const { return g_; }

  friend void swap(GhostedArray2& a, GhostedArray2& b) noexcept {
    std::swap(a.mx_, b.mx_);
    std::swap(a.my_, b.my_);
    std::swap(a.g_, b.g_);
    std::swap(a.stride_, b.stride_);
    a.data_.swap(b.data_);
    a.rows_.swap(b.rows_);
  }

 private:
  int mx_ = 0, my_ = 0, g_ = 0, stride_ = 0;
  std::vector<double> data_;
  std::vector<double*> rows_;
};

}  // namespace granflow::interface
