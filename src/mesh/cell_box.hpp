#pragma once
// The block of cells a rank owns, in global cell indices: [xs, xs+xm) x [ys, ys+ym).
namespace granflow {
struct CellBox {
  int xs = 0, ys = 0, xm = 0, ym = 0;
  int xe() const { return xs + xm; }
  int ye() const { return ys + ym; }
};
}  // namespace granflow
